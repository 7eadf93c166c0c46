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
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;
    started_in_a_hallway(&r, &cfg);
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.out.step == 0); /* the explorer's phase: follow */
    CHECK(r.st.explore.side == FFR_SIDE_RIGHT);
    CHECK(r.out.pwm[0] > 100 && r.out.pwm[1] > 100);

    /* the home circle crossed before the flame is out: counted, the walk goes
     * on (no room searched yet: the same wall) */
    rig_line(&r, 5, 3);
    rig_line(&r, 40, 3);
    rig_tick(&r);
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
    ffr_config_default(&cfg);
    cfg.start_area = FFR_START_HALLWAY;
    started_in_a_hallway(&r, &cfg);
    r.st.flags |= FFR_FLAG_EXTINGUISHED;
    rig_line(&r, 5, 3);
    /* a doorway's line crossed straight: past a circle's chord with no second
     * line, the robot turns round (half a turn, square) */
    CHECK(rig_run_until_state(&r, FFR_ST_TURN, 400));
    CHECK_NEAR(r.st.explore.target_rad - r.st.route.heading_ref_rad, FFR_PI, 1e-5);
    CHECK(!(r.out.flags & FFR_FLAG_DONE));
}

SUITE(explore,
      TEST_REF(the_home_circle_is_two_lines_a_chord_apart),
      TEST_REF(turn_targets_are_square_to_the_walls),
      TEST_REF(the_mode_switch_is_off_by_default),
      TEST_REF(in_a_hallway_it_follows_passes_home_and_stops_there_with_the_flame_out),
      TEST_REF(a_lone_line_on_the_way_home_turns_the_robot_round));
