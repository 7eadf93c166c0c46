#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* the six cases of Fig. 9 and the turn each asks for */
TEST(the_six_cases_and_the_turn_each_asks_for)
{
    CHECK(ffr_wall_case(1, 1, 0) == FFR_CASE_CORNER_LEFT);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORNER_LEFT, FFR_SIDE_RIGHT) == 90);
    CHECK(ffr_wall_case(1, 0, 1) == FFR_CASE_CORNER_RIGHT);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORNER_RIGHT, FFR_SIDE_LEFT) == -90);
    CHECK(ffr_wall_case(1, 1, 1) == FFR_CASE_T);
    CHECK(ffr_wall_case_turn(FFR_CASE_T, FFR_SIDE_LEFT) == 90);
    CHECK(ffr_wall_case_turn(FFR_CASE_T, FFR_SIDE_RIGHT) == -90);
    CHECK(ffr_wall_case(1, 0, 0) == FFR_CASE_DEAD_END);
    CHECK(ffr_wall_case_turn(FFR_CASE_DEAD_END, FFR_SIDE_NONE) == 180);
    CHECK(ffr_wall_case(0, 1, 0) == FFR_CASE_BRANCH_LEFT);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_LEFT, FFR_SIDE_LEFT) == 90);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_LEFT, FFR_SIDE_NONE) == 0);
    CHECK(ffr_wall_case(0, 0, 1) == FFR_CASE_BRANCH_RIGHT);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_RIGHT, FFR_SIDE_RIGHT) == -90);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_RIGHT, FFR_SIDE_LEFT) == 0);
    CHECK(ffr_wall_case(0, 0, 0) == FFR_CASE_CORRIDOR);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORRIDOR, FFR_SIDE_LEFT) == 0);
    CHECK(ffr_wall_case(0, 1, 1) == FFR_CASE_OPEN);
}

TEST(the_case_sensed_from_the_rangers_and_the_openings)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_openings_t op;
    ffr_config_default(&cfg);
    /* sensed at a left corner: the front-left ranger now sees the wall
     * ahead, but the left wall was seen to end on the way in */
    rig_no_walls(&cfg, ir);
    ffr_openings_reset(&op);
    ir[FFR_IR_CF] = 130.0f;
    ir[FFR_IR_LF] = 212.0f;
    ir[FFR_IR_RF] = 212.0f;
    CHECK(ffr_wall_case_sensed(&cfg, ir, &op) == FFR_CASE_DEAD_END);
    op.since_open_mm[FFR_SIDE_LEFT] = 150.0f;
    CHECK(ffr_wall_case_sensed(&cfg, ir, &op) == FFR_CASE_CORNER_LEFT);
    /* open long ago (further back than a hallway is wide): a dead end */
    op.since_open_mm[FFR_SIDE_LEFT] = 900.0f;
    CHECK(ffr_wall_case_sensed(&cfg, ir, &op) == FFR_CASE_DEAD_END);
    /* a side seeing nothing at all is open too */
    ffr_openings_reset(&op);
    ir[FFR_IR_RF] = FFR_IR_NONE(&cfg);
    CHECK(ffr_wall_case_sensed(&cfg, ir, &op) == FFR_CASE_CORNER_RIGHT);
}

SUITE(wall_cases,
      TEST_REF(the_six_cases_and_the_turn_each_asks_for),
      TEST_REF(the_case_sensed_from_the_rangers_and_the_openings));
