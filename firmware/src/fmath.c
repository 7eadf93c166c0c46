/*
 * Portable single-precision math. The host (glibc) and the target (newlib)
 * libm give different last bits for sinf/cosf/atan2f, which would break the
 * bit-identical host/target equivalence, so the firmware uses these instead:
 * plain float arithmetic whose result IEEE-754 fixes on every platform
 * (built with -ffp-contract=off so no fused multiply-adds sneak in).
 */
#include "ffr_internal.h"

float ffr_wrap_pi(float a)
{
    const float two_pi = 2.0f * FFR_PI;
    while (a > FFR_PI) {
        a -= two_pi;
    }
    while (a < -FFR_PI) {
        a += two_pi;
    }
    return a;
}

float ffr_sinf(float x)
{
    float x2;
    x = ffr_wrap_pi(x);
    /* fold into [-pi/2, pi/2] where the odd Taylor series converges fast */
    if (x > 0.5f * FFR_PI) {
        x = FFR_PI - x;
    } else if (x < -0.5f * FFR_PI) {
        x = -FFR_PI - x;
    }
    x2 = x * x;
    return x * (1.0f - x2 / 6.0f * (1.0f - x2 / 20.0f * (1.0f - x2 / 42.0f * (1.0f - x2 / 72.0f * (1.0f - x2 / 110.0f)))));
}

float ffr_cosf(float x) { return ffr_sinf(x + 0.5f * FFR_PI); }

/* atan on [0, 1]: minimax polynomial, |error| < 2e-5 rad. */
static float atan_unit(float t)
{
    float t2 = t * t;
    return t * (0.99997726f + t2 * (-0.33262347f + t2 * (0.19354346f + t2 * (-0.11643287f + t2 * (0.05265332f + t2 * -0.01172120f)))));
}

float ffr_atan2f(float y, float x)
{
    float ax = ffr_absf(x);
    float ay = ffr_absf(y);
    float a;
    if (ax == 0.0f && ay == 0.0f) {
        return 0.0f;
    }
    if (ay <= ax) {
        a = atan_unit(ay / ax);
    } else {
        a = 0.5f * FFR_PI - atan_unit(ax / ay);
    }
    if (x < 0.0f) {
        a = FFR_PI - a;
    }
    return y < 0.0f ? -a : a;
}

/* Newton iterations from a bit-level first guess: exact enough (< 1 ulp
 * after three steps) and the same everywhere, unlike a libm call. */
float ffr_sqrtf(float x)
{
    union {
        float f;
        uint32_t u;
    } g;
    float r;
    if (x <= 0.0f) {
        return 0.0f;
    }
    g.f = x;
    g.u = (g.u >> 1) + 0x1FC00000u;
    r = g.f;
    r = 0.5f * (r + x / r);
    r = 0.5f * (r + x / r);
    r = 0.5f * (r + x / r);
    return r;
}

/* A stretch (dx, dy) of length len weighted into the sums of cos and sin of
 * 4 x its direction (walls meeting at right angles agree modulo 90 degrees):
 * the unit vector squared twice as a complex number, no trigonometry (a
 * tick's budget on a soft-float core). */
void ffr_add_dir4(float dx, float dy, float len, float *c4, float *s4)
{
    float u = dx / len, v = dy / len;
    float c2 = u * u - v * v, s2 = 2.0f * u * v;
    *c4 += len * (c2 * c2 - s2 * s2);
    *s4 += len * (2.0f * c2 * s2);
}
