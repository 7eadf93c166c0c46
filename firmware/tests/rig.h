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
/* `before` ticks on black floor, then a white line under the sensor for `on` ticks */
void rig_line(rig_t *r, int before, int on);
/* A route that searches room 1 (ROOM 1, END) and, with `home`, its way home:
 * HOME with no wall to follow */
void rig_room_route(ffr_config_t *cfg, int home);
/* The rangers' hit points for readings ir_mm, as ffr_step works them out
 * (the beam directions from cfg, then the hits); returns g. */
const ffr_ir_geom_t *rig_geom(ffr_ir_geom_t *g, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT]);
/* openings.c alone: `ticks` ticks of 3 mm travel from *d with these ranges */
void rig_travel(ffr_openings_t *op, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float *d, int ticks);
/* the same in a route step following to pend_side's opening (-1: none) */
void rig_travel_pend(ffr_openings_t *op, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float *d,
                     int ticks, int pend_side);
/* Straight walls around a true pose, for the rangers' readings in closed-loop tests. */
typedef struct {
    float left_y, right_y;   /* hallway walls along x: y = left_y (> 0), y = right_y (< 0) */
    float ahead_x;           /* a wall across at x = ahead_x (0: none)                     */
    float jog_x, jog_dy;     /* the right wall steps out by jog_dy beyond x = jog_x (0: none) */
    float part_mm[FFR_IR_COUNT]; /* each part reads this much long (mm along its beam)      */
} rig_walls_t;

/* Distance along ranger i's beam to the nearest wall from the true pose (x, y mm,
 * th rad), the part's error added; FFR_IR_NONE past the valid range. */
/* ranger i's mount (mx, my) and unit beam (ux, uy) in the world, robot at (x, y, th) */
void rig_ray(const ffr_config_t *cfg, int i, float x, float y, float th, float *mx, float *my, float *ux,
             float *uy);
float rig_beam_mm(const ffr_config_t *cfg, const rig_walls_t *w, int i, float x, float y, float th);
/* tick until the firmware reports `state`; 0 if it does not within max_ticks */
int rig_run_until_state(rig_t *r, uint8_t state, int max_ticks);
/* tick until the robot drives forward (a turn in place has ended) */
int rig_run_until_driving(rig_t *r, int max_ticks);
#endif
