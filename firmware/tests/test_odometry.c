#include "ffr_internal.h"
#include "unit.h"

/* distance per encoder tick of the default wheel */
static float mm_per_tick(const ffr_config_t *cfg)
{
    return 2.0f * FFR_PI * cfg->wheel_radius_mm / cfg->encoder_ticks_per_rev;
}

TEST(the_first_reading_only_sets_the_zero)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    int32_t enc[2] = {1000, -5};
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    CHECK_NEAR(o.x_mm, 0.0, 1e-6);
    CHECK_NEAR(o.dist_mm, 0.0, 1e-6);
}

TEST(straight_one_circumference_per_revolution)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    int32_t enc[2] = {1000, -5};
    int i;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    /* both wheels 360 ticks = one circumference */
    for (i = 0; i < 36; ++i) {
        enc[0] += 10;
        enc[1] += 10;
        ffr_odometry_update(&o, &cfg, enc, 0.01f);
    }
    CHECK_NEAR(o.x_mm, 360.0f * mm_per_tick(&cfg), 0.01);
    CHECK_NEAR(o.y_mm, 0.0, 0.01);
    CHECK_NEAR(o.heading_rad, 0.0, 1e-6);
    CHECK_NEAR(o.v_mm_s[0], 10.0f * mm_per_tick(&cfg) / 0.01f, 1.0);
}

TEST(spin_in_place_a_quarter_turn)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    int32_t enc[2] = {0, 0};
    int32_t i, ticks;
    float arc;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    /* a quarter turn is track * pi / 4 per wheel */
    arc = cfg.track_width_mm * FFR_PI / 4.0f;
    ticks = (int32_t)(arc / mm_per_tick(&cfg) + 0.5f);
    for (i = 0; i < ticks; ++i) {
        enc[0] -= 1;
        enc[1] += 1;
        ffr_odometry_update(&o, &cfg, enc, 0.01f);
    }
    CHECK_NEAR(o.heading_rad, 0.5 * 3.14159265, 0.01);
    CHECK_NEAR(o.x_mm, 0.0, 1e-3);
}

TEST(counter_wrap_around_is_harmless)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    int32_t enc[2] = {2147483640, 2147483640};
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    enc[0] = (int32_t)((uint32_t)enc[0] + 20u);
    enc[1] = (int32_t)((uint32_t)enc[1] + 20u);
    ffr_odometry_update(&o, &cfg, enc, 0.01f);
    CHECK_NEAR(o.x_mm, 20.0f * mm_per_tick(&cfg), 0.01);
}

SUITE(odometry,
      TEST_REF(the_first_reading_only_sets_the_zero),
      TEST_REF(straight_one_circumference_per_revolution),
      TEST_REF(spin_in_place_a_quarter_turn),
      TEST_REF(counter_wrap_around_is_harmless));
