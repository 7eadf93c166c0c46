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
    CHECK_NEAR(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_LEFT, cfg.wall_target_mm), 0.0, 1e-3);
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
        CHECK(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_LEFT, cfg.wall_target_mm) < 0.0f);
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
    CHECK(ffr_wall_follow_yaw(&cfg, &w, FFR_SIDE_RIGHT, cfg.wall_target_mm) < 0.0f);
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

/* The held corridor heading follows a two-ranger wall only within 5 degrees
 * of it (drive.c): a pair's line ~10 degrees off is two walls at a
 * junction's mouth, not drift. Every wall direction from -11 to 11 degrees
 * off the held heading, either side followed. */
TEST(the_held_heading_follows_a_wall_only_within_5_degrees)
{
    int a, side, t;
    for (side = FFR_SIDE_LEFT; side <= FFR_SIDE_RIGHT; ++side) {
        for (a = -11; a <= 11; ++a) {
            rig_t r;
            ffr_config_t cfg;
            float ang = (float)a * FFR_DEG;
            float ref0 = 0.5f * FFR_PI;
            float sgn = side == FFR_SIDE_LEFT ? 1.0f : -1.0f;
            float nx = -sgn * ffr_sinf(ang), ny = sgn * ffr_cosf(ang);
            int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
            int rr = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
            ffr_config_default(&cfg);
            rig_init(&r, &cfg);
            r.st.odo.heading_rad = ref0;
            r.st.route.heading_ref_rad = ref0;
            rig_no_walls(&cfg, r.st.ir_mm);
            /* a wall 230 mm to the side running `ang` off the heading */
            r.st.ir_mm[f] = reading(&cfg, f, nx, ny, 230.0f);
            r.st.ir_mm[rr] = reading(&cfg, rr, nx, ny, 230.0f);
            rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
            for (t = 0; t < 200; ++t) {
                ffr_drive_corridor(&r.st, (uint8_t)side, 300.0f);
            }
            if (a == -5 || a == 5) {
                continue; /* exactly the bound: either side of it, by rounding */
            }
            if (a > -5 && a < 5) {
                /* followed: the held heading has gone (nearly all) the way to the wall's */
                CHECK_NEAR(r.st.route.heading_ref_rad, ref0 + ang, 0.01f * FFR_DEG + 1e-5f);
            } else {
                CHECK_NEAR(r.st.route.heading_ref_rad, ref0, 1e-6); /* not this wall: left alone */
            }
        }
    }
}

/* A front corner near a wall beside it (drive.c, ffr_corridor_guard): the
 * robot turned 0-20 degrees toward a side wall 110-160 mm away (its front
 * corner ranger's hit within guard_side_mm of the body's side and front),
 * following the other side's wall 230 mm away, its held heading 10 degrees
 * further toward the near wall (a heading left off by a room's exit): the
 * yaw command turns away from the near wall at least as fast as the leaving
 * guard's push. Either side. */
TEST(a_front_corner_near_a_side_wall_is_steered_off_it)
{
    int side, a, c;
    for (side = FFR_SIDE_LEFT; side <= FFR_SIDE_RIGHT; ++side) {
        float sgn = side == FFR_SIDE_LEFT ? 1.0f : -1.0f; /* + left */
        int near_f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        int near_r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
        int far_f = side == FFR_SIDE_LEFT ? FFR_IR_RF : FFR_IR_LF;
        int far_r = side == FFR_SIDE_LEFT ? FFR_IR_RR : FFR_IR_LR;
        for (a = 0; a <= 20; a += 5) {
            for (c = 110; c <= 160; c += 10) {
                rig_t r;
                ffr_config_t cfg;
                float toward = (float)a * FFR_DEG * sgn; /* the heading's turn toward the near wall */
                float nx = sgn * ffr_sinf(toward), ny = sgn * ffr_cosf(toward);
                float g;
                ffr_config_default(&cfg);
                rig_init(&r, &cfg);
                r.st.odo.heading_rad = 0.5f * FFR_PI;
                r.st.route.heading_ref_rad = r.st.odo.heading_rad + 10.0f * FFR_DEG * sgn;
                rig_no_walls(&cfg, r.st.ir_mm);
                r.st.ir_mm[near_f] = reading(&cfg, near_f, nx, ny, (float)c);
                r.st.ir_mm[near_r] = reading(&cfg, near_r, nx, ny, (float)c);
                r.st.ir_mm[far_f] = reading(&cfg, far_f, -nx, -ny, 230.0f);
                r.st.ir_mm[far_r] = reading(&cfg, far_r, -nx, -ny, 230.0f);
                rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
                g = ffr_leave_guard(&r.st);
                CHECK(g * sgn < 0.0f); /* the guard sees the corner's wall: pushes off it */
                ffr_drive_corridor(&r.st, (uint8_t)(1 - side), 300.0f);
                CHECK(r.st.cmd_w_rad_s * sgn <= g * sgn + 1e-6f);
                CHECK(r.st.cmd_v_mm_s > 0.0f);
            }
        }
    }
}

/* With both walls 230 mm away and parallel, the guard sees nothing and the
 * corridor driving is the wall following alone (no steering on target). */
TEST(on_the_corridor_middle_the_corner_guard_does_nothing)
{
    int side;
    for (side = FFR_SIDE_LEFT; side <= FFR_SIDE_RIGHT; ++side) {
        rig_t r;
        ffr_config_t cfg;
        ffr_config_default(&cfg);
        rig_init(&r, &cfg);
        r.st.odo.heading_rad = 0.5f * FFR_PI;
        r.st.route.heading_ref_rad = r.st.odo.heading_rad;
        rig_no_walls(&cfg, r.st.ir_mm);
        r.st.ir_mm[FFR_IR_LF] = reading(&cfg, FFR_IR_LF, 0.0f, 1.0f, 230.0f);
        r.st.ir_mm[FFR_IR_LR] = reading(&cfg, FFR_IR_LR, 0.0f, 1.0f, 230.0f);
        r.st.ir_mm[FFR_IR_RF] = reading(&cfg, FFR_IR_RF, 0.0f, -1.0f, 230.0f);
        r.st.ir_mm[FFR_IR_RR] = reading(&cfg, FFR_IR_RR, 0.0f, -1.0f, 230.0f);
        rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
        CHECK(ffr_leave_guard(&r.st) == 0.0f);
        ffr_drive_corridor(&r.st, (uint8_t)side, 300.0f);
        CHECK_NEAR(r.st.cmd_w_rad_s, 0.0, 1e-3);
    }
}

/* The route's last stretch past an opening (route.c, drive_to_goal) holds
 * the held heading alone; a held heading 5-15 degrees toward a side wall
 * whose front corner ranger's hit is within the guard band now turns away
 * from that wall (it turned toward it before). */
TEST(the_last_stretch_past_an_opening_keeps_a_front_corner_off_a_wall)
{
    int side, a;
    for (side = FFR_SIDE_LEFT; side <= FFR_SIDE_RIGHT; ++side) {
        float sgn = side == FFR_SIDE_LEFT ? 1.0f : -1.0f;
        int near_f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        for (a = 5; a <= 15; a += 5) {
            rig_t r;
            ffr_config_t cfg;
            ffr_inputs_t in;
            ffr_config_default(&cfg);
            rig_init(&r, &cfg);
            in = r.in;
            r.st.route.pc = 2; /* the default route's FOLLOW(RIGHT, OPEN_L) */
            CHECK(cfg.route[2].op == FFR_OP_FOLLOW && cfg.route[2].event == FFR_EV_OPEN_L);
            r.st.route.phase = 1; /* past the opening's wall end: on to its middle */
            r.st.route.goal_mm = r.st.odo.dist_mm + 400.0f;
            r.st.odo.heading_rad = 0.5f * FFR_PI;
            r.st.route.heading_ref_rad = r.st.odo.heading_rad + (float)a * FFR_DEG * sgn;
            rig_no_walls(&cfg, r.st.ir_mm);
            r.st.ir_mm[near_f] = reading(&cfg, near_f, 0.0f, sgn, 140.0f);
            rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
            ffr_route_step(&r.st, &in);
            CHECK(r.st.route.pc == 2);
            CHECK(r.st.cmd_v_mm_s > 0.0f);
            CHECK(r.st.cmd_w_rad_s * sgn < 0.0f);
            CHECK(r.st.cmd_w_rad_s * sgn <= ffr_leave_guard(&r.st) * sgn + 1e-6f);
        }
    }
}


/* Facing a wall `d_mm` ahead, turned `psi` off its normal, odometry on the
 * held heading; the watch saw the wall beside `exit_wall` (or
 * FFR_EXIT_WALL_NONE). Squares out of the room; the rig is left for checks. */
static float square_rig(rig_t *r, float psi, float d_mm, float c_extra_mm, int drop_c, float exit_wall)
{
    ffr_config_t cfg;
    float ref0 = 0.25f * FFR_PI;
    ffr_config_default(&cfg);
    rig_init(r, &cfg);
    r->st.odo.heading_rad = ref0;
    r->st.route.heading_ref_rad = ref0;
    rig_no_walls(&cfg, r->st.ir_mm);
    /* the wall x = d_mm in the wall's frame; in the body frame its normal is (cos psi, -sin psi) */
    r->st.ir_mm[FFR_IR_LF] = reading(&cfg, FFR_IR_LF, ffr_cosf(psi), -ffr_sinf(psi), d_mm);
    r->st.ir_mm[FFR_IR_RF] = reading(&cfg, FFR_IR_RF, ffr_cosf(psi), -ffr_sinf(psi), d_mm);
    r->st.ir_mm[FFR_IR_CF] = drop_c ? FFR_IR_NONE(&cfg)
                                    : reading(&cfg, FFR_IR_CF, ffr_cosf(psi), -ffr_sinf(psi), d_mm) + c_extra_mm;
    rig_geom(&r->st.ir_geom, &cfg, r->st.ir_mm);
    r->st.route.exit_wall_rad = exit_wall;
    ffr_square_out_of_room(&r->st);
    return r->st.odo.heading_rad - ref0;
}

/* Out of a room, facing the corridor's far wall (route.c,
 * ffr_square_out_of_room, no wall seen beside): the robot truly turned
 * `psi` off the wall's normal while odometry holds the exit heading. An
 * angle within SQUARE_MIN_DEG (13) changes nothing (two parts' bias);
 * beyond it, odometry is set to within SQUARE_KEEP_DEG (4) of the wall's
 * angle, either side. A
 * corner ahead (the centre ranger's hit off the corner rangers' line), a
 * wall seen by two rangers only, and three hits in a line with one read
 * beyond SQUARE_RANGE_MM (600: a square robot whose left front ranger looks
 * through a door beside the wall ahead, seen in a jittered arena as a wall
 * 26 degrees off) change nothing. */
static float square_after(float psi, float d_mm, float c_extra_mm, int drop_c)
{
    rig_t r;
    return square_rig(&r, psi, d_mm, c_extra_mm, drop_c, FFR_EXIT_WALL_NONE);
}

/* the left front ranger through a door: its hit far out on a line with the others */
static float square_through_a_door(void)
{
    rig_t r;
    ffr_config_t cfg;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    r.st.odo.heading_rad = 0.0f;
    r.st.route.heading_ref_rad = 0.0f;
    rig_no_walls(&cfg, r.st.ir_mm);
    r.st.ir_mm[FFR_IR_CF] = 164.0f;
    r.st.ir_mm[FFR_IR_LF] = 716.0f;
    r.st.ir_mm[FFR_IR_RF] = 173.0f;
    rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
    r.st.route.exit_wall_rad = FFR_EXIT_WALL_NONE;
    ffr_square_out_of_room(&r.st);
    return r.st.odo.heading_rad;
}

TEST(out_of_a_room_the_heading_is_set_square_to_the_wall_ahead_when_far_off)
{
    int a;
    float dm;
    for (dm = 200.0f; dm <= 300.0f; dm += 50.0f) {
        for (a = -20; a <= 20; ++a) {
            float psi = (float)a * FFR_DEG;
            float got = square_after(psi, dm, 0.0f, 0);
            if (a == -13 || a == 13) {
                continue; /* exactly the bound: either side of it, by rounding */
            }
            if (a > -13 && a < 13) {
                CHECK_NEAR(got, 0.0f, 1e-6f);
            } else {
                CHECK_NEAR(got, psi - (a > 0 ? 4.0f : -4.0f) * FFR_DEG, 0.2f * FFR_DEG);
            }
            /* not one straight wall: a corner 60 mm nearer in the middle, or no centre hit */
            CHECK_NEAR(square_after(psi, dm, -60.0f, 0), 0.0f, 1e-6f);
            CHECK_NEAR(square_after(psi, dm, 0.0f, 1), 0.0f, 1e-6f);
        }
    }
    CHECK_NEAR(square_through_a_door(), 0.0f, 1e-6f);
}

/* Out of a room along a wall (route.c, ffr_exit_wall_watch and
 * ffr_square_out_of_room, no wall ahead): the robot drives 400 mm out
 * holding the exit heading by odometry while it is truly turned `psi` off the wall beside
 * it (right, 250 mm; its parts reading 30 mm long and short: the windows'
 * direction does not depend on them). Within EXIT_MIN_DEG (8) nothing
 * changes; beyond it odometry is set to within EXIT_KEEP_DEG (3) of the
 * wall; a wall more than 20 degrees off the travel is not one the windows
 * take, and no wall beside (or a watch that saw none) changes nothing. */
static float beside_after(float psi, int wall)
{
    rig_t r;
    ffr_config_t cfg;
    rig_walls_t w = {5000.0f, -250.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 30.0f, 0.0f, -30.0f}};
    float ref0 = 0.5f * FFR_PI, s, rot = ref0 - psi; /* odometry's frame: the world turned by rot */
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    if (!wall) {
        w.right_y = -5000.0f;
    }
    r.st.route.heading_ref_rad = ref0;
    r.st.route.exit_wall_rad = FFR_EXIT_WALL_NONE;
    ffr_wall_dir_reset(&r.st.wall_cal);
    for (s = 0.0f; s <= 400.0f; s += 3.0f) {
        float x = s * ffr_cosf(psi), y = s * ffr_sinf(psi);
        int i;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            r.st.ir_mm[i] = rig_beam_mm(&cfg, &w, i, x, y, psi);
        }
        rig_geom(&r.st.ir_geom, &cfg, r.st.ir_mm);
        r.st.odo.x_mm = ffr_cosf(rot) * x - ffr_sinf(rot) * y;
        r.st.odo.y_mm = ffr_sinf(rot) * x + ffr_cosf(rot) * y;
        r.st.odo.heading_rad = ref0; /* held by odometry all the way */
        r.st.odo.dist_mm = s;
        ffr_exit_wall_watch(&r.st);
    }
    ffr_square_out_of_room(&r.st);
    CHECK(r.st.route.exit_wall_rad == FFR_EXIT_WALL_NONE); /* taken once */
    return r.st.odo.heading_rad - ref0;
}

TEST(out_of_a_room_the_heading_is_set_square_to_the_wall_beside_when_far_off)
{
    int a;
    for (a = -30; a <= 30; ++a) {
        float psi = (float)a * FFR_DEG;
        float got = beside_after(psi, 1);
        if (a >= -7 && a <= 7) {
            CHECK_NEAR(got, 0.0f, 1e-6f);
        } else if (a >= 9 && a <= 19) {
            CHECK_NEAR(got, psi - 3.0f * FFR_DEG, 0.3f * FFR_DEG);
        } else if (a <= -9 && a >= -19) {
            CHECK_NEAR(got, psi + 3.0f * FFR_DEG, 0.3f * FFR_DEG);
        } else if (a <= -22 || a >= 22) {
            CHECK_NEAR(got, 0.0f, 1e-6f);
        }
        CHECK_NEAR(beside_after(psi, 0), 0.0f, 1e-6f);
    }
}

/* Both walls out of a room (route.c, ffr_square_out_of_room): the wall
 * ahead read `psi_a` off its normal (250 mm ahead; none with drop_c) and
 * the watch's wall beside `psi_b` off the held heading (the test above
 * shows the watch reads it): a body truly turned psi_b left sees the wall
 * beside psi_b to the right of the held heading. */
static float square_both(float psi_a, float psi_b, int drop_c)
{
    rig_t r;
    float got = square_rig(&r, psi_a, 250.0f, 0.0f, drop_c, -psi_b);
    CHECK(r.st.route.exit_wall_rad == FFR_EXIT_WALL_NONE);
    return got;
}

/* A robot left room 2 with odometry 15 degrees short: the wall ahead read
 * 10.5 (two parts' bias), the wall beside 11.4; neither was taken. Now the
 * wall beside is, when the wall ahead reads the error the same way within
 * SQUARE_MIN_DEG; read the other way (or exactly square) it is not; far off
 * (beyond 13) the wall ahead is taken as before, and unread, the wall beside. */
TEST(out_of_a_room_the_wall_beside_is_taken_when_the_wall_ahead_agrees)
{
    int a, b;
    for (b = -19; b <= 19; ++b) {
        float pb = (float)b * FFR_DEG, keep = (b > 0 ? 3.0f : -3.0f) * FFR_DEG;
        if (b > -9 && b < 9) {
            continue; /* within EXIT_MIN_DEG: the beside test above */
        }
        for (a = -12; a <= 12; ++a) {
            float pa = (float)a * FFR_DEG, got = square_both(pa, pb, 0);
            if (a * b > 0) {
                CHECK_NEAR(got, pb - keep, 0.2f * FFR_DEG);
            } else {
                CHECK_NEAR(got, 0.0f, 1e-6f);
            }
        }
        /* the wall ahead far off: its angle, less 4 degrees, whatever the wall beside says */
        CHECK_NEAR(square_both(16.0f * FFR_DEG, pb, 0), 12.0f * FFR_DEG, 0.2f * FFR_DEG);
        CHECK_NEAR(square_both(-16.0f * FFR_DEG, pb, 0), -12.0f * FFR_DEG, 0.2f * FFR_DEG);
        /* no wall ahead read: the wall beside */
        CHECK_NEAR(square_both(-5.0f * FFR_DEG, pb, 1), pb - keep, 0.2f * FFR_DEG);
    }
}

/* The default route's HOME(LEFT) (step 27, home from room 1) in a straight
 * hallway on the rig, its walls at y = left_y and right_y: the robot starts
 * on its middle line's left side, at wall_target_mm from the left wall,
 * heading along it; beyond x = 900 mm the right wall opens (a junction).
 * No line comes, so the step goes on. Returns the robot's y at x = 800 mm
 * (both walls beside) and at x = 1500 mm (the right side open), from the
 * rig's odometry (its wheels do not slip: the truth). */
static void home_leg(float left_y, float right_y, float *y_both, float *y_open)
{
    ffr_config_t cfg;
    rig_t r;
    rig_walls_t w = {0.0f, 0.0f, 0.0f, 900.0f, -2000.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    int i, ticks = 0;
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_AS_PLACED; /* no orientation: the route at once */
    CHECK(cfg.route[27].op == FFR_OP_HOME && cfg.route[27].side == FFR_SIDE_LEFT);
    w.left_y = left_y - (left_y - cfg.wall_target_mm);
    w.right_y = right_y - (left_y - cfg.wall_target_mm);
    rig_init(&r, &cfg);
    r.in.start = 1;
    rig_tick(&r);
    ffr_route_begin(&r.st, 27);
    *y_both = *y_open = 1.0e9f;
    while (r.st.odo.x_mm < 1500.0f && ticks++ < 3000) {
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            float b = rig_beam_mm(&cfg, &w, i, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
            r.in.ir_mv[i] = b < FFR_IR_NONE(&cfg) ? rig_mv_for_mm(&cfg, b) : 0u;
        }
        rig_tick(&r);
        if (*y_both > 1.0e8f && r.st.odo.x_mm >= 800.0f) {
            *y_both = r.st.odo.y_mm;
        }
    }
    CHECK(r.out.state == FFR_ST_HOMING);
    *y_open = r.st.odo.y_mm;
}

/* HOME follows its wall at the hallway's middle as read (route.c,
 * home_middle), and keeps that distance where the other side opens: the
 * home circle lies within the hallway, nearer its middle line than half the
 * hallway less its radius. A 560 mm hallway (the robot starts 230 mm from
 * its left wall, 50 mm left of the middle): on the middle within 15 mm by
 * x = 800, and still within 25 mm 600 mm past the right wall's end; at
 * wall_target_mm from the left wall (before) it stayed 50 mm off. The
 * contest's 460 mm hallway: on its middle as before. A wall 700 mm off on the
 * right (a junction, not a hallway): the left wall at wall_target_mm. */
TEST(home_follows_the_hallways_middle_and_keeps_it_where_a_side_opens)
{
    float y_both, y_open;
    home_leg(230.0f, -330.0f, &y_both, &y_open); /* the middle: y = -50 */
    CHECK(ffr_absf(y_both + 50.0f) < 15.0f);
    CHECK(ffr_absf(y_open + 50.0f) < 25.0f);
    home_leg(230.0f, -230.0f, &y_both, &y_open);
    CHECK(ffr_absf(y_both) < 15.0f && ffr_absf(y_open) < 15.0f);
    home_leg(230.0f, -700.0f, &y_both, &y_open);
    CHECK(ffr_absf(y_both) < 15.0f && ffr_absf(y_open) < 15.0f);
}

SUITE(wall_follow,
      TEST_REF(a_parallel_wall_on_target_needs_no_steering),
      TEST_REF(turned_toward_a_wall_steers_away),
      TEST_REF(too_far_from_a_right_wall_steers_right_the_rear_ranger_alone_gives_distance),
      TEST_REF(heading_hold_turns_toward_the_reference),
      TEST_REF(the_held_heading_follows_a_wall_only_within_5_degrees),
      TEST_REF(a_front_corner_near_a_side_wall_is_steered_off_it),
      TEST_REF(on_the_corridor_middle_the_corner_guard_does_nothing),
      TEST_REF(the_last_stretch_past_an_opening_keeps_a_front_corner_off_a_wall),
      TEST_REF(home_follows_the_hallways_middle_and_keeps_it_where_a_side_opens),
      TEST_REF(out_of_a_room_the_heading_is_set_square_to_the_wall_ahead_when_far_off),
      TEST_REF(out_of_a_room_the_heading_is_set_square_to_the_wall_beside_when_far_off),
      TEST_REF(out_of_a_room_the_wall_beside_is_taken_when_the_wall_ahead_agrees));
