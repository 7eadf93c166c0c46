/*
 * A test rig for the whole firmware with plain inputs (Grenning's spy
 * actuators): a fake drive turns each wheel's encoder in proportion to its
 * PWM; rangers, line and flame readings are set by the test.
 */
#ifndef FFR_TEST_RIG_H
#define FFR_TEST_RIG_H
#include "ffr_internal.h"

typedef struct {
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    float enc_f[2];
} rig_t;

/* the GP2D12 reading (mV) for a wall mm away, by the firmware's own fit */
uint16_t rig_mv_for_mm(const ffr_config_t *cfg, float mm);
/* every ranger reads "no wall in range" */
void rig_no_walls(const ffr_config_t *cfg, float ir_mm[FFR_IR_COUNT]);
/* nothing in range, dark flame sensors, black floor, no start signal */
void rig_init(rig_t *r, const ffr_config_t *cfg);
/* one tick; checks the sequence number is echoed */
void rig_tick(rig_t *r);
/* tick until the firmware reports `state`; 0 if it does not within max_ticks */
int rig_run_until_state(rig_t *r, uint8_t state, int max_ticks);
/* tick until the robot drives forward (a turn in place has ended) */
int rig_run_until_driving(rig_t *r, int max_ticks);
#endif
