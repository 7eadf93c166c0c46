/*
 * turn_calibration.c: odometry's turn scale learned from the heading errors
 * the walls report after turns. A simulated robot whose true rotation is c x
 * what odometry counts raw (wheel radius and track width off what it was
 * told) turns; the walls then report odometry's heading error.
 */
#include "ffr_internal.h"
#include "rig.h"
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

/* A room's scan in place (turn_calibration.c, ffr_scan_sq_*) at the world's
 * origin among the walls w, from true heading th0 through `turn` radians
 * (true) at the default scan rate in 20 ms ticks. The robot's true rotation
 * is c x odometry's raw count; odometry starts e0 off the truth with scale 1.
 * The rangers read as GP2D12s do: a new reading every other tick (38 ms),
 * of the pose `age` ticks before. Returns what fix said; *after: odometry's
 * heading error at the end with the scan's share (grow x raw) taken off. */
static int scan(ffr_odometry_t *o, ffr_scan_square_t *q, const ffr_config_t *cfg, const rig_walls_t *w, float th0,
                float turn, float c, float e0, int age, float *grow, float *after)
{
    const float dt = 0.02f;
    float rate = cfg->scan_rate_deg_s * FFR_DEG * (turn < 0.0f ? -1.0f : 1.0f);
    int n = (int)(ffr_absf(turn) / (cfg->scan_rate_deg_s * FFR_DEG * dt));
    float th = th0;
    float ir[FFR_IR_COUNT];
    ffr_ir_geom_t g;
    int k, i, fixed;
    ffr_odometry_reset(o);
    o->heading_rad = th0 + e0;
    ffr_scan_sq_reset(q);
    for (k = 0; k < n; ++k) {
        float raw = rate * dt / c;
        th += rate * dt;
        if (k % 2 == 0) {
            for (i = 0; i < FFR_IR_COUNT; ++i) {
                ir[i] = rig_beam_mm(cfg, w, i, 0.0f, 0.0f, th - (float)age * rate * dt);
            }
        }
        o->dpos_mm[1] = 0.5f * raw * cfg->track_width_mm;
        o->dpos_mm[0] = -o->dpos_mm[1];
        o->heading_rad += o->turn_scale * raw;
        ffr_scan_sq_record(q, cfg, o, rig_geom(&g, cfg, ir), ir);
    }
    *grow = 0.0f;
    fixed = ffr_scan_sq_fix(q, o, grow);
    *after = o->heading_rad - *grow * q->raw_rad - th;
    return fixed;
}

TEST(a_rooms_scan_tells_what_it_added_to_the_heading_error_and_the_turn_scale)
{
    /* a room 600 mm wide, the robot 250 mm from its far wall, open behind
     * (its door); true scales over the realistic profile's range and beyond
     * (0.85-1.2), heading errors at the scan's start up to +-15 degrees,
     * start headings round the turn, both ways, readings 0-3 ticks old, a
     * turn and a bit (three parts) */
    rig_walls_t w = {300.0f, -300.0f, 250.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_scan_square_t q;
    float worst_e = 0.0f, worst_far = 0.0f, worst_s = 0.0f;
    int i, j;
    ffr_config_default(&cfg);
    for (i = 0; i <= 14; ++i) {
        float c = 0.85f + 0.025f * (float)i;
        for (j = 0; j < 8; ++j) {
            float e0 = (-15.0f + 30.0f * (float)j / 7.0f) * FFR_DEG;
            float th0 = (float)(i * 8 + j) * 11.0f * FFR_DEG;
            float turn = (j & 1 ? -380.0f : 380.0f) * FFR_DEG;
            float grow = 0.0f, after = 0.0f, e;
            CHECK(scan(&o, &q, &cfg, &w, th0, turn, c, e0, j % 4, &grow, &after));
            /* the heading error left is the one it came in with */
            e = ffr_absf(after - e0);
            if (ffr_absf(1.0f - c) <= 0.1f && e > worst_e) {
                worst_e = e;
            }
            worst_far = e > worst_far ? e : worst_far;
            /* the scale it learned is the truth's */
            if (ffr_absf(o.turn_scale - c) > worst_s) {
                worst_s = ffr_absf(o.turn_scale - c);
            }
        }
    }
    /* within 2.5 degrees for scales within 10 % (the realistic profile's
     * calibration and floor), 3.5 beyond (the error then grows 45-75 degrees
     * over the turn and bends each stretch of hits a little) */
    CHECK_NEAR(worst_e, 0.0f, 2.5f * FFR_DEG);
    CHECK_NEAR(worst_far, 0.0f, 3.5f * FFR_DEG);
    CHECK_NEAR(worst_s, 0.0f, 0.02f);
}

TEST(a_short_scan_tells_nothing)
{
    /* 150 degrees: one or two parts, too close together for the growth */
    rig_walls_t w = {300.0f, -300.0f, 250.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_scan_square_t q;
    float grow = 0.0f, after = 0.0f;
    ffr_config_default(&cfg);
    CHECK(!scan(&o, &q, &cfg, &w, 0.3f, 150.0f * FFR_DEG, 0.9f, 8.0f * FFR_DEG, 2, &grow, &after));
    CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
    CHECK_NEAR(grow, 0.0f, 0.0f);
}

TEST(no_wall_in_reach_tells_nothing)
{
    /* walls 2 m away: beyond SQ_RANGE_MM, the scan sees no wall */
    rig_walls_t w = {2000.0f, -2000.0f, 2000.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_scan_square_t q;
    float grow = 0.0f, after = 0.0f;
    ffr_config_default(&cfg);
    CHECK(!scan(&o, &q, &cfg, &w, 0.0f, 380.0f * FFR_DEG, 0.9f, 0.1f, 2, &grow, &after));
    CHECK_NEAR(o.turn_scale, 1.0f, 0.0f);
}

SUITE(turn_calibration,
      TEST_REF(the_scale_converges_over_the_whole_range),
      TEST_REF(small_turns_and_large_errors_teach_nothing),
      TEST_REF(a_rooms_scan_tells_what_it_added_to_the_heading_error_and_the_turn_scale),
      TEST_REF(a_short_scan_tells_nothing),
      TEST_REF(no_wall_in_reach_tells_nothing));
