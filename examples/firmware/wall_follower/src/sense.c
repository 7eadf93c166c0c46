/*
 * sense.c - small float math (no libm: the image links on any board), the
 * sensors in mm and counts, odometry, and the wheel speed control.
 */
#include "wall_follower.h"

float wf_sqrt(float x)
{
    float r;
    int i;
    if (x <= 0.0f) {
        return 0.0f;
    }
    r = x > 1.0f ? x * 0.5f : 1.0f;
    for (i = 0; i < 30; i++) {
        float n = 0.5f * (r + x / r);
        if (n == r) {
            break;
        }
        r = n;
    }
    return r;
}

float wf_wrap(float a)
{
    while (a > WF_PI) {
        a -= 2.0f * WF_PI;
    }
    while (a < -WF_PI) {
        a += 2.0f * WF_PI;
    }
    return a;
}

/* sin on [-pi, pi] by odd Taylor terms after folding to [-pi/2, pi/2]: error < 2e-6. */
float wf_sin(float a)
{
    float x = wf_wrap(a);
    float x2;
    if (x > 0.5f * WF_PI) {
        x = WF_PI - x;
    } else if (x < -0.5f * WF_PI) {
        x = -WF_PI - x;
    }
    x2 = x * x;
    return x * (1.0f - x2 / 6.0f * (1.0f - x2 / 20.0f * (1.0f - x2 / 42.0f * (1.0f - x2 / 72.0f))));
}

float wf_cos(float a)
{
    return wf_sin(a + 0.5f * WF_PI);
}

/* atan on [0, 1]: a minimax-style rational fit, error < 1e-3 rad. */
static float atan01(float z)
{
    return z * (0.7853982f + 0.2447f * (1.0f - z) + 0.0663f * z * (1.0f - z)) ;
}

float wf_atan2(float y, float x)
{
    float ax = x < 0.0f ? -x : x;
    float ay = y < 0.0f ? -y : y;
    float a;
    if (ax == 0.0f && ay == 0.0f) {
        return 0.0f;
    }
    a = ay <= ax ? atan01(ay / ax) : 0.5f * WF_PI - atan01(ax / ay);
    if (x < 0.0f) {
        a = WF_PI - a;
    }
    return y < 0.0f ? -a : a;
}

/* GP2D12: d = k / (mV - offset) - d0, along the beam from the sensor. */
float wf_ir_mm(const struct ffr_config *c, uint16_t mv)
{
    float v = (float)mv - c->ir_offset_mv;
    float d;
    if (v <= 1.0f) {
        return c->ir_max_mm + 1.0f;
    }
    d = c->ir_k_mv_mm / v - c->ir_d0_mm;
    if (d > c->ir_max_mm || d < 0.0f) {
        return c->ir_max_mm + 1.0f;
    }
    return d;
}

/* The hit of ranger i in the body frame, y mirrored for the right side (side < 0). */
static void hit(const struct ffr_config *c, int i, float d, float side, float *hx, float *hy)
{
    float a = c->ir_angle_deg[i] * WF_DEG;
    *hx = c->ir_x_mm[i] + d * wf_cos(a);
    *hy = side * (c->ir_y_mm[i] + d * wf_sin(a));
}

static uint16_t median3(uint16_t a, uint16_t b, uint16_t c)
{
    if (a > b) {
        uint16_t t = a;
        a = b;
        b = t;
    }
    /* a <= b */
    if (c <= a) {
        return a;
    }
    return c < b ? c : b;
}

static uint16_t median_ir(const uint16_t h[WF_IR_WINDOW])
{
    uint16_t v[WF_IR_WINDOW];
    int i, j;
    for (i = 0; i < WF_IR_WINDOW; i++) { /* insertion sort of a copy */
        uint16_t x = h[i];
        for (j = i; j > 0 && v[j - 1] > x; j--) {
            v[j] = v[j - 1];
        }
        v[j] = x;
    }
    return v[WF_IR_WINDOW / 2];
}

void wf_sense(ffr_state_t *st, const ffr_inputs_t *in, wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float fl[2];
    int i;
    int fi = st->side > 0.0f ? FFR_IR_LF : FFR_IR_RF;
    int ri = st->side > 0.0f ? FFR_IR_LR : FFR_IR_RR;
    for (i = 0; i < FFR_IR_COUNT; i++) {
        /* a ranger holds each measurement ~38 ms (4 ticks): the median of the last
         * WF_IR_WINDOW ticks drops a lone spike or dropout, ~45 ms late */
        if (!st->ir_primed) { /* the first tick fills the window */
            int k;
            for (k = 0; k < WF_IR_WINDOW; k++) {
                st->ir_hist[i][k] = in->ir_mv[i];
            }
        }
        st->ir_hist[i][st->ir_pos] = in->ir_mv[i];
        s->ir_mm[i] = wf_ir_mm(c, median_ir(st->ir_hist[i]));
    }
    st->ir_pos = (uint8_t)((st->ir_pos + 1u) % WF_IR_WINDOW);
    st->ir_primed = 1u;
    s->side_front_mm = s->ir_mm[fi];
    s->side_hit_x_mm = 0.0f;
    s->side_hit_y_mm = c->open_mm;
    if (s->ir_mm[fi] < c->open_mm) {
        float hx, hy;
        hit(c, fi, s->ir_mm[fi], st->side, &hx, &hy);
        s->side_hit_x_mm = hx;
        s->side_hit_y_mm = hy;
    }
    s->side_ok = 0u;
    s->side_mm = c->ir_max_mm;
    s->side_deg = 0.0f;
    if (s->ir_mm[fi] < c->open_mm && s->ir_mm[ri] < c->open_mm) {
        float fx, fy, rx, ry, dx, dy, len;
        hit(c, fi, s->ir_mm[fi], st->side, &fx, &fy);
        hit(c, ri, s->ir_mm[ri], st->side, &rx, &ry);
        dx = fx - rx;
        dy = fy - ry;
        len = wf_sqrt(dx * dx + dy * dy);
        if (len > 1.0f) {
            s->side_ok = 1u;
            s->side_mm = (ry * dx - rx * dy) / len;
            s->side_deg = wf_atan2(dy, dx) / WF_DEG;
        }
    }
    /* the flame sensors, read every tick: the median of the last three ticks each */
    for (i = 0; i < 2; i++) {
        uint16_t *h = st->flame_hist[i];
        h[2] = h[1];
        h[1] = h[0];
        h[0] = in->flame[i];
        fl[i] = (float)median3(h[0], h[1], h[2]);
    }
    s->flame_sum = fl[0] + fl[1];
    s->flame_diff = fl[0] - fl[1];
    /* a line is white for WF_LINE_TICKS ticks in a row (a 2.5 cm line is ~10 ticks at
     * cruise speed): a one-tick misread is not a line */
    s->line_edge = 0u;
    if ((in->line != 0u) == (st->line_level != 0u)) {
        st->line_run = 0u;
    } else if (++st->line_run >= WF_LINE_TICKS) {
        st->line_level = in->line ? 1u : 0u;
        st->line_run = 0u;
        s->line_edge = st->line_level;
    }
}

void wf_odometry(ffr_state_t *st, const int32_t enc[2])
{
    const struct ffr_config *c = &st->cfg;
    float mm_per_tick = 2.0f * WF_PI * c->wheel_radius_mm / c->encoder_ticks_per_rev;
    float dl, dr, ds, h;
    if (!st->primed) {
        st->last_enc[0] = enc[0];
        st->last_enc[1] = enc[1];
        st->primed = 1u;
        return;
    }
    dl = (float)(enc[0] - st->last_enc[0]) * mm_per_tick;
    dr = (float)(enc[1] - st->last_enc[1]) * mm_per_tick;
    st->last_enc[0] = enc[0];
    st->last_enc[1] = enc[1];
    ds = 0.5f * (dl + dr);
    h = st->heading_rad + 0.5f * (dr - dl) / c->track_width_mm;
    st->x_mm += ds * wf_cos(h);
    st->y_mm += ds * wf_sin(h);
    st->heading_rad = wf_wrap(st->heading_rad + (dr - dl) / c->track_width_mm);
    st->dist_mm += ds < 0.0f ? -ds : ds;
    /* wheel speeds, mm/s, lightly filtered (the ticks are coarse) */
    st->v_mm_s[0] += 0.3f * (dl * 100.0f - st->v_mm_s[0]);
    st->v_mm_s[1] += 0.3f * (dr * 100.0f - st->v_mm_s[1]);
}

static float clampf(float v, float lo, float hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* Command v (mm/s) and w (rad/s, + = left) to per mille PWM: ramped
 * references, feed-forward and a proportional term on each wheel's speed. */
void wf_drive(ffr_state_t *st, float v_mm_s, float w_rad_s, int16_t pwm[2])
{
    const struct ffr_config *c = &st->cfg;
    float half = 0.5f * c->track_width_mm * w_rad_s;
    float want[2];
    float step = c->accel_mm_s2 * 0.01f;
    int k;
    want[0] = v_mm_s - half;
    want[1] = v_mm_s + half;
    for (k = 0; k < 2; k++) {
        float u;
        st->v_ref[k] += clampf(want[k] - st->v_ref[k], -step, step);
        u = c->pwm_per_mm_s * st->v_ref[k] + c->pwm_kp * (st->v_ref[k] - st->v_mm_s[k]);
        if (st->v_ref[k] > 5.0f) {
            u += c->pwm_offset;
        } else if (st->v_ref[k] < -5.0f) {
            u -= c->pwm_offset;
        }
        pwm[k] = (int16_t)clampf(u, -1000.0f, 1000.0f);
    }
}
