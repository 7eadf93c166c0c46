#include "ffr_internal.h"
#include "unit.h"

void suite_odometry(void)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    int32_t enc[2] = {1000, -5};
    int i;
    float mm_per_tick;
    ffr_config_default(&cfg);
    mm_per_tick = 2.0f * FFR_PI * cfg.wheel_radius_mm / cfg.encoder_ticks_per_rev;

    /* first reading only sets the zero */
    ffr_odometry_reset(&o);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    CHECK_NEAR(o.x_mm, 0.0, 1e-6);
    CHECK_NEAR(o.dist_mm, 0.0, 1e-6);

    /* straight: both wheels 360 ticks = one circumference */
    for (i = 0; i < 36; ++i) {
        enc[0] += 10;
        enc[1] += 10;
        ffr_odometry_update(&o, &cfg, enc, 0.01f);
    }
    CHECK_NEAR(o.x_mm, 360.0f * mm_per_tick, 0.01);
    CHECK_NEAR(o.y_mm, 0.0, 0.01);
    CHECK_NEAR(o.heading_rad, 0.0, 1e-6);
    CHECK_NEAR(o.v_mm_s[0], 10.0f * mm_per_tick / 0.01f, 1.0);

    /* spin in place: a quarter turn is track * pi / 4 per wheel */
    ffr_odometry_reset(&o);
    enc[0] = 0;
    enc[1] = 0;
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    {
        float arc = cfg.track_width_mm * FFR_PI / 4.0f;
        int32_t ticks = (int32_t)(arc / mm_per_tick + 0.5f);
        for (i = 0; i < ticks; ++i) {
            enc[0] -= 1;
            enc[1] += 1;
            ffr_odometry_update(&o, &cfg, enc, 0.01f);
        }
        CHECK_NEAR(o.heading_rad, 0.5 * 3.14159265, 0.01);
        CHECK_NEAR(o.x_mm, 0.0, 1e-3);
    }

    /* counter wrap-around is harmless */
    ffr_odometry_reset(&o);
    enc[0] = 2147483640;
    enc[1] = 2147483640;
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    enc[0] = (int32_t)((uint32_t)enc[0] + 20u);
    enc[1] = (int32_t)((uint32_t)enc[1] + 20u);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    CHECK_NEAR(o.x_mm, 20.0f * mm_per_tick, 0.01);
}
