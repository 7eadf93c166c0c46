/*
 * The explorer (explore.c), the arbitrary start mode: the home circle told by
 * its two lines, the turns' square targets, and the whole firmware in the
 * mode on the test rig (hand-set walls and line).
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

TEST(the_home_circle_is_two_lines_a_chord_apart)
{
    float m = 0.0f;
    /* through the middle of a 15 cm circle: the origin 110 mm behind the line
     * sensor is 40 mm past the chord's middle */
    CHECK(ffr_explore_is_circle(300.0f, 110.0f, &m));
    CHECK_NEAR(m, -40.0f, 1e-4);
    /* a short chord near the circle's edge: on 60 mm more to its middle */
    CHECK(ffr_explore_is_circle(100.0f, 110.0f, &m));
    CHECK_NEAR(m, 60.0f, 1e-4);
    CHECK(ffr_explore_is_circle(FFR_HOME_CHORD_MM, 110.0f, &m));
    /* farther apart: two lines that are not one circle (a doorway's, then another) */
    m = 123.0f;
    CHECK(!ffr_explore_is_circle(FFR_HOME_CHORD_MM + 1.0f, 110.0f, &m));
    CHECK(!ffr_explore_is_circle(-1.0f, 110.0f, &m));
    CHECK_NEAR(m, 123.0f, 0.0); /* untouched when not a circle */
}

TEST(turn_targets_are_square_to_the_walls)
{
    const float q = 0.5f * FFR_PI;
    CHECK_NEAR(ffr_explore_square(0.1f), 0.0f, 1e-6);
    CHECK_NEAR(ffr_explore_square(-0.1f), 0.0f, 1e-6);
    CHECK_NEAR(ffr_explore_square(q + 0.3f), q, 1e-6);
    CHECK_NEAR(ffr_explore_square(q - 0.7f), q, 1e-6);
    CHECK_NEAR(ffr_explore_square(-2.0f), -q, 1e-6);
    CHECK_NEAR(ffr_explore_square(3.0f), 2.0f * q, 1e-6);
    /* odometry's heading is unwrapped: two turns round is still square */
    CHECK_NEAR(ffr_explore_square(4.0f * q + 0.2f), 4.0f * q, 1e-5);
    CHECK_NEAR(ffr_explore_square(-5.0f * q - 0.4f), -5.0f * q, 1e-5);
}

/* a hallway: a wall each side at the wanted distance, nothing ahead */
static void hallway(rig_t *r, const ffr_config_t *cfg)
{
    r->in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(cfg, 226.0f);
    r->in.ir_mv[FFR_IR_LR] = rig_mv_for_mm(cfg, 226.0f);
    r->in.ir_mv[FFR_IR_RF] = rig_mv_for_mm(cfg, 226.0f);
    r->in.ir_mv[FFR_IR_RR] = rig_mv_for_mm(cfg, 226.0f);
}

/* Started in a hallway (its walls fed to the rangers), 30 ticks on. */
static void started_in_a_hallway(rig_t *r, const ffr_config_t *cfg)
{
    int i;
    rig_init(r, cfg);
    r->in.start = 1;
    hallway(r, cfg);
    for (i = 0; i < 30; ++i) {
        rig_tick(r);
    }
}

/* The default configuration in the arbitrary start mode, started in a hallway. */
static void explorer_started(rig_t *r, ffr_config_t *cfg)
{
    ffr_config_default(cfg);
    cfg->start_area = FFR_START_HALLWAY;
    started_in_a_hallway(r, cfg);
}

/* the home circle's two lines, a chord apart, after `before` ticks on the floor */
static void cross_home(rig_t *r, int before)
{
    rig_line(r, before, 3);
    rig_line(r, 40, 3);
    rig_tick(r);
}

TEST(the_mode_switch_is_off_by_default)
{
    ffr_config_t cfg;
    rig_t r;
    ffr_config_default(&cfg);
    CHECK(cfg.start_area == FFR_START_HOME);
    started_in_a_hallway(&r, &cfg);
    /* the route program's first step, not the explorer */
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.out.step == 0);
    CHECK(r.st.explore.homes == 0 && r.st.explore.edge_mm < -1.0e8f);
}

TEST(in_a_hallway_it_follows_passes_home_and_stops_there_with_the_flame_out)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    explorer_started(&r, &cfg);
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.out.step == 0); /* the explorer's phase: follow */
    CHECK(r.st.explore.side == FFR_SIDE_RIGHT);
    CHECK(r.out.pwm[0] > 100 && r.out.pwm[1] > 100);

    /* the home circle crossed before the flame is out: counted, the walk goes
     * on (no room searched yet: the same wall) */
    cross_home(&r, 5);
    CHECK(r.st.explore.homes == 1);
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.st.explore.side == FFR_SIDE_RIGHT);
    CHECK(!(r.out.flags & FFR_FLAG_DONE));

    /* a lone line, no second within a circle's chord: not home */
    r.st.flags |= FFR_FLAG_EXTINGUISHED; /* as the room task leaves it */
    rig_line(&r, 150, 3);
    for (i = 0; i < 40; ++i) {
        rig_tick(&r);
    }
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.st.explore.homes == 1);

    /* with the flame out, the circle's two lines: on to the chord's middle, stop */
    rig_line(&r, 20, 3);
    CHECK(r.st.explore.homes == 2);
    CHECK(rig_run_until_state(&r, FFR_ST_DONE, 200));
    CHECK(r.out.flags & FFR_FLAG_DONE);
    rig_tick(&r);
    CHECK(r.out.pwm[0] == 0 && r.out.pwm[1] == 0);
}

TEST(a_lone_line_on_the_way_home_turns_the_robot_round)
{
    ffr_config_t cfg;
    rig_t r;
    explorer_started(&r, &cfg);
    r.st.flags |= FFR_FLAG_EXTINGUISHED;
    rig_line(&r, 5, 3);
    /* a doorway's line crossed straight: past a circle's chord with no second
     * line, the robot turns round (half a turn, square) */
    CHECK(rig_run_until_state(&r, FFR_ST_TURN, 400));
    CHECK_NEAR(r.st.explore.target_rad - r.st.route.heading_ref_rad, FFR_PI, 1e-5);
    CHECK(!(r.out.flags & FFR_FLAG_DONE));
}


/* the explorer's phases as outputs.step reports them (explore.c) */
enum { PH_FOLLOW = 0, PH_WRAP = 1, PH_TURN = 2, PH_PROBE = 3 };
/* and its phases as explore.c numbers them (ffr_explore_t.phase) */
enum { EX_LEG_WRAP = 1, EX_LEG_PROBE = 3, EX_LEG_HOME = 5, EX_LEG_BACK = 6 };

/* In a hallway, the leg begun 600 mm back, an opening on the followed side
 * seen whole, its far edge `edge_mm` ahead; one tick. Where the robot stood. */
static float whole_opening_ahead(rig_t *r, const ffr_config_t *cfg, float edge_mm)
{
    float d;
    started_in_a_hallway(r, cfg);
    d = r->st.odo.dist_mm;
    r->st.explore.start_mm = d - 600.0f;
    r->st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r->st.open.gap_end_mm[FFR_SIDE_RIGHT] = d + edge_mm;
    rig_tick(r);
    return d;
}

TEST(a_whole_opening_whose_middle_is_passed_is_backed_to_then_turned_into)
{
    ffr_config_t cfg;
    rig_t r;
    float d, x0;
    int i;
    explorer_started(&r, &cfg);
    /* an opening on the followed side seen whole (open, then its far edge
     * 180 mm ahead): its middle, half a hallway before that edge, is 50 mm
     * behind the robot; the leg began 600 mm back (not the door just left) */
    d = r.st.odo.dist_mm;
    x0 = r.st.odo.x_mm;
    r.st.explore.start_mm = d - 600.0f;
    r.st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = d + cfg.hallway_half_mm - 50.0f;
    rig_tick(&r);
    CHECK(r.out.step == PH_WRAP);
    CHECK(r.st.explore.backing == 1);
    CHECK(r.st.cmd_v_mm_s < 0.0f); /* backing */
    CHECK(rig_run_until_state(&r, FFR_ST_TURN, 300));
    /* back to the middle, 50 mm behind (along the held heading: the stop's
     * coasting on is backed too), then the quarter turn toward the
     * followed wall */
    CHECK(r.st.odo.x_mm < x0 - 45.0f && r.st.odo.x_mm > x0 - 60.0f);
    CHECK_NEAR(r.st.explore.target_rad - r.st.route.heading_ref_rad, -0.5f * FFR_PI, 1e-5);
    CHECK(r.st.explore.backing == 0);

    /* its middle still ahead: on to it, no backing */
    (void)whole_opening_ahead(&r, &cfg, cfg.hallway_half_mm + 100.0f);
    CHECK(r.out.step == PH_WRAP);
    CHECK(r.st.explore.backing == 0);
    for (i = 0; i < 5; ++i) {
        rig_tick(&r);
    }
    CHECK(r.st.cmd_v_mm_s > 0.0f);
}

TEST(a_probe_that_finds_a_hallway_keeps_where_the_leg_began)
{
    ffr_config_t cfg;
    rig_t r;
    float d, start;
    explorer_started(&r, &cfg);
    /* a probe 301 mm on with no line: a hallway, the follow goes on */
    d = r.st.odo.dist_mm;
    start = d - 301.0f;
    r.st.explore.phase = PH_PROBE;
    r.st.state = FFR_ST_FORWARD;
    r.st.explore.start_mm = start;
    rig_tick(&r);
    CHECK(r.out.step == PH_FOLLOW);
    CHECK(r.st.explore.start_mm == start);
    /* an opening seen whole, its far edge 250 mm ahead: 550 mm from where
     * the leg began, more than a hallway's width, so not the door just left */
    d = r.st.odo.dist_mm;
    r.st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = d + 250.0f;
    rig_tick(&r);
    CHECK(r.out.step == PH_WRAP);
    CHECK_NEAR(r.st.explore.goal_mm, d + 250.0f - cfg.hallway_half_mm, 1e-3);

    /* the same opening when the leg began at a turn (out of a door) just
     * before: within a hallway's width of its start, the door just left */
    started_in_a_hallway(&r, &cfg);
    r.st.explore.phase = PH_TURN;
    r.st.state = FFR_ST_TURN;
    r.st.explore.after = PH_FOLLOW;
    r.st.explore.target_rad = r.st.odo.heading_rad;
    rig_tick(&r);
    CHECK(r.out.step == PH_FOLLOW);
    d = r.st.odo.dist_mm;
    CHECK(r.st.explore.start_mm > d - 20.0f);
    r.st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = d + 250.0f;
    rig_tick(&r);
    CHECK(r.out.step == PH_FOLLOW);
}

/* the far (left) wall 330 mm off on both its rangers: the wall following
 * asks to turn toward it (left) */
static float follow_yaw_with_heading_off(float off_deg)
{
    ffr_config_t cfg;
    rig_t r;
    explorer_started(&r, &cfg);
    r.in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(&cfg, 330.0f);
    r.in.ir_mv[FFR_IR_LR] = rig_mv_for_mm(&cfg, 330.0f);
    r.in.ir_mv[FFR_IR_RF] = 0;
    r.in.ir_mv[FFR_IR_RR] = 0;
    r.st.odo.heading_rad = r.st.route.heading_ref_rad + off_deg * FFR_DEG;
    rig_tick(&r);
    CHECK(r.out.step == PH_FOLLOW);
    return r.st.cmd_w_rad_s;
}

TEST(the_follow_holds_the_hallway_heading_within_ten_degrees)
{
    /* 5 degrees off the held heading: the wall following steers on, left */
    CHECK(follow_yaw_with_heading_off(5.0f) > 0.0f);
    CHECK(follow_yaw_with_heading_off(-5.0f) > 0.0f);
    /* 12 degrees off already to the left: no further, back toward the
     * hallway's heading (right) */
    CHECK(follow_yaw_with_heading_off(12.0f) < 0.0f);
    /* 12 degrees off to the right: the steering left brings it back, kept */
    CHECK(follow_yaw_with_heading_off(-12.0f) > 0.0f);
}

/* following in a hallway, the leg begun 20 mm back, the right wall ended
 * `before_mm` before that start; one tick. The leg's start. */
static float right_wall_ended_before_the_leg(rig_t *r, const ffr_config_t *cfg, float before_mm)
{
    float start;
    started_in_a_hallway(r, cfg);
    start = r->st.odo.dist_mm - 20.0f;
    r->st.explore.start_mm = start;
    r->st.open.opened[FFR_SIDE_RIGHT] = 1;
    r->st.open.seen[FFR_SIDE_RIGHT] = 1;
    r->st.open.open_at_mm[FFR_SIDE_RIGHT] = start - before_mm;
    rig_tick(r);
    return start;
}

TEST(a_wall_end_behind_where_the_leg_began_is_the_door_just_left)
{
    ffr_config_t cfg;
    rig_t r;
    float start;
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;
    /* the rear ranger's wall ended 300 mm before the leg began: the
     * opening's middle is 70 mm behind that start (the robot stood in it) */
    (void)right_wall_ended_before_the_leg(&r, &cfg, 300.0f);
    CHECK(r.out.step == PH_FOLLOW);
    CHECK(r.st.open.opened[FFR_SIDE_RIGHT] == 0); /* watched afresh */
    CHECK(r.st.cmd_v_mm_s > 0.0f);

    /* ended 200 mm before: its middle 30 mm past the start, taken */
    start = right_wall_ended_before_the_leg(&r, &cfg, 200.0f);
    CHECK(r.out.step == PH_WRAP);
    CHECK_NEAR(r.st.explore.goal_mm, start + 30.0f, 1e-3);
}

/* the right wall ended 100 mm past where the leg began: the wrap to half a
 * hallway past that end (one tick); then the opening's far edge seen
 * `width_mm` past the end, one tick more. The wrap's goal, from the wall's end. */
static float wrap_goal_with_far_edge(rig_t *r, const ffr_config_t *cfg, float width_mm)
{
    float end = right_wall_ended_before_the_leg(r, cfg, -100.0f) + 100.0f;
    r->st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r->st.open.gap_end_mm[FFR_SIDE_RIGHT] = end + width_mm;
    rig_tick(r);
    return r->st.explore.goal_mm - end;
}

TEST(a_narrow_openings_far_edge_seen_in_the_wrap_brings_the_turn_short_of_it)
{
    ffr_config_t cfg;
    rig_t r;
    float cap, end;
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;
    /* no far edge yet: half a hallway past the wall's end */
    end = right_wall_ended_before_the_leg(&r, &cfg, -100.0f) + 100.0f;
    CHECK(r.out.step == PH_WRAP);
    CHECK_NEAR(r.st.explore.goal_mm - end, cfg.hallway_half_mm, 1e-3);

    /* a 30 cm opening as seen (a 41 cm hallway of a +-2.5 cm arena, its
     * edges seen late and early): the turn comes 100 mm and the half width
     * short of the far edge, before the middle a 46 cm one would have */
    cap = 300.0f - cfg.body_half_width_mm - 100.0f;
    CHECK_NEAR(wrap_goal_with_far_edge(&r, &cfg, 300.0f), cap, 1e-3);
    CHECK(r.out.step == PH_WRAP);
    CHECK(rig_run_until_state(&r, FFR_ST_TURN, 300));
    CHECK(r.st.odo.dist_mm - end >= cap && r.st.odo.dist_mm - end < cap + 15.0f);
    CHECK_NEAR(r.st.explore.target_rad - r.st.route.heading_ref_rad, -0.5f * FFR_PI, 1e-5);

    /* a contest opening (46 cm): its far edge leaves the middle as it was */
    CHECK_NEAR(wrap_goal_with_far_edge(&r, &cfg, 460.0f), cfg.hallway_half_mm, 1e-3);
    /* nearly so: a turn less than 20 mm sooner is not worth a change */
    CHECK_NEAR(wrap_goal_with_far_edge(&r, &cfg, cfg.hallway_half_mm + cfg.body_half_width_mm + 100.0f - 19.0f),
               cfg.hallway_half_mm, 1e-3);
    CHECK(wrap_goal_with_far_edge(&r, &cfg, cfg.hallway_half_mm + cfg.body_half_width_mm + 100.0f - 21.0f) <
          cfg.hallway_half_mm - 20.0f);
    /* no opening the body fits (two faces glimpsed 24 cm apart): as it was */
    CHECK_NEAR(wrap_goal_with_far_edge(&r, &cfg, 2.0f * cfg.body_half_width_mm + 40.0f), cfg.hallway_half_mm, 1e-3);
    CHECK(wrap_goal_with_far_edge(&r, &cfg, 2.0f * cfg.body_half_width_mm + 60.0f) < cfg.hallway_half_mm);
    /* a far edge before the wall's end (an earlier opening's): as it was */
    CHECK_NEAR(wrap_goal_with_far_edge(&r, &cfg, -300.0f), cfg.hallway_half_mm, 1e-3);
    /* the gap tracker has closed no gap on this leg: its edge is not one */
    end = right_wall_ended_before_the_leg(&r, &cfg, -100.0f) + 100.0f;
    r.st.open.gaps[FFR_SIDE_RIGHT] = 0;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = end + 300.0f;
    rig_tick(&r);
    CHECK_NEAR(r.st.explore.goal_mm - end, cfg.hallway_half_mm, 1e-3);
    /* a wrap backing to a whole opening's middle (its goal along the held
     * heading, not odometry's distance) is not capped */
    end = right_wall_ended_before_the_leg(&r, &cfg, -100.0f) + 100.0f;
    r.st.explore.backing = 1;
    r.st.explore.goal_mm = 1.0e6f;
    r.st.open.gaps[FFR_SIDE_RIGHT] = 1;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = end + 300.0f;
    rig_tick(&r);
    CHECK_NEAR(r.st.explore.goal_mm, 1.0e6f, 0.0);
    /* a wrap to a whole opening seen from its start (no wall's end on this
     * leg): its goal stays as first set when the far edge is seen nearer
     * (that wrap is not refined, above), however far back a wall's end lies */
    end = whole_opening_ahead(&r, &cfg, cfg.hallway_half_mm + 100.0f);
    CHECK(r.out.step == PH_WRAP && r.st.explore.backing == 0);
    r.in.ir_mv[FFR_IR_RF] = 0; /* the side's front ranger on nothing: the wall's end stays put */
    r.st.open.open_at_mm[FFR_SIDE_RIGHT] = end - 500.0f;
    r.st.open.gap_end_mm[FFR_SIDE_RIGHT] = end - 50.0f;
    rig_tick(&r);
    CHECK_NEAR(r.st.explore.goal_mm - end, 100.0f, 1e-3);
}

/* A straight leg of the explorer (ffr_drive_held) beside a hallway's walls,
 * odometry's heading `err` off the truth from the start: the robot's true
 * pose driven by the firmware's commands, the rangers read from it. Returns
 * the true lateral offset after `mm` of travel; *err_end: odometry's error
 * then. held: ffr_drive_held, else the heading held by odometry alone. */
static float straight_leg(int held, float err, float mm, float *err_end)
{
    ffr_config_t cfg;
    ffr_state_t st;
    rig_walls_t w = {230.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    const float dt = 0.02f;
    float x = 0.0f, y = 0.0f, th = 0.0f;
    int i;
    ffr_config_default(&cfg);
    ffr_init(&st, &cfg);
    st.odo.heading_rad = err;
    st.route.heading_ref_rad = 0.0f; /* the hallway's heading as it believes it */
    while (st.odo.dist_mm < mm) {
        float before, ds, dth;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            st.ir_mm[i] = rig_beam_mm(&cfg, &w, i, x, y, th);
        }
        ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm);
        before = st.odo.heading_rad;
        if (held) {
            ffr_drive_held(&st, 300.0f);
        } else {
            ffr_drive_heading(&st, st.route.heading_ref_rad, 300.0f);
        }
        err -= before - st.odo.heading_rad; /* what the walls took off odometry's error */
        ds = st.cmd_v_mm_s * dt;
        dth = st.cmd_w_rad_s * dt;
        x += ds * ffr_cosf(th + 0.5f * dth);
        y += ds * ffr_sinf(th + 0.5f * dth);
        th += dth;
        st.odo.heading_rad = th + err;
        st.odo.x_mm += ds * ffr_cosf(st.odo.heading_rad);
        st.odo.y_mm += ds * ffr_sinf(st.odo.heading_rad);
        st.odo.dist_mm += ds;
    }
    *err_end = err;
    return y;
}

TEST(a_straight_leg_is_trued_up_by_the_walls_beside)
{
    float err, y;
    /* odometry 6 degrees off (a robot whose sides differ, after a few
     * metres): held by odometry alone, 1.2 m on it crosses 1200 sin 6 deg =
     * 125 mm of a 460 mm hallway, toward the wall the rangers see */
    y = straight_leg(0, 6.0f * FFR_DEG, 1200.0f, &err);
    CHECK(y < -110.0f);
    CHECK_NEAR(err / FFR_DEG, 6.0, 1e-3);
    /* trued up by the walls as it goes: the error down to the fix's dead
     * zone (1.5 degrees) and the robot still near the hallway's middle */
    y = straight_leg(1, 6.0f * FFR_DEG, 1200.0f, &err);
    CHECK(ffr_absf(err) < 2.0f * FFR_DEG);
    CHECK(ffr_absf(y) < 60.0f);
    y = straight_leg(1, -6.0f * FFR_DEG, 1200.0f, &err);
    CHECK(ffr_absf(err) < 2.0f * FFR_DEG);
    CHECK(ffr_absf(y) < 60.0f);
}

/* One of the explorer's straight legs (WRAP, PROBE, BACK or HOME) in the
 * whole firmware on the rig, odometry's heading `err` off the truth at the
 * start, in the middle of a 460 mm hallway. The truth is a second odometry
 * fed the rig's encoders (its wheels do not slip), `err` turned from the
 * firmware's; the rangers read the hallway's walls from it. After `mm` of
 * travel on the leg, returns odometry's error then (rad). */
static float leg_error_after(uint8_t leg, float err, float mm)
{
    ffr_config_t cfg;
    rig_t r;
    ffr_odometry_t truth;
    rig_walls_t w = {230.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    float d0;
    int i, ticks = 0;
    explorer_started(&r, &cfg);
    ffr_odometry_reset(&truth);
    ffr_odometry_update(&truth, &cfg, r.in.enc, 0.01f); /* its zero: the encoders as they are */
    truth.heading_rad = r.st.odo.heading_rad - err;
    r.st.route.heading_ref_rad = r.st.odo.heading_rad; /* the hallway's heading as it believes it */
    r.st.explore.phase = leg;
    r.st.explore.backing = 0;
    r.st.explore.edge_mm = -1.0e9f; /* no line crossed */
    r.st.explore.start_mm = r.st.odo.dist_mm;
    r.st.explore.goal_mm = leg == EX_LEG_BACK ? 5000.0f : r.st.odo.dist_mm + 5000.0f;
    r.st.state = FFR_ST_FORWARD;
    d0 = r.st.odo.dist_mm;
    while (r.st.odo.dist_mm - d0 < mm && ticks++ < 5000) {
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            float b = rig_beam_mm(&cfg, &w, i, truth.x_mm, truth.y_mm, truth.heading_rad);
            r.in.ir_mv[i] = b < FFR_IR_NONE(&cfg) ? rig_mv_for_mm(&cfg, b) : 0u;
        }
        rig_tick(&r);
        ffr_odometry_update(&truth, &cfg, r.in.enc, 0.01f);
    }
    CHECK(r.st.explore.phase == leg); /* still on the leg, driving */
    CHECK(r.st.cmd_v_mm_s > 0.0f);
    CHECK(ffr_absf(truth.y_mm) < 150.0f); /* off no wall */
    return ffr_wrap_pi(r.st.odo.heading_rad - truth.heading_rad);
}

TEST(every_straight_leg_of_the_explorer_is_trued_up_by_the_walls_beside)
{
    static const uint8_t legs[4] = {EX_LEG_WRAP, EX_LEG_PROBE, EX_LEG_BACK, EX_LEG_HOME};
    int k;
    for (k = 0; k < 4; ++k) {
        /* 6 degrees off at the start (a robot whose sides differ, after a
         * few metres): one wall window (120 mm) takes half of what is over
         * the fix's dead zone (1.5 degrees) off it, so within 250 mm of
         * travel (a probe's is 300) it is under 4.5, the same sign; held by
         * odometry alone (the rig's wheels do not slip) it would stay 6 */
        float e = leg_error_after(legs[k], 6.0f * FFR_DEG, 250.0f);
        CHECK(e < 4.5f * FFR_DEG && e > 1.0f * FFR_DEG);
        e = leg_error_after(legs[k], -6.0f * FFR_DEG, 250.0f);
        CHECK(e > -4.5f * FFR_DEG && e < -1.0f * FFR_DEG);
        /* and none made beyond the dead zone where there was none */
        CHECK(ffr_absf(leg_error_after(legs[k], 0.0f, 250.0f)) < 1.5f * FFR_DEG);
    }
}

TEST(a_loop_with_its_rooms_searched_and_no_flame_makes_the_next_rooms_searched_harder)
{
    /* round a loop (home's two lines) with rooms searched on it and no
     * flame: the walls change, and from then on every room is searched
     * harder (room.c: a second and a third scan point); once the flame is
     * out, no more */
    ffr_config_t cfg;
    rig_t r;
    explorer_started(&r, &cfg);
    CHECK(r.st.explore.flips == 0u);
    CHECK(ffr_explore_searched_round(&r.st) == 0);
    cross_home(&r, 5); /* no room searched yet: the same wall */
    CHECK(r.st.explore.homes == 1 && r.st.explore.flips == 0u);
    CHECK(ffr_explore_searched_round(&r.st) == 0);
    r.st.rooms_searched = 2u; /* as the room task leaves it, two rooms on the loop */
    cross_home(&r, 150);
    CHECK(r.st.explore.homes == 2 && r.st.explore.flips == 1u);
    CHECK(r.st.explore.side == FFR_SIDE_LEFT);
    CHECK(ffr_explore_searched_round(&r.st) == 1);
    r.st.flags |= FFR_FLAG_EXTINGUISHED;
    CHECK(ffr_explore_searched_round(&r.st) == 0);
}

/* Leaving a room (room.c's last phase, on its next tick: the wall across
 * the hallway ahead), the right side's two corner rangers reading right_mm */
static void leaving_a_room(rig_t *r, const ffr_config_t *cfg, float right_mm, float left_mm)
{
    started_in_a_hallway(r, cfg);
    ffr_room_begin(&r->st, 1u, r->st.route.heading_ref_rad);
    r->st.explore.phase = 4u; /* EX_ROOM (explore.c) */
    r->st.room.phase = 11u;   /* RP_LEAVE_OUT (room.c): done once the wall ahead is within front_stop_mm */
    r->in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(cfg, 110.0f);
    r->in.ir_mv[FFR_IR_RF] = rig_mv_for_mm(cfg, right_mm);
    r->in.ir_mv[FFR_IR_RR] = rig_mv_for_mm(cfg, right_mm);
    r->in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(cfg, left_mm);
    r->in.ir_mv[FFR_IR_LR] = rig_mv_for_mm(cfg, left_mm);
}

TEST(out_of_a_door_beside_a_hallways_end_the_walk_turns_away_from_it)
{
    /* out of a door the walk turns toward the followed side (right); with
     * that side's two corner rangers on a wall within the front corner's
     * turning circle (a door in a hallway's end) it turns left instead */
    static const struct {
        float right_mm, left_mm;
        float deg;
    } cases[] = {
        {226.0f, 226.0f, -90.0f}, /* a hallway's walls from its middle: toward the followed side */
        {120.0f, 226.0f, 90.0f},  /* the end wall along the right: away from it */
        {120.0f, 120.0f, -90.0f}, /* walls close both sides: as before */
        {170.0f, 226.0f, -90.0f}, /* beyond the turning circle: as before */
    };
    ffr_config_t cfg;
    rig_t r;
    unsigned i;
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        leaving_a_room(&r, &cfg, cases[i].right_mm, cases[i].left_mm);
        CHECK(r.st.explore.side == FFR_SIDE_RIGHT);
        CHECK(rig_run_until_state(&r, FFR_ST_TURN, 20));
        CHECK(r.st.explore.phase == 2u); /* EX_TURN, then the follow */
        CHECK_NEAR(r.st.explore.target_rad - r.st.route.heading_ref_rad, cases[i].deg * FFR_DEG, 1e-5);
        CHECK(ffr_explore_way_out(&r.st) == (int)cases[i].deg);
    }
}

/* In a hallway, the home circle's near side crossed, then a wall ahead
 * (the follow's turn into the crossing hallway, inside the circle), and the
 * circle's far side met while turning */
static void turning_in_the_home_circle(rig_t *r, const ffr_config_t *cfg)
{
    int i;
    started_in_a_hallway(r, cfg);
    rig_line(r, 5, 3);
    CHECK(r->st.explore.edge_mm > -1.0e8f); /* the near side: a line to pair */
    for (i = 0; i < 40; ++i) {
        rig_tick(r); /* on past the line counter's hold-off */
    }
    r->in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(cfg, 110.0f);
    r->in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(cfg, 600.0f); /* open on the left: a corner */
    r->in.ir_mv[FFR_IR_LR] = rig_mv_for_mm(cfg, 600.0f);
    CHECK(rig_run_until_state(r, FFR_ST_TURN, 40));
    CHECK(r->st.odo.dist_mm - r->st.explore.edge_mm < FFR_HOME_CHORD_MM);
    r->in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(cfg, 600.0f);
    CHECK(rig_run_until_state(r, FFR_ST_TURN, 3)); /* turning, not yet at the target */
}

TEST(the_home_circles_far_side_met_while_turning_in_it_is_home)
{
    ffr_config_t cfg;
    rig_t r;
    float target;
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;

    /* before the flame is out, a room searched on the loop: the walls change,
     * the turn goes on to its target */
    turning_in_the_home_circle(&r, &cfg);
    CHECK(r.st.explore.homes == 0u && r.st.explore.side == FFR_SIDE_RIGHT);
    r.st.rooms_searched = 1u;
    target = r.st.explore.target_rad;
    rig_line(&r, 0, 3);
    CHECK(r.st.explore.homes == 1u);
    CHECK(r.st.explore.flips == 1u && r.st.explore.side == FFR_SIDE_LEFT);
    CHECK(r.out.state == FFR_ST_TURN && r.st.explore.phase == 2u); /* EX_TURN */
    CHECK_NEAR(r.st.explore.target_rad, target, 0.0);

    /* with the flame out: home, the robot stops in the circle */
    turning_in_the_home_circle(&r, &cfg);
    r.st.flags |= FFR_FLAG_EXTINGUISHED;
    rig_line(&r, 0, 3);
    CHECK(r.st.explore.homes == 1u);
    CHECK(rig_run_until_state(&r, FFR_ST_DONE, 20));
    CHECK(r.out.flags & FFR_FLAG_DONE);
}

SUITE(explore,
      TEST_REF(the_home_circle_is_two_lines_a_chord_apart),
      TEST_REF(turn_targets_are_square_to_the_walls),
      TEST_REF(the_mode_switch_is_off_by_default),
      TEST_REF(in_a_hallway_it_follows_passes_home_and_stops_there_with_the_flame_out),
      TEST_REF(a_lone_line_on_the_way_home_turns_the_robot_round),
      TEST_REF(a_whole_opening_whose_middle_is_passed_is_backed_to_then_turned_into),
      TEST_REF(a_probe_that_finds_a_hallway_keeps_where_the_leg_began),
      TEST_REF(the_follow_holds_the_hallway_heading_within_ten_degrees),
      TEST_REF(a_wall_end_behind_where_the_leg_began_is_the_door_just_left),
      TEST_REF(a_narrow_openings_far_edge_seen_in_the_wrap_brings_the_turn_short_of_it),
      TEST_REF(a_straight_leg_is_trued_up_by_the_walls_beside),
      TEST_REF(every_straight_leg_of_the_explorer_is_trued_up_by_the_walls_beside),
      TEST_REF(a_loop_with_its_rooms_searched_and_no_flame_makes_the_next_rooms_searched_harder),
      TEST_REF(out_of_a_door_beside_a_hallways_end_the_walk_turns_away_from_it),
      TEST_REF(the_home_circles_far_side_met_while_turning_in_it_is_home));
