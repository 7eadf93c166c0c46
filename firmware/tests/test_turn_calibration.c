/*
 * turn_calibration.c: odometry's turn scale learned from the heading errors
 * the walls report after turns. A simulated robot whose true rotation is c x
 * what odometry counts raw (wheel radius and track width off what it was
 * told) turns; the walls then report odometry's heading error.
 */
#include "ffr_internal.h"
#include "unit.h"

/* odometry's heading error after a turn of `raw` (rad, odometry's raw count)
 * with the scale it has now, for a robot whose true scale is c */
static float turn_and_fix(ffr_odometry_t *o, float c, float raw)
{
    float counted = o->turn_scale * raw;
    float truth = c * raw;
    o->rot_raw_rad += raw;
    return counted - truth;
}

TEST(the_scale_converges_over_the_whole_range)
{
    /* true scales from 0.9 to 1.1 (wheel radius +-3 %, track width +-5 % and more),
     * turns of 90 and 180 degrees and a room's scan of 540, both ways */
    static const float turns_deg[] = {90.0f, -90.0f, 540.0f, 90.0f, -180.0f, 90.0f, -90.0f, 450.0f};
    int i, k;
    float worst = 0.0f;
    for (i = 0; i <= 20; ++i) {
        float c = 0.9f + 0.01f * (float)i;
        ffr_odometry_t o;
        ffr_odometry_reset(&o);
        CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
        for (k = 0; k < 8; ++k) {
            float err = turn_and_fix(&o, c, turns_deg[k] * FFR_DEG);
            ffr_turn_cal_learn(&o, err);
            CHECK_NEAR(o.rot_raw_rad, 0.0f, 0.0f);
        }
        if (ffr_absf(o.turn_scale - c) > worst) {
            worst = ffr_absf(o.turn_scale - c);
        }
    }
    CHECK_NEAR(worst, 0.0f, 0.002f);
}

TEST(small_turns_and_large_errors_teach_nothing)
{
    ffr_odometry_t o;
    ffr_odometry_reset(&o);
    /* 30 degrees of rotation: a heading error there is mostly the wall's noise */
    ffr_turn_cal_learn(&o, turn_and_fix(&o, 1.1f, 30.0f * FFR_DEG));
    CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
    /* an error of 30 degrees is not a scale's doing (a wrong wall) */
    o.rot_raw_rad = 90.0f * FFR_DEG;
    ffr_turn_cal_learn(&o, 30.0f * FFR_DEG);
    CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
    CHECK_NEAR(o.rot_raw_rad, 0.0f, 0.0f);
    /* an error within the wall measurement's noise (0.5 degrees) teaches nothing */
    o.rot_raw_rad = 90.0f * FFR_DEG;
    ffr_turn_cal_learn(&o, 0.4f * FFR_DEG);
    CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
    /* one good fix moves it most of the way */
    ffr_turn_cal_learn(&o, turn_and_fix(&o, 1.06f, 90.0f * FFR_DEG));
    CHECK(o.turn_scale > 1.03f && o.turn_scale < 1.06f);
    /* odometry applies it: a turn in place counted raw x scale */
    {
        ffr_config_t cfg;
        int32_t enc[2] = {0, 0};
        float before;
        ffr_config_default(&cfg);
        o.primed = 0;
        ffr_odometry_update(&o, &cfg, enc, 0.01f);
        before = o.heading_rad;
        enc[0] = -100;
        enc[1] = 100;
        ffr_odometry_update(&o, &cfg, enc, 0.01f);
        CHECK_NEAR(o.heading_rad - before,
                   o.turn_scale * (200.0f * 2.0f * 3.14159265f * cfg.wheel_radius_mm / cfg.encoder_ticks_per_rev) /
                       cfg.track_width_mm,
                   1e-4);
    }
}

SUITE(turn_calibration,
      TEST_REF(the_scale_converges_over_the_whole_range),
      TEST_REF(small_turns_and_large_errors_teach_nothing));
