/*
 * wall_calibration.c (each side's two-ranger tilt learned from travel) and
 * wall_direction.c (the walls' direction from each ranger's hits). First the
 * tilt alone with synthetic wall estimates, then closed loop: the whole
 * firmware beside one straight wall, its rangers' readings computed from the
 * true pose, with a pair of parts at opposite ends of the datasheet's offset
 * spread, and odometry off by what a room's scan leaves.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* Feed `ticks` ticks of travel, `step` mm each, beside a straight wall. The
 * robot's heading is `rel` to the right of the wall (the wall runs `rel` to
 * the left of the heading); odometry's heading is off the truth by `err`
 * (which the tilt must not depend on). The two rangers' angle reads the
 * wall's true angle to the heading plus `tilt`. */
static void feed(ffr_wall_cal_t *c, int side, float err, float *s, float rel, float tilt, int ticks, float step)
{
    int i;
    for (i = 0; i < ticks; ++i, *s += step) {
        ffr_wall_t w;
        w.valid = 1;
        w.angle_valid = 1;
        /* away from a left wall that runs to the left of the path, toward a right one */
        w.dist_mm = 230.0f + (side == FFR_SIDE_LEFT ? 1.0f : -1.0f) * rel * (*s - 1000.0f);
        w.angle_rad = rel + tilt;
        ffr_wall_cal_update(c, &w, side, -rel + err, *s);
    }
}

TEST(a_pairs_tilt_is_learned_per_side)
{
    ffr_wall_cal_t c;
    ffr_wall_t w;
    float s = 0.0f;
    ffr_wall_cal_reset(&c);
    /* 60 mm: no window completed yet */
    feed(&c, FFR_SIDE_LEFT, 0.0f, &s, 4.0f * FFR_DEG, 5.0f * FFR_DEG, 20, 3.0f);
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0 && c.bias_rad[FFR_SIDE_LEFT] == 0.0f);
    /* the robot drives 4 degrees off a left wall, the left pair reads 5 degrees more */
    feed(&c, FFR_SIDE_LEFT, 0.0f, &s, 4.0f * FFR_DEG, 5.0f * FFR_DEG, 400, 3.0f);
    CHECK_NEAR(c.bias_rad[FFR_SIDE_LEFT] / FFR_DEG, 5.0, 0.1);
    CHECK(c.bias_n[FFR_SIDE_LEFT] > 0 && c.bias_n[FFR_SIDE_RIGHT] == 0);
    /* the right pair is unaffected, then learns its own, whatever odometry's error */
    CHECK(c.bias_rad[FFR_SIDE_RIGHT] == 0.0f);
    feed(&c, FFR_SIDE_RIGHT, 10.0f * FFR_DEG, &s, -2.0f * FFR_DEG, -3.0f * FFR_DEG, 400, 3.0f);
    CHECK_NEAR(c.bias_rad[FFR_SIDE_RIGHT] / FFR_DEG, -3.0, 0.1);
    CHECK_NEAR(c.bias_rad[FFR_SIDE_LEFT] / FFR_DEG, 5.0, 0.1);
    /* and comes off that side's angle only, when both rangers measured it */
    w.valid = 1;
    w.angle_valid = 1;
    w.dist_mm = 230.0f;
    w.angle_rad = 1.0f * FFR_DEG;
    ffr_wall_cal_correct(&c, &w, FFR_SIDE_LEFT);
    CHECK_NEAR(w.angle_rad / FFR_DEG, -4.0, 0.1);
    w.angle_rad = 1.0f * FFR_DEG;
    ffr_wall_cal_correct(&c, &w, FFR_SIDE_RIGHT);
    CHECK_NEAR(w.angle_rad / FFR_DEG, 4.0, 0.1);
    w.angle_valid = 0;
    w.angle_rad = 1.0f * FFR_DEG;
    ffr_wall_cal_correct(&c, &w, FFR_SIDE_RIGHT);
    CHECK_NEAR(w.angle_rad / FFR_DEG, 1.0, 1e-6);
    /* a new window keeps it, a reset forgets it */
    ffr_wall_cal_restart(&c);
    CHECK_NEAR(c.bias_rad[FFR_SIDE_LEFT] / FFR_DEG, 5.0, 0.1);
    ffr_wall_cal_reset(&c);
    CHECK(c.bias_rad[0] == 0.0f && c.bias_rad[1] == 0.0f && c.bias_n[0] == 0 && c.bias_n[1] == 0);
}

TEST(gaps_turns_and_other_walls_teach_nothing)
{
    ffr_wall_cal_t c;
    ffr_wall_t w;
    float h = 12.0f * FFR_DEG, s = 0.0f;
    int i;
    ffr_wall_cal_reset(&c);
    /* one ranger every third tick: never a whole window */
    w.valid = 1;
    w.dist_mm = 230.0f;
    w.angle_rad = 3.0f * FFR_DEG;
    for (i = 0; i < 600; ++i, s += 3.0f) {
        w.angle_valid = (uint8_t)(i % 3 != 0);
        ffr_wall_cal_update(&c, &w, FFR_SIDE_LEFT, h, s);
    }
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
    /* turning 1 degree every 10 mm: never 100 mm within 8 degrees */
    w.angle_valid = 1;
    for (i = 0; i < 600; ++i, s += 3.0f) {
        h += 0.3f * FFR_DEG;
        ffr_wall_cal_update(&c, &w, FFR_SIDE_LEFT, h, s);
    }
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
    /* standing still (a turn in place) completes no window */
    ffr_wall_cal_restart(&c);
    for (i = 0; i < 600; ++i) {
        ffr_wall_cal_update(&c, &w, FFR_SIDE_LEFT, 10.0f * FFR_DEG, s);
    }
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
    /* no side (heading hold) is no window */
    ffr_wall_cal_update(&c, &w, FFR_SIDE_NONE, 0.0f, s);
    CHECK(c.side == -1);
    /* the pair's line 20 degrees off the travel: two walls, not a tilt */
    feed(&c, FFR_SIDE_LEFT, 0.0f, &s, 0.0f, 20.0f * FFR_DEG, 300, 3.0f);
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
    /* the pair's line jumping by 4 degrees every other tick (one ranger
     * between two walls): not steady, not learned */
    for (i = 0; i < 300; ++i, s += 3.0f) {
        w.angle_rad = (i & 1) ? 4.0f * FFR_DEG : 0.0f;
        ffr_wall_cal_update(&c, &w, FFR_SIDE_LEFT, 0.0f, s);
    }
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
    /* nor the distance jumping by 10 mm */
    w.angle_rad = 0.0f;
    for (i = 0; i < 300; ++i, s += 3.0f) {
        w.dist_mm = (i & 1) ? 240.0f : 230.0f;
        ffr_wall_cal_update(&c, &w, FFR_SIDE_LEFT, 0.0f, s);
    }
    CHECK(c.bias_n[FFR_SIDE_LEFT] == 0);
}

/* ---- closed loop: the firmware beside a straight wall ------------------ */

typedef struct {
    rig_t r;
    float x, y, th;      /* true pose, mm and rad */
    int32_t enc_prev[2];
    rig_walls_t walls;   /* a right wall only                         */
    float offset_mv[FFR_IR_COUNT]; /* each part's reading error   */
} world_t;

static uint16_t ranger_mv(const world_t *wd, const ffr_config_t *cfg, int i)
{
    float d = rig_beam_mm(cfg, &wd->walls, i, wd->x, wd->y, wd->th);
    float mv;
    if (!ffr_ir_valid(cfg, d)) {
        return 0; /* nothing in range */
    }
    mv = cfg->ir_k_mv_mm / (d + cfg->ir_d0_mm) + cfg->ir_offset_mv + wd->offset_mv[i];
    return (uint16_t)(mv + 0.5f);
}

static void world_tick(world_t *wd)
{
    const ffr_config_t *cfg = &wd->r.st.cfg;
    const float mm_per_tick = 2.0f * FFR_PI * cfg->wheel_radius_mm / cfg->encoder_ticks_per_rev;
    float dl, dr, ds, dth;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        wd->r.in.ir_mv[i] = ranger_mv(wd, cfg, i);
    }
    rig_tick(&wd->r);
    dl = (float)(wd->r.in.enc[0] - wd->enc_prev[0]) * mm_per_tick;
    dr = (float)(wd->r.in.enc[1] - wd->enc_prev[1]) * mm_per_tick;
    wd->enc_prev[0] = wd->r.in.enc[0];
    wd->enc_prev[1] = wd->r.in.enc[1];
    ds = 0.5f * (dl + dr);
    dth = (dr - dl) / cfg->track_width_mm;
    wd->x += ds * ffr_cosf(wd->th + 0.5f * dth);
    wd->y += ds * ffr_sinf(wd->th + 0.5f * dth);
    wd->th += dth;
}

/* Follow the right wall (nothing ahead ever) from the origin heading +x,
 * odometry starting `odo_err_deg` off the truth; return after `ticks`. */
static void follow_wall(world_t *wd, float front_mv, float rear_mv, float odo_err_deg, int ticks)
{
    ffr_config_t cfg;
    int i;
    ffr_config_default(&cfg);
    cfg.route[0].op = FFR_OP_FOLLOW;
    cfg.route[0].side = FFR_SIDE_RIGHT;
    cfg.route[0].event = FFR_EV_FRONT;
    cfg.route[1].op = FFR_OP_END;
    cfg.route_len = 2;
    rig_init(&wd->r, &cfg);
    wd->x = wd->y = wd->th = 0.0f;
    wd->enc_prev[0] = wd->enc_prev[1] = 0;
    wd->walls.left_y = 1.0e6f;
    wd->walls.right_y = -cfg.wall_target_mm;
    wd->walls.ahead_x = wd->walls.jog_x = wd->walls.jog_dy = 0.0f;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        wd->offset_mv[i] = 0.0f;
        wd->walls.part_mm[i] = 0.0f;
    }
    wd->offset_mv[FFR_IR_RF] = front_mv;
    wd->offset_mv[FFR_IR_RR] = rear_mv;
    world_tick(wd); /* primes odometry */
    wd->r.st.odo.heading_rad = odo_err_deg * FFR_DEG;
    wd->r.in.start = 1;
    for (i = 0; i < ticks; ++i) {
        world_tick(wd);
    }
}

TEST(opposite_parts_no_longer_tilt_the_corridor_heading)
{
    world_t wd;
    float ref_true_deg, tilt_deg;
    /* the front part reads 120 mV high (near), the rear one 120 mV low (far):
     * their line runs ~4 degrees off the wall, toward it ahead */
    follow_wall(&wd, 120.0f, -120.0f, 0.0f, 1000);
    CHECK(wd.r.out.state == FFR_ST_FOLLOW);
    /* the robot drove ~3 m along the wall without touching it */
    CHECK(wd.x > 2500.0f);
    CHECK(wd.y > -120.0f && wd.y < 120.0f);
    /* the tilt it learned is the pair's (positive: the line turns left of
     * the wall, as a right wall nearer ahead does) */
    tilt_deg = wd.r.st.wall_cal.bias_rad[FFR_SIDE_RIGHT] / FFR_DEG;
    CHECK(tilt_deg > 3.0f && tilt_deg < 6.0f);
    /* the corridor heading (what the next turn is measured from) runs along
     * the wall within a degree; odometry is exact here, so truth = odometry */
    ref_true_deg = wd.r.st.route.heading_ref_rad / FFR_DEG;
    CHECK_NEAR(ref_true_deg, 0.0, 1.0);
    CHECK_NEAR(wd.th / FFR_DEG, 0.0, 1.5);
    /* without the correction the corridor heading would hold the tilt: the
     * measured angle, tilt not taken off, is what it would follow */
    {
        ffr_ir_geom_t g;
        ffr_wall_t w = ffr_wall_estimate(&wd.r.st.cfg, rig_geom(&g, &wd.r.st.cfg, wd.r.st.ir_mm), wd.r.st.ir_mm,
                                         FFR_SIDE_RIGHT);
        CHECK(w.angle_valid);
        CHECK(ffr_absf(w.angle_rad / FFR_DEG - -wd.th / FFR_DEG) > 3.0f);
    }
}

TEST(odometry_off_by_a_turn_is_brought_back_by_the_wall)
{
    world_t wd;
    float err_deg;
    /* odometry 9 degrees off (a scan's track slip), matched parts */
    follow_wall(&wd, 0.0f, 0.0f, 9.0f, 1000);
    err_deg = (wd.r.st.odo.heading_rad - wd.th) / FFR_DEG;
    /* brought within the dead zone of 1.5 degrees (from 9) */
    CHECK(err_deg > -2.0f && err_deg < 2.0f);
    CHECK(wd.x > 2500.0f);
    /* and with opposite parts as well */
    follow_wall(&wd, -120.0f, 120.0f, -9.0f, 1000);
    err_deg = (wd.r.st.odo.heading_rad - wd.th) / FFR_DEG;
    CHECK(err_deg > -2.0f && err_deg < 2.0f);
    /* the corridor heading was set by the 9-degree-off odometry: it runs along the wall now */
    CHECK_NEAR((wd.r.st.route.heading_ref_rad - wd.r.st.odo.heading_rad + wd.th) / FFR_DEG, 0.0, 1.5);
    CHECK(wd.r.st.wall_cal.bias_rad[FFR_SIDE_RIGHT] / FFR_DEG < -3.0f);
}

/* The pair's tilt split between its rangers for where walls end: each side's
 * front hit moves in along its beam by half the lateral difference the tilt
 * makes at the followed wall's spacing, the rear hit out by as much; a side
 * that learned nothing, an invalid reading and the other rangers keep theirs. */
TEST(a_pairs_tilt_is_split_half_each_along_the_beams)
{
    ffr_config_t cfg;
    ffr_ir_geom_t g, before;
    ffr_wall_cal_t c;
    float ir[FFR_IR_COUNT];
    float spacing, half;
    int i;
    ffr_config_default(&cfg);
    ffr_ir_geom_init(&g, &cfg);
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        ir[i] = 250.0f;
    }
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    ffr_ir_geom_update(&g, &cfg, ir);
    before = g;
    ffr_wall_cal_reset(&c);
    /* nothing learned: nothing moves */
    ffr_wall_cal_split(&c, &cfg, ir, &g);
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        CHECK(g.hit_x_mm[i] == before.hit_x_mm[i] && g.hit_y_mm[i] == before.hit_y_mm[i]);
    }
    /* the left pair's line reads 6 degrees left of the wall, the right's 4 right
     * of it: either way the front part reads farther out than the rear one */
    c.bias_rad[FFR_SIDE_LEFT] = 6.0f * FFR_DEG;
    c.bias_n[FFR_SIDE_LEFT] = 1u;
    c.bias_rad[FFR_SIDE_RIGHT] = -4.0f * FFR_DEG;
    c.bias_n[FFR_SIDE_RIGHT] = 1u;
    ffr_wall_cal_split(&c, &cfg, ir, &g);
    /* the hits' spacing on a wall at the followed distance, front to rear */
    spacing = (cfg.ir_x_mm[FFR_IR_LF] + (cfg.wall_target_mm - cfg.ir_y_mm[FFR_IR_LF]))
              - (cfg.ir_x_mm[FFR_IR_LR] - (cfg.wall_target_mm - cfg.ir_y_mm[FFR_IR_LR]));
    CHECK(spacing > 300.0f);
    half = 0.5f * 6.0f * FFR_DEG * spacing;
    CHECK_NEAR(g.hit_y_mm[FFR_IR_LF], before.hit_y_mm[FFR_IR_LF] - half, 0.5);
    CHECK_NEAR(g.hit_x_mm[FFR_IR_LF], before.hit_x_mm[FFR_IR_LF] - half, 0.5); /* 45 degrees: earlier as much */
    CHECK_NEAR(g.hit_y_mm[FFR_IR_LR], before.hit_y_mm[FFR_IR_LR] + half, 0.5);
    CHECK_NEAR(g.hit_x_mm[FFR_IR_LR], before.hit_x_mm[FFR_IR_LR] - half, 0.5);
    /* right (y negative to the side): the front hit moves in, and earlier */
    half = 0.5f * 4.0f * FFR_DEG * spacing;
    CHECK_NEAR(g.hit_y_mm[FFR_IR_RF], before.hit_y_mm[FFR_IR_RF] + half, 0.5);
    CHECK_NEAR(g.hit_x_mm[FFR_IR_RF], before.hit_x_mm[FFR_IR_RF] - half, 0.5);
    /* no reading from the right rear: its hit stays where the geometry put it */
    CHECK(g.hit_x_mm[FFR_IR_RR] == before.hit_x_mm[FFR_IR_RR] && g.hit_y_mm[FFR_IR_RR] == before.hit_y_mm[FFR_IR_RR]);
    CHECK(g.hit_x_mm[FFR_IR_CF] == before.hit_x_mm[FFR_IR_CF] && g.hit_y_mm[FFR_IR_CF] == before.hit_y_mm[FFR_IR_CF]);
}

SUITE(wall_calibration,
      TEST_REF(a_pairs_tilt_is_learned_per_side),
      TEST_REF(a_pairs_tilt_is_split_half_each_along_the_beams),
      TEST_REF(gaps_turns_and_other_walls_teach_nothing),
      TEST_REF(opposite_parts_no_longer_tilt_the_corridor_heading),
      TEST_REF(odometry_off_by_a_turn_is_brought_back_by_the_wall));
