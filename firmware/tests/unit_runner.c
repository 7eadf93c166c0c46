/*
 * The one runner of the C test programs (the firmware's unit tests,
 * firmware/tests/main.c, and the wire tests, firmware/tests/wire/main.c):
 *   PROGRAM                 run every suite's tests
 *   PROGRAM NAME...         only the suites or tests named (suite or suite.test)
 *   PROGRAM --list          print suite.test for every test
 *   PROGRAM --demo-failure  run the program's demo test, which fails on purpose
 * The last line counts suites, tests and checks; pytest asserts the exact numbers.
 */
#include <string.h>

#include "unit.h"

unit_tally_t unit_tally;

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

int unit_run(const char *label, const unit_suite_t *const *suites, int n_suites, const unit_suite_t *demo,
             int argc, char **argv)
{
    int n_run = 0, tests = 0, tests_failed = 0;
    int i, k;
    if (argc == 2 && strcmp(argv[1], "--demo-failure") == 0) {
        tests_failed = run_test(demo, &demo->tests[0]);
        printf("%s: 1 suites, 1 tests (%d failed), %d checks passed, %d failed\n", label, tests_failed,
               unit_tally.passed, unit_tally.failed);
        return tests_failed ? 1 : 0;
    }
    if (argc == 2 && strcmp(argv[1], "--list") == 0) {
        for (i = 0; i < n_suites; ++i) {
            for (k = 0; k < suites[i]->count; ++k) {
                printf("%s.%s\n", suites[i]->name, suites[i]->tests[k].name);
            }
        }
        return 0;
    }
    for (i = 0; i < n_suites; ++i) {
        const unit_suite_t *s = suites[i];
        int ran = 0;
        for (k = 0; k < s->count; ++k) {
            if (selected(s, &s->tests[k], argc, argv)) {
                tests_failed += run_test(s, &s->tests[k]);
                ++tests;
                ran = 1;
            }
        }
        n_run += ran;
    }
    printf("%s: %d suites, %d tests (%d failed), %d checks passed, %d failed\n", label, n_run, tests,
           tests_failed, unit_tally.passed, unit_tally.failed);
    return unit_tally.failed == 0 && tests > 0 ? 0 : 1;
}
