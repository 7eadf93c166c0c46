/*
 * Self-test: step the firmware through a deterministic synthetic mission
 * (a fake drive that turns the wheels in proportion to the PWM, rangers and
 * flame readings from a fixed generator) and fold every output into an
 * FNV-1a checksum. Built for the host and for each board, the checksums must
 * be equal: the same sources give the same bits on both.
 */
#ifndef FFR_SELFTEST_H
#define FFR_SELFTEST_H
#include <stdint.h>

typedef struct {
    uint32_t ticks;
    uint32_t checksum;
    int16_t last_pwm[2];
    uint8_t last_state;
    uint32_t clock_sum; /* with a clock: sum and worst of its counts per ffr_step */
    uint32_t clock_max;
} ffr_selftest_result_t;

/* `clock` (may be NULL) returns a free-running up-counter, 24 bits wide, read
 * around every ffr_step to profile it. */
void ffr_selftest_run(uint32_t ticks, uint32_t (*clock)(void), ffr_selftest_result_t *res);
/* "ffr-selftest ticks=N checksum=XXXXXXXX state=S" into buf (>= 64 bytes) */
void ffr_selftest_format(const ffr_selftest_result_t *res, char *buf);
#endif
