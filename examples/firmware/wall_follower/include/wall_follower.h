/*
 * wall_follower.h - a small, table-driven left-hand wall follower that meets
 * ffr's firmware contract (ffr_contract.h, version 2). It is the example a
 * team copies: its own configuration and state, nothing from ffr's firmware.
 *
 * Behaviour (README.md): turn to put a wall on the left, follow it; entering
 * a room (doorway lines alternate in, out), scan a full turn with the flame
 * sensors; a flame seen: aim, approach, fans on until it is out; then back
 * along the other wall (the way in, backwards) past as many doorways as it
 * came through: the next line is home's ring; stop inside it.
 *
 * C99, no heap, no mutable globals, float only; all state in the caller's
 * struct ffr_state. Hardware units in, hardware units out.
 */
#ifndef WALL_FOLLOWER_H
#define WALL_FOLLOWER_H

#include <stdint.h>

#include "ffr_contract.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WF_NAME "wall_follower 0.1"
#define WF_IR_WINDOW 9 /* ticks of each ranger's median filter (sense.c) */
#define WF_LINE_TICKS 3 /* ticks a line reading must last (sense.c) */

/* Configuration: the first block carries the names ffr writes the robot's
 * calibration into (docs/contract.md); the rest is this firmware's own. */
struct ffr_config {
    float wheel_radius_mm;
    float track_width_mm;
    float encoder_ticks_per_rev;
    float body_front_mm;
    float body_half_width_mm;
    float ir_x_mm[FFR_IR_COUNT];
    float ir_y_mm[FFR_IR_COUNT];
    float ir_angle_deg[FFR_IR_COUNT];
    float line_sensor_x_mm;
    float ir_k_mv_mm;            /* GP2D12: d = k / (mV - offset) - d0        */
    float ir_offset_mv;
    float ir_d0_mm;

    float ir_max_mm;             /* farther than this: nothing seen            */
    float cruise_mm_s;           /* wall following speed                       */
    float approach_mm_s;         /* towards the flame                          */
    float turn_deg_s;            /* turns in place                             */
    float scan_deg_s;            /* the flame scan's rotation rate             */
    float accel_mm_s2;           /* wheel speed ramp                           */
    float pwm_per_mm_s;          /* motor feed-forward, per mille per mm/s     */
    float pwm_offset;            /* per mille to get a wheel moving            */
    float pwm_kp;                /* per mille per mm/s of speed error          */
    float wall_mm;               /* wanted distance: robot origin to the left wall */
    float wall_kp;               /* yaw rate (deg/s) per mm of distance error  */
    float angle_kp;              /* yaw rate (deg/s) per degree of wall angle  */
    float heading_kp;            /* yaw rate (deg/s) per degree of heading error */
    float heading_learn;         /* per tick, how much a straight wall corrects odometry's heading (0: never) */
    float max_yaw_deg_s;         /* clamp of the following's yaw rate          */
    float front_mm;              /* CF closer than this: a wall ahead, turn right */
    float open_mm;               /* LF farther than this: the left wall ends   */
    float corner_mm;             /* straight on this far past a wall's end, then arc */
    float arc_max_deg;           /* arc this far with no wall: open floor      */
    float start_turn_deg;        /* at home, turn this much first (+ = left)   */
    float entry_mm;              /* past a line this far, then scan            */
    float line_holdoff_mm;       /* a line within this travel of the last is the same one */
    float flame_detect;          /* counts, both sensors: a flame seen         */
    float flame_near;            /* counts, both sensors: close enough for the fans */
    float flame_out;             /* counts, both sensors: below this it is out */
    float out_fraction;          /* or below this fraction of its brightness when the fans started */
    float flame_steer_deg_s;     /* yaw rate for a full left/right imbalance   */
    float approach_stop_mm;      /* CF closer than this: stop approaching      */
    float guard_mm;              /* approaching, LF or RF closer than this: steer off */
    float guard_kp;              /* yaw rate (deg/s) per mm inside guard_mm    */
    float home_zone_mm;          /* a line this near the start (odometry) is home's circle */
    float away_mm;               /* ... once the robot was this far away       */
    uint32_t out_confirm_ms;     /* flame below flame_out this long: out       */
    uint32_t fan_max_ms;         /* fans on at most this long                  */
    uint32_t mission_max_ms;     /* give up after this long                    */
    uint8_t scan_attempts;       /* rescans when the flame is lost             */
    uint8_t reserved[3];
};

/* Behaviour states: outputs.state, and the index of ffr_names(FFR_NAMES_STATE). */
typedef enum {
    WF_IDLE = 0,
    WF_START_TURN,
    WF_FOLLOW,
    WF_CORNER,
    WF_ARC,
    WF_TURN_AWAY,
    WF_FIND_WALL,
    WF_SCAN,
    WF_AIM,
    WF_APPROACH,
    WF_EXTINGUISH,
    WF_GOTO,
    WF_RESUME,
    WF_HOME,
    WF_DONE,
    WF_FAILED,
    WF_STATE_COUNT
} wf_state_code_t;

/* Events a handler returns; the state table maps (state, event) to the next state. */
typedef enum {
    WF_EV_NONE = 0,   /* stay                                      */
    WF_EV_DONE,       /* the behaviour finished                    */
    WF_EV_FRONT,      /* a wall ahead                              */
    WF_EV_OPEN,       /* the left wall ended                       */
    WF_EV_WALL,       /* a wall found on the left                  */
    WF_EV_LINE,       /* time to scan (a line, then entry_mm)      */
    WF_EV_FLAME,      /* the scan saw a flame                      */
    WF_EV_NO_FLAME,   /* the scan saw none                         */
    WF_EV_NEAR,       /* close enough for the fans                 */
    WF_EV_LOST,       /* the flame went out of view                */
    WF_EV_OUT,        /* the flame is out                          */
    WF_EV_HOME,       /* home's circle reached                     */
    WF_EV_FAIL,       /* give up (fail_code says why)              */
    WF_EV_COUNT
} wf_event_t;

/* outputs.fail_code, and the index of ffr_names(FFR_NAMES_FAIL). */
typedef enum {
    WF_FAIL_NONE = 0,
    WF_FAIL_NO_FLAME,  /* back home, no flame seen on the way      */
    WF_FAIL_NOT_OUT,   /* the fans ran fan_max_ms, flame still lit */
    WF_FAIL_LOST,      /* the flame lost scan_attempts times       */
    WF_FAIL_TIMEOUT,   /* mission_max_ms passed                    */
    WF_FAIL_COUNT
} wf_fail_t;

/* What the sensors say this tick, in mm and counts (sense.c). */
typedef struct {
    float ir_mm[FFR_IR_COUNT];   /* range along each beam, ir_max_mm + 1: none */
    float side_front_mm;         /* the followed side's front ranger (LF or RF) */
    float side_hit_x_mm;         /* where it meets the wall: ahead of the origin */
    float side_hit_y_mm;         /* and to the followed side                   */
    uint8_t side_ok;             /* both rangers of the followed side see a wall */
    float side_mm;               /* origin to that wall's line                 */
    float side_deg;              /* its angle to the heading (+: it turns away from the robot) */
    float flame_sum;             /* both flame sensors, counts                 */
    float flame_diff;            /* left - right, counts                       */
    uint8_t line_edge;           /* a new white line under the sensor          */
} wf_sense_t;

struct ffr_state {
    struct ffr_config cfg;
    /* odometry */
    int32_t last_enc[2];
    uint8_t primed;
    uint8_t state;               /* wf_state_code_t                            */
    uint8_t resume_state;        /* where a scan returns to                    */
    uint8_t flags;
    uint8_t fail_code;
    uint8_t fan;
    uint8_t line_level;
    uint8_t attempts;
    uint8_t lines;               /* white lines crossed                        */
    uint8_t rooms;               /* scans made                                 */
    uint8_t doors;               /* doorway lines crossed (odd: in a room)     */
    uint8_t prev_state;          /* the state before this one                  */
    uint8_t home_phase;          /* HOME: 0 across the circle, 1 back to the chord's middle */
    uint8_t ir_pos;              /* where the next tick goes in ir_hist        */
    uint8_t ir_primed;           /* ir_hist filled by the first tick           */
    uint8_t line_run;            /* ticks the line sensor has read other than line_level */
    uint8_t doors_at_scan;       /* doorway lines crossed before the scan that saw the flame */
    uint8_t doors_back;          /* and since, on the way back                 */

    uint16_t ir_hist[FFR_IR_COUNT][WF_IR_WINDOW]; /* each ranger's last ticks (a ring) */
    uint16_t flame_hist[2][3];   /* each flame sensor's last three ticks       */
    float x_mm, y_mm, heading_rad;
    float dist_mm;               /* path length                                */
    float v_mm_s[2];             /* measured wheel speeds, filtered            */
    float v_ref[2];              /* ramped wheel speed references              */
    /* the current behaviour */
    uint32_t t_ms;
    uint32_t entered_ms;         /* when the state was entered                 */
    uint32_t below_ms;           /* since when the flame reads out             */
    float entered_mm;            /* dist_mm when the state was entered         */
    float entered_rad;           /* heading when the state was entered         */
    float target_rad;            /* turn target                                */
    float scan_at_mm;            /* a scan is due at this distance (< 0: none) */
    float last_line_mm;          /* dist_mm of the last white line             */
    float resume_rad;            /* heading to turn back to after a scan       */
    float best_sum;              /* the scan's brightest reading               */
    float best_rad;              /* and its heading                            */
    float flame_ref;             /* the flame's brightness when the fans started */
    float max_away_mm;           /* farthest from the start so far             */
    float scan_x_mm, scan_y_mm;  /* where the scan was made (odometry)         */
    float goal_x_mm, goal_y_mm;  /* where GOTO and HOME drive to               */
    float follow_from_mm;        /* dist_mm where following this wall began    */
    float scan_dist_mm;          /* dist_mm at the last scan                   */
    float pending_run_mm;        /* back from a flame: the wall's run ahead (< 0: none) */
    float end_at_mm;             /* dist_mm where the robot is abreast of the wall's last seen point */
    float side;                  /* +1: follow the left wall, -1: the right (the way back) */
    float cmd_v;                 /* this tick's command: mm/s, rad/s           */
    float cmd_w;
};

/* One row of the state table (states.c): what to do on entry, what to do
 * each tick (returns an event), and where each event leads (WF_IDLE = no
 * transition: the event is ignored in this state). */
typedef struct {
    void (*entry)(ffr_state_t *st);
    wf_event_t (*tick)(ffr_state_t *st, const wf_sense_t *s);
    uint8_t next[WF_EV_COUNT];
} wf_state_row_t;

/* Internals shared by the source files (and the unit tests). */
const wf_state_row_t *wf_state_table(void);
const char *const *wf_state_names(void);
void wf_sense(ffr_state_t *st, const ffr_inputs_t *in, wf_sense_t *s);
float wf_ir_mm(const struct ffr_config *c, uint16_t mv);
void wf_odometry(ffr_state_t *st, const int32_t enc[2]);
void wf_drive(ffr_state_t *st, float v_mm_s, float w_rad_s, int16_t pwm[2]);
float wf_wrap(float a);
void wf_enter(ffr_state_t *st, uint8_t state);
float wf_sqrt(float x);
float wf_atan2(float y, float x);
float wf_sin(float a);
float wf_cos(float a);

#define WF_PI 3.14159265f
#define WF_DEG (WF_PI / 180.0f)
#define WF_RESUME_PREV 255u /* a next-state value: back to the state a scan interrupted */

#ifdef __cplusplus
}
#endif
#endif /* WALL_FOLLOWER_H */
