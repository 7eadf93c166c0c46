/*
 * wall_direction.c: each side ranger's hits, placed in odometry's frame,
 * give the wall's direction there, whatever the part's calibration. The
 * rangers' readings are computed from a true pose beside straight walls;
 * odometry's frame is the world turned by its heading error.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

static int drive_worst(ffr_wall_cal_t *c, const ffr_config_t *cfg, const rig_walls_t *w, float *x, float th, float err,
                       float turn_per_mm, float mm, float *dir_out, float *worst)
{
    ffr_odometry_t o;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    float y = 0.0f, s = 0.0f, dir;
    int i, found = 0;
    ffr_odometry_reset(&o);
    while (s < mm) {
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            ir[i] = rig_beam_mm(cfg, w, i, *x, y, th);
        }
        /* odometry's frame: the world turned by err */
        o.x_mm = ffr_cosf(err) * *x - ffr_sinf(err) * y;
        o.y_mm = ffr_sinf(err) * *x + ffr_cosf(err) * y;
        o.heading_rad = th + err;
        o.dist_mm = s;
        if (ffr_wall_dir_update(c, cfg, &o, rig_geom(&g, cfg, ir), ir, &dir)) {
            *dir_out = dir;
            if (ffr_absf(dir - err) > *worst) {
                *worst = ffr_absf(dir - err);
            }
            ++found;
        }
        *x += 3.0f * ffr_cosf(th);
        y += 3.0f * ffr_sinf(th);
        th += turn_per_mm * 3.0f;
        s += 3.0f;
    }
    return found;
}

/* Drive `mm` from (x, 0) at true heading `th` (turning turn_per_mm), with
 * odometry's heading `err` off; returns how many windows closed, the last
 * direction seen and how far the worst was from the walls' (err). */
static int drive(ffr_wall_cal_t *c, const ffr_config_t *cfg, const rig_walls_t *w, float *x, float th, float err,
                 float turn_per_mm, float mm, float *dir_out)
{
    float worst = 0.0f;
    return drive_worst(c, cfg, w, x, th, err, turn_per_mm, mm, dir_out, &worst);
}

TEST(the_walls_direction_in_odometrys_frame)
{
    ffr_config_t cfg;
    ffr_wall_cal_t c;
    rig_walls_t w = {230.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0.0f, -30.0f, 30.0f, 30.0f, -30.0f}};
    float x = 0.0f, dir = 99.0f;
    ffr_config_default(&cfg);
    ffr_wall_cal_reset(&c);
    /* parts 30 mm long and short, in opposite pairs (their two-ranger lines
     * tilt by degrees); odometry 7 degrees off: the walls read at 7 degrees */
    CHECK(drive(&c, &cfg, &w, &x, 0.0f, 7.0f * FFR_DEG, 0.0f, 1000.0f, &dir) >= 7);
    CHECK_NEAR(dir / FFR_DEG, 7.0, 0.2);
    /* driving 5 degrees toward the right wall changes nothing */
    ffr_wall_dir_reset(&c);
    w.left_y = 300.0f;
    CHECK(drive(&c, &cfg, &w, &x, -5.0f * FFR_DEG, -4.0f * FFR_DEG, 0.0f, 500.0f, &dir) >= 3);
    CHECK_NEAR(dir / FFR_DEG, -4.0, 0.3);
    /* one wall, one ranger (the other looks into an opening): enough */
    {
        rig_walls_t one = {2000.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 25.0f, 0.0f, 0.0f}};
        ffr_wall_dir_reset(&c);
        x = 0.0f;
        cfg.ir_angle_deg[FFR_IR_RR] = 180.0f; /* blind the rear right ranger */
        CHECK(drive(&c, &cfg, &one, &x, 0.0f, 3.0f * FFR_DEG, 0.0f, 600.0f, &dir) >= 4);
        CHECK_NEAR(dir / FFR_DEG, 3.0, 0.2);
        ffr_config_default(&cfg);
    }
}

TEST(not_a_straight_wall_along_the_travel)
{
    ffr_config_t cfg;
    ffr_wall_cal_t c;
    rig_walls_t w = {230.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0}};
    float x = 0.0f, dir = 0.0f;
    ffr_config_default(&cfg);
    ffr_wall_cal_reset(&c);
    /* too little travel */
    CHECK(drive(&c, &cfg, &w, &x, 0.0f, 0.0f, 0.0f, 110.0f, &dir) == 0);
    /* turning 12 degrees per 100 mm */
    ffr_wall_dir_reset(&c);
    CHECK(drive(&c, &cfg, &w, &x, 0.0f, 0.0f, 0.12f * FFR_DEG, 600.0f, &dir) == 0);
    /* a wall across ahead: the front rangers' hits bend onto it (the rear
     * ones still see the hallway's walls, whose direction is right) */
    ffr_wall_dir_reset(&c);
    x = 0.0f;
    w.ahead_x = 450.0f;
    dir = 99.0f;
    drive(&c, &cfg, &w, &x, 0.0f, 0.0f, 0.0f, 150.0f, &dir);
    CHECK(dir == 99.0f || ffr_absf(dir) < 0.5f * FFR_DEG);
    /* the right wall steps out 30 mm (a door jamb, a wall's thickness): the
     * windows across the step are not a line, the others are right */
    {
        rig_walls_t jog = {5000.0f, -230.0f, 0.0f, 600.0f, -30.0f, {0}};
        float worst = 0.0f;
        ffr_wall_dir_reset(&c);
        x = 0.0f;
        CHECK(drive_worst(&c, &cfg, &jog, &x, 0.0f, 2.0f * FFR_DEG, 0.0f, 1200.0f, &dir, &worst) >= 6);
        CHECK(worst < 0.3f * FFR_DEG);
    }
    /* hits that only move along the beam (driving straight at a wall seen by
     * one ranger) are no line along the travel */
    {
        rig_walls_t across = {5000.0f, -5000.0f, 900.0f, 0.0f, 0.0f, {0}};
        ffr_wall_dir_reset(&c);
        x = 0.0f;
        dir = 99.0f;
        CHECK(drive(&c, &cfg, &across, &x, 0.0f, 0.0f, 0.0f, 400.0f, &dir) == 0);
    }
}

SUITE(wall_direction,
      TEST_REF(the_walls_direction_in_odometrys_frame),
      TEST_REF(not_a_straight_wall_along_the_travel));
