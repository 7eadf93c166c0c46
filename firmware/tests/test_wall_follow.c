#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* ranger reading for a straight wall: points p with n.p = c (n unit normal) */
static float reading(const ffr_config_t *cfg, int i, float nx, float ny, float c)
{
    float a = cfg->ir_angle_deg[i] * FFR_DEG;
    float dn = nx * ffr_cosf(a) + ny * ffr_sinf(a);
    float t;
    if (dn <= 1e-6f) {
        return FFR_IR_NONE(cfg);
    }
    t = (c - (nx * cfg->ir_x_mm[i] + ny * cfg->ir_y_mm[i])) / dn;
    return t > cfg->ir_max_mm ? FFR_IR_NONE(cfg) : t;
}

TEST(a_parallel_wall_on_target_needs_no_steering)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_ir_geom_t g;
    ffr_wall_t w;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* a left wall 230 mm away, parallel */
    ir[FFR_IR_LF] = reading(&cfg, FFR_IR_LF, 0.0f, 1.0f, 230.0f);
    ir[FFR_IR_LR] = reading(&cfg, FFR_IR_LR, 0.0f, 1.0f, 230.0f);
    w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_LEFT);
    CHECK(w.valid && w.angle_valid);
    CHECK_NEAR(w.dist_mm, 230.0, 0.5);
    CHECK_NEAR(w.angle_rad, 0.0, 1e-3);
    /* on target and parallel: no steering */
    CHECK_NEAR(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_LEFT), 0.0, 1e-3);
}

TEST(turned_toward_a_wall_steers_away)
{
    /* the left wall 230 mm away with the robot turned 10 degrees toward it
     * (wall appears rotated -10 degrees): steer right, away from it */
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_ir_geom_t g;
    ffr_wall_t w;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    {
        float a = -10.0f * FFR_DEG;
        float nx = -ffr_sinf(a), ny = ffr_cosf(a);
        ir[FFR_IR_LF] = reading(&cfg, FFR_IR_LF, nx, ny, 230.0f);
        ir[FFR_IR_LR] = reading(&cfg, FFR_IR_LR, nx, ny, 230.0f);
        w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_LEFT);
        CHECK(w.angle_valid);
        CHECK_NEAR(w.angle_rad, a, 0.002);
        CHECK_NEAR(w.dist_mm, 230.0, 1.0);
        CHECK(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_LEFT) < 0.0f);
    }
}

TEST(too_far_from_a_right_wall_steers_right_the_rear_ranger_alone_gives_distance)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_ir_geom_t g;
    ffr_wall_t w;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* too far from a right wall: steer right (negative yaw) */
    ir[FFR_IR_RF] = reading(&cfg, FFR_IR_RF, 0.0f, -1.0f, 300.0f);
    ir[FFR_IR_RR] = reading(&cfg, FFR_IR_RR, 0.0f, -1.0f, 300.0f);
    w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_RIGHT);
    CHECK(w.valid);
    CHECK_NEAR(w.dist_mm, 300.0, 0.5);
    CHECK(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_RIGHT) < 0.0f);
    /* only the rear ranger: distance without angle */
    ir[FFR_IR_RF] = FFR_IR_NONE(&cfg);
    w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_RIGHT);
    CHECK(w.valid && !w.angle_valid);
    CHECK_NEAR(w.dist_mm, 300.0, 60.0);
    /* nothing on the left */
    w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_LEFT);
    CHECK(!w.valid);
}

TEST(heading_hold_turns_toward_the_reference)
{
    ffr_config_t cfg;
    ffr_config_default(&cfg);
    CHECK(ffr_heading_hold_yaw(&cfg, 0.0f, 0.2f) > 0.0f);
    CHECK(ffr_heading_hold_yaw(&cfg, 0.0f, -0.2f) < 0.0f);
}


/* The held corridor heading kept near odometry's right angles (drive.c):
 * over every right angle of an unwrapped heading, every offset within 15
 * degrees in quarter degrees. */
TEST(the_held_heading_is_kept_within_1_5_degrees_of_the_nearest_right_angle)
{
    int k, q;
    for (k = -8; k <= 8; ++k) {
        float square = (float)k * 0.5f * FFR_PI;
        for (q = -60; q <= 60; ++q) {
            float off = (float)q * 0.25f * FFR_DEG;
            float got = ffr_square_hold(square + off);
            if (q == -48 || q == 48) {
                continue; /* exactly 12 degrees: either side of the bound, by rounding */
            }
            if (q >= -6 && q <= 6) {
                CHECK_NEAR(got, square + off, 1e-5);      /* within 1.5 degrees: left alone */
            } else if (q > -48 && q < 48) {
                /* 1.5-12 degrees off: moved to 1.5 degrees off, the same side */
                CHECK_NEAR(got, square + (off > 0.0f ? 1.5f : -1.5f) * FFR_DEG, 1e-4);
            } else {
                CHECK_NEAR(got, square + off, 1e-5);      /* 12 or more: not this right angle */
            }
        }
    }
}

/* Two rangers on two corners of a junction (a steep fake wall) or a tilted
 * pair turn the held heading; with the corridor driving it stays within 1.5
 * degrees of square, and with no wall beside the robot steers to it. */
TEST(wall_angles_do_not_move_the_held_heading_far_off_square)
{
    int a, t;
    for (a = -11; a <= 11; ++a) {
        rig_t r;
        ffr_config_t cfg;
        float ang = (float)a * FFR_DEG;
        ffr_config_default(&cfg);
        rig_init(&r, &cfg);
        r.st.odo.heading_rad = 0.5f * FFR_PI;
        r.st.route.heading_ref_rad = 0.5f * FFR_PI;
        rig_no_walls(&cfg, r.st.ir_mm);
        {
            /* a left wall 230 mm away running `ang` off the heading */
            float nx = -ffr_sinf(ang), ny = ffr_cosf(ang);
            r.st.ir_mm[FFR_IR_LF] = reading(&cfg, FFR_IR_LF, nx, ny, 230.0f);
            r.st.ir_mm[FFR_IR_LR] = reading(&cfg, FFR_IR_LR, nx, ny, 230.0f);
        }
        rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
        for (t = 0; t < 200; ++t) {
            ffr_drive_corridor(&r.st, FFR_SIDE_LEFT, 300.0f);
            CHECK(ffr_absf(r.st.route.heading_ref_rad - 0.5f * FFR_PI) <= 1.5f * FFR_DEG + 1e-5f);
        }
        /* the wall followed 200 ticks: the reference went its way, but only so far */
        if (a <= -2 || a >= 2) {
            CHECK_NEAR(r.st.route.heading_ref_rad, 0.5f * FFR_PI + (a > 0 ? 1.5f : -1.5f) * FFR_DEG, 1e-4);
        }
        /* then no wall: the held heading is where the robot steers */
        rig_no_walls(&cfg, r.st.ir_mm);
        rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
        r.st.odo.heading_rad = 0.5f * FFR_PI;
        ffr_drive_corridor(&r.st, FFR_SIDE_LEFT, 300.0f);
        if (a >= 2) {
            CHECK(r.st.cmd_w_rad_s > 0.0f);
        } else if (a <= -2) {
            CHECK(r.st.cmd_w_rad_s < 0.0f);
        }
        CHECK(ffr_absf(r.st.cmd_w_rad_s) <= cfg.heading_kp * 1.5f * FFR_DEG + 1e-4f);
    }
}

SUITE(wall_follow,
      TEST_REF(a_parallel_wall_on_target_needs_no_steering),
      TEST_REF(turned_toward_a_wall_steers_away),
      TEST_REF(too_far_from_a_right_wall_steers_right_the_rear_ranger_alone_gives_distance),
      TEST_REF(heading_hold_turns_toward_the_reference),
      TEST_REF(the_held_heading_is_kept_within_1_5_degrees_of_the_nearest_right_angle),
      TEST_REF(wall_angles_do_not_move_the_held_heading_far_off_square));
