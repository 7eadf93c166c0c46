/*
 * The firmware's C unit tests: every suite's tests, one after another.
 *   ffr_unit_tests              run them all
 *   ffr_unit_tests NAME...      only the suites or tests named (suite or suite.test)
 *   ffr_unit_tests --list       print suite.test for every test
 *   ffr_unit_tests --demo-failure  run one test that fails on purpose (how a failure reads)
 * The last line counts suites, tests and checks (tests/firmware/test_c_units.py
 * asserts the exact numbers). The runner is unit_runner.c (shared with the wire tests).
 */
#include "unit.h"

static const unit_suite_t *const k_suites[] = {
    &suite_fmath,          &suite_ir_calibration,   &suite_odometry,       &suite_speed_control,
    &suite_wall_follow,    &suite_wall_cases,       &suite_wall_calibration, &suite_wall_direction,
    &suite_line_counter,   &suite_openings,         &suite_mission,        &suite_layout,
    &suite_robustness,     &suite_home_orient,      &suite_turn_calibration, &suite_turn_room,
    &suite_room_guards,    &suite_room,             &suite_obstacle_avoid,
    &suite_explore,
};

TEST(a_check_that_fails_on_purpose) { CHECK(1 + 1 == 3); }
SUITE(unit_demo, TEST_REF(a_check_that_fails_on_purpose));

int main(int argc, char **argv)
{
    return unit_run("firmware", k_suites, (int)(sizeof(k_suites) / sizeof(k_suites[0])), &suite_unit_demo, argc,
                    argv);
}
