/*
 * Minimal unit-test support for the firmware's host tests (our own, in the
 * spirit of Grenning's TEST_GROUP/TEST): every test is a named function
 * that builds its own fixture (no state is shared between tests), each
 * file lists its tests in one SUITE, and main.c runs the suites (with the
 * runner in unit_runner.c, which the wire tests' main.c uses too). A failed
 * check prints file:line, suite.test and the expression.
 *
 *   TEST(a_quarter_turn_is_a_quarter_turn)
 *   {
 *       ffr_config_t cfg;
 *       ffr_config_default(&cfg);
 *       CHECK(...);
 *   }
 *   SUITE(odometry, TEST_REF(a_quarter_turn_is_a_quarter_turn), ...);
 *
 * A test that makes no check at all fails: a test must assert something.
 */
#ifndef FFR_UNIT_H
#define FFR_UNIT_H
#include <stdio.h>

typedef struct {
    int passed;        /* checks */
    int failed;
    const char *suite; /* the test running now (NULL outside a test) */
    const char *test;
} unit_tally_t;

extern unit_tally_t unit_tally;

typedef struct {
    const char *name;
    void (*run)(void);
} unit_test_t;

typedef struct {
    const char *name;
    const unit_test_t *tests;
    int count;
} unit_suite_t;

/* A test: a function of its own (its fixture is its locals). */
#define TEST(name) static void name(void)
/* A test's entry in its file's SUITE. */
#define TEST_REF(name) {#name, name}
/* The file's suite: suite_<sname>, its tests in the order they run. */
#define SUITE(sname, ...)                                                              \
    static const unit_test_t sname##_tests_[] = {__VA_ARGS__};                         \
    const unit_suite_t suite_##sname = {#sname, sname##_tests_,                        \
                                        (int)(sizeof(sname##_tests_) / sizeof(sname##_tests_[0]))}

/* where a failure is: file:line, then suite.test when a test is running */
#define UNIT_WHERE_()                                                                  \
    do {                                                                               \
        printf("FAIL %s:%d: ", __FILE__, __LINE__);                                    \
        if (unit_tally.test != NULL) {                                                 \
            printf("%s.%s: ", unit_tally.suite, unit_tally.test);                      \
        }                                                                              \
    } while (0)

#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (cond) {                                                                    \
            unit_tally.passed++;                                                       \
        } else {                                                                       \
            unit_tally.failed++;                                                       \
            UNIT_WHERE_();                                                             \
            printf("%s\n", #cond);                                                     \
        }                                                                              \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                          \
    do {                                                                               \
        double a_ = (double)(a), b_ = (double)(b);                                     \
        if (a_ - b_ <= (double)(tol) && b_ - a_ <= (double)(tol)) {                    \
            unit_tally.passed++;                                                       \
        } else {                                                                       \
            unit_tally.failed++;                                                       \
            UNIT_WHERE_();                                                             \
            printf("%s = %g, want %g +- %g\n", #a, a_, b_, (double)(tol));             \
        }                                                                              \
    } while (0)

/* The runner (unit_runner.c): runs the suites as argv asks (NAME..., --list,
 * --demo-failure runs demo), prints "label: N suites, N tests (N failed), N checks
 * passed, N failed" and returns the exit status. */
int unit_run(const char *label, const unit_suite_t *const *suites, int n_suites, const unit_suite_t *demo,
             int argc, char **argv);

extern const unit_suite_t suite_fmath;
extern const unit_suite_t suite_ir_calibration;
extern const unit_suite_t suite_odometry;
extern const unit_suite_t suite_speed_control;
extern const unit_suite_t suite_wall_follow;
extern const unit_suite_t suite_wall_cases;
extern const unit_suite_t suite_wall_calibration;
extern const unit_suite_t suite_wall_direction;
extern const unit_suite_t suite_line_counter;
extern const unit_suite_t suite_openings;
extern const unit_suite_t suite_mission;
extern const unit_suite_t suite_layout;
extern const unit_suite_t suite_robustness;
extern const unit_suite_t suite_home_orient;
extern const unit_suite_t suite_turn_calibration;
extern const unit_suite_t suite_turn_room;
extern const unit_suite_t suite_room_guards;
extern const unit_suite_t suite_room;
extern const unit_suite_t suite_obstacle_avoid;
extern const unit_suite_t suite_explore;
#endif
