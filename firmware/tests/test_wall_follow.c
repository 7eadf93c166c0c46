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

SUITE(wall_follow,
      TEST_REF(a_parallel_wall_on_target_needs_no_steering),
      TEST_REF(turned_toward_a_wall_steers_away),
      TEST_REF(too_far_from_a_right_wall_steers_right_the_rear_ranger_alone_gives_distance),
      TEST_REF(heading_hold_turns_toward_the_reference));
