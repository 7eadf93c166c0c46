/* Minimal unit-test support for the firmware's host tests. */
#ifndef FFR_UNIT_H
#define FFR_UNIT_H
#include <stdio.h>

typedef struct {
    int passed;
    int failed;
} unit_tally_t;

extern unit_tally_t unit_tally;

#define CHECK(cond)                                                                    \
    do {                                                                               \
        if (cond) {                                                                    \
            unit_tally.passed++;                                                       \
        } else {                                                                       \
            unit_tally.failed++;                                                       \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                     \
        }                                                                              \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                          \
    do {                                                                               \
        double a_ = (double)(a), b_ = (double)(b);                                     \
        if (a_ - b_ <= (double)(tol) && b_ - a_ <= (double)(tol)) {                    \
            unit_tally.passed++;                                                       \
        } else {                                                                       \
            unit_tally.failed++;                                                       \
            printf("FAIL %s:%d: %s = %g, want %g +- %g\n", __FILE__, __LINE__, #a, a_, b_, \
                   (double)(tol));                                                     \
        }                                                                              \
    } while (0)

void suite_fmath(void);
void suite_ir_calibration(void);
void suite_odometry(void);
void suite_speed_control(void);
void suite_wall_follow(void);
void suite_wall_cases(void);
void suite_wall_calibration(void);
void suite_wall_direction(void);
void suite_line_counter(void);
void suite_openings(void);
void suite_mission(void);
void suite_layout(void);
void suite_robustness(void);
void suite_home_orient(void);
void suite_turn_calibration(void);
void suite_turn_room(void);
#endif
