/*
 * The firmware's C unit tests: every suite's tests, one after another.
 *   ffr_unit_tests              run them all
 *   ffr_unit_tests NAME...      only the suites or tests named (suite or suite.test)
 *   ffr_unit_tests --list       print suite.test for every test
 *   ffr_unit_tests --demo-failure  run one test that fails on purpose (how a failure reads)
 * The last line counts suites, tests and checks (tests/firmware/test_c_units.py
 * asserts the exact numbers).
 */
#include <string.h>

#include "unit.h"

unit_tally_t unit_tally;

static const unit_suite_t *const k_suites[] = {
    &suite_fmath,          &suite_ir_calibration,   &suite_odometry,       &suite_speed_control,
    &suite_wall_follow,    &suite_wall_cases,       &suite_wall_calibration, &suite_wall_direction,
    &suite_line_counter,   &suite_openings,         &suite_mission,        &suite_layout,
    &suite_robustness,     &suite_home_orient,      &suite_turn_calibration, &suite_turn_room,
    &suite_room_guards,    &suite_room,
};

TEST(a_check_that_fails_on_purpose) { CHECK(1 + 1 == 3); }
SUITE(unit_demo, TEST_REF(a_check_that_fails_on_purpose));

/* Is test t of suite s among the names given (none: all)? */
static int selected(const unit_suite_t *s, const unit_test_t *t, int argc, char **argv)
{
    int i;
    if (argc <= 1) {
        return 1;
    }
    for (i = 1; i < argc; ++i) {
        size_t n = strlen(s->name);
        if (strcmp(argv[i], s->name) == 0
            || (strncmp(argv[i], s->name, n) == 0 && argv[i][n] == '.' && strcmp(argv[i] + n + 1, t->name) == 0)) {
            return 1;
        }
    }
    return 0;
}

/* Runs one test; 1 if it failed (a failed check, or no check at all). */
static int run_test(const unit_suite_t *s, const unit_test_t *t)
{
    int passed = unit_tally.passed;
    int failed = unit_tally.failed;
    unit_tally.suite = s->name;
    unit_tally.test = t->name;
    t->run();
    if (unit_tally.passed == passed && unit_tally.failed == failed) {
        printf("FAIL %s.%s: the test made no check\n", s->name, t->name);
        unit_tally.failed++;
    }
    unit_tally.suite = NULL;
    unit_tally.test = NULL;
    return unit_tally.failed != failed;
}

int main(int argc, char **argv)
{
    const int n_suites = (int)(sizeof(k_suites) / sizeof(k_suites[0]));
    int suites = 0, tests = 0, tests_failed = 0;
    int i, k;
    if (argc == 2 && strcmp(argv[1], "--demo-failure") == 0) {
        tests_failed = run_test(&suite_unit_demo, &suite_unit_demo.tests[0]);
        printf("firmware: 1 suites, 1 tests (%d failed), %d checks passed, %d failed\n", tests_failed,
               unit_tally.passed, unit_tally.failed);
        return tests_failed ? 1 : 0;
    }
    if (argc == 2 && strcmp(argv[1], "--list") == 0) {
        for (i = 0; i < n_suites; ++i) {
            for (k = 0; k < k_suites[i]->count; ++k) {
                printf("%s.%s\n", k_suites[i]->name, k_suites[i]->tests[k].name);
            }
        }
        return 0;
    }
    for (i = 0; i < n_suites; ++i) {
        const unit_suite_t *s = k_suites[i];
        int ran = 0;
        for (k = 0; k < s->count; ++k) {
            if (selected(s, &s->tests[k], argc, argv)) {
                tests_failed += run_test(s, &s->tests[k]);
                ++tests;
                ran = 1;
            }
        }
        suites += ran;
    }
    printf("firmware: %d suites, %d tests (%d failed), %d checks passed, %d failed\n", suites, tests,
           tests_failed, unit_tally.passed, unit_tally.failed);
    return unit_tally.failed == 0 && tests > 0 ? 0 : 1;
}
