#include <math.h>

#include "ffr_internal.h"
#include "unit.h"

TEST(sin_and_cos_match_libm_within_1e_5)
{
    int i;
    double worst = 0.0;
    for (i = -2000; i <= 2000; ++i) {
        float x = (float)i * 0.01f;
        double e = fabs((double)ffr_sinf(x) - sin((double)x));
        if (e > worst) {
            worst = e;
        }
        e = fabs((double)ffr_cosf(x) - cos((double)x));
        if (e > worst) {
            worst = e;
        }
    }
    CHECK(worst < 1e-5);
}

TEST(atan2_matches_libm_within_5e_5)
{
    int i;
    double worst = 0.0;
    for (i = 0; i < 360; ++i) {
        float a = (float)i * FFR_DEG - FFR_PI + 0.001f;
        float y = 3.0f * ffr_sinf(a), x = 3.0f * ffr_cosf(a);
        double e = fabs((double)ffr_atan2f(y, x) - atan2((double)y, (double)x));
        if (e > worst) {
            worst = e;
        }
    }
    CHECK(worst < 5e-5);
    CHECK(ffr_atan2f(0.0f, 0.0f) == 0.0f);
    CHECK_NEAR(ffr_atan2f(1.0f, -1.0f), 0.75 * 3.14159265358979, 5e-5);
}

TEST(sqrt_matches_libm_within_2e_7_relative)
{
    int i;
    double worst = 0.0;
    for (i = 1; i < 5000; ++i) {
        float x = (float)i * 37.1f;
        double e = fabs((double)ffr_sqrtf(x) - sqrt((double)x)) / sqrt((double)x);
        if (e > worst) {
            worst = e;
        }
    }
    CHECK(worst < 2e-7);
    CHECK(ffr_sqrtf(-1.0f) == 0.0f);
}

TEST(wrap_pi_keeps_pi)
{
    CHECK_NEAR(ffr_wrap_pi(3.0f * FFR_PI), FFR_PI, 1e-5);
}

SUITE(fmath,
      TEST_REF(sin_and_cos_match_libm_within_1e_5),
      TEST_REF(atan2_matches_libm_within_5e_5),
      TEST_REF(sqrt_matches_libm_within_2e_7_relative),
      TEST_REF(wrap_pi_keeps_pi));
