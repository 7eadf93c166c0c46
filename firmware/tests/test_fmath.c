#include <math.h>

#include "ffr_internal.h"
#include "unit.h"

void suite_fmath(void)
{
    int i;
    double worst_sin = 0.0, worst_atan = 0.0, worst_sqrt = 0.0;
    for (i = -2000; i <= 2000; ++i) {
        float x = (float)i * 0.01f;
        double e = fabs((double)ffr_sinf(x) - sin((double)x));
        if (e > worst_sin) {
            worst_sin = e;
        }
        e = fabs((double)ffr_cosf(x) - cos((double)x));
        if (e > worst_sin) {
            worst_sin = e;
        }
    }
    for (i = 0; i < 360; ++i) {
        float a = (float)i * FFR_DEG - FFR_PI + 0.001f;
        float y = 3.0f * ffr_sinf(a), x = 3.0f * ffr_cosf(a);
        double e = fabs((double)ffr_atan2f(y, x) - atan2((double)y, (double)x));
        if (e > worst_atan) {
            worst_atan = e;
        }
    }
    for (i = 1; i < 5000; ++i) {
        float x = (float)i * 37.1f;
        double e = fabs((double)ffr_sqrtf(x) - sqrt((double)x)) / sqrt((double)x);
        if (e > worst_sqrt) {
            worst_sqrt = e;
        }
    }
    CHECK(worst_sin < 1e-5);
    CHECK(worst_atan < 5e-5);
    CHECK(worst_sqrt < 2e-7);
    CHECK(ffr_atan2f(0.0f, 0.0f) == 0.0f);
    CHECK_NEAR(ffr_atan2f(1.0f, -1.0f), 0.75 * 3.14159265358979, 5e-5);
    CHECK_NEAR(ffr_wrap_pi(3.0f * FFR_PI), FFR_PI, 1e-5);
    CHECK(ffr_sqrtf(-1.0f) == 0.0f);
}
