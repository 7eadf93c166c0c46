/*
 * ffr.h - public API of the fire-fighting robot navigation firmware.
 *
 * Portable C99: no heap, no mutable globals, single-precision float, no
 * platform headers. All state lives in a caller-owned ffr_state_t; the
 * firmware sees only hardware units (mV, ADC counts, encoder counts, ms).
 *
 *   ffr_config_default(&cfg);       // documented defaults, then tune
 *   ffr_init(&st, &cfg);
 *   every tick: fill ffr_inputs_t, ffr_step(&st, &in, &out), apply out.
 *
 * The I/O structs, the layout self-description and the functions every
 * firmware exports are the contract's (ffr_contract.h, docs/contract.md);
 * this header completes our own configuration and state and adds our extras.
 */
#ifndef FFR_H
#define FFR_H

#include <stdint.h>

#include "ffr_contract.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Our firmware's name and release (ffr_firmware_name()); ffr_version() is the
 * contract's version (ffr_contract.h). */
#define FFR_FIRMWARE_NAME "ffr-reference 1.1"

/* The IR rangers' order (FFR_IR_CF ...) is the contract's (the paper's Fig. 6). */
enum { FFR_LEFT = 0, FFR_RIGHT = 1 };

/* ------------------------------------------------------------------ */
/* Route program: how the robot gets from room to room, by its sensors. */
/* ------------------------------------------------------------------ */

typedef enum {
    FFR_OP_END = 0,     /* end of program                                          */
    FFR_OP_FOLLOW = 1,  /* drive, following the wall on `side`, until `event`      */
    FFR_OP_TURN = 2,    /* turn in place by odometry: param = degrees, + = left    */
    FFR_OP_FORWARD = 3, /* drive param mm by odometry, following the wall on side  */
    FFR_OP_ROOM = 4,    /* enter the door ahead, scan, put out or leave: param=room */
    FFR_OP_HOME = 5     /* drive (following side) to the home circle and stop in it */
} ffr_op_t;

typedef enum {
    FFR_SIDE_LEFT = 0,
    FFR_SIDE_RIGHT = 1,
    FFR_SIDE_NONE = 2 /* hold heading by odometry */
} ffr_side_t;

typedef enum {
    FFR_EV_FRONT = 0,  /* wall ahead closer than front_stop_mm                  */
    FFR_EV_OPEN_L = 1, /* the left wall ends (a wall seen, then an opening)     */
    FFR_EV_OPEN_R = 2, /* the right wall ends                                   */
    FFR_EV_LINE = 3,   /* a white line under the line sensor                    */
    FFR_EV_GAP_L = 4,  /* the arg-th opening on the left (0 = the first), seen
                        * whole: open, then a wall again; the robot goes on to
                        * half a hallway before its far edge (openings.c)      */
    FFR_EV_GAP_R = 5   /* the same on the right                                 */
} ffr_event_t;

typedef struct {
    uint8_t op;     /* ffr_op_t                       */
    uint8_t side;   /* ffr_side_t (FOLLOW, FORWARD, HOME) */
    uint8_t event;  /* ffr_event_t (FOLLOW)           */
    uint8_t arg;    /* room number for ROOM; n-th opening for GAP_L/R (0 = 1st) */
    int16_t param;  /* degrees (TURN), mm (FORWARD)   */
    int16_t reserved;
} ffr_step_t;

#define FFR_ROUTE_MAX 48

/* ffr_config_t.home_wall_side */
enum { FFR_HOME_WALL_LEFT = 0, FFR_HOME_WALL_RIGHT = 1, FFR_HOME_WALL_ANY = 2, FFR_HOME_AS_PLACED = 3 };
/* ffr_config_t.start_area: where the team places the robot (the contest's
 * modes; the team knows which it runs): at home, the route program; anywhere
 * in a hallway (the arbitrary start mode), the explorer (explore.c) */
enum { FFR_START_HOME = 0, FFR_START_HALLWAY = 1 };
#define FFR_ROOMS_MAX 4

/* ------------------------------------------------------------------ */
/* Configuration: everything a student would tune.                      */
/* ------------------------------------------------------------------ */
struct ffr_config {
    /* geometry */
    float wheel_radius_mm;       /* drive wheel (sprocket) radius            */
    float track_width_mm;        /* distance between the drive wheels        */
    float encoder_ticks_per_rev; /* encoder counts per wheel revolution      */
    float body_front_mm;         /* origin (axle midpoint) to front face     */
    float body_half_width_mm;
    float ir_x_mm[FFR_IR_COUNT]; /* ranger poses in the body frame           */
    float ir_y_mm[FFR_IR_COUNT];
    float ir_angle_deg[FFR_IR_COUNT];
    float line_sensor_x_mm;      /* line sensor ahead of the origin          */

    /* GP2D12 inverse calibration: d = k / (mV - offset) - d0, valid range */
    float ir_k_mv_mm;
    float ir_offset_mv;
    float ir_d0_mm;
    float ir_min_mm;
    float ir_max_mm;
    float ir_min_mv;             /* below this the ranger sees nothing        */

    /* motor speed control: pwm = ff_gain*v + ff_offset + kp*e + ki*integral */
    float ff_gain_permille_per_mm_s;
    float ff_offset_permille;
    float speed_kp;              /* per mille per mm/s                         */
    float speed_ki;              /* per mille per mm of position error          */
    float accel_mm_s2;           /* speed ramp                                 */
    int16_t pwm_limit;           /* per mille                                  */
    int16_t reserved0;

    /* speeds */
    float cruise_speed_mm_s;
    float room_speed_mm_s;       /* entering, leaving, moving inside rooms     */
    float approach_speed_mm_s;
    float turn_rate_deg_s;
    float scan_rate_deg_s;

    /* corridor navigation */
    float wall_target_mm;        /* wanted distance origin -> followed wall    */
    float wall_kp_deg_per_mm;    /* heading offset per mm of distance error    */
    float wall_max_deg;          /* clamp of that offset                       */
    float heading_kp;            /* yaw rate (deg/s) per deg of heading error  */
    float wall_align_gain;       /* 0..1, how fast the wall corrects heading   */
    float front_stop_mm;         /* FRONT event: wall ahead this close (origin) */
    float front_slow_mm;         /* start slowing down for a wall ahead        */
    float open_mm;               /* a side ranger beyond this sees no wall     */
    float open_confirm_mm;       /* travel the opening must persist            */
    float wall_seen_mm;          /* travel a wall must be seen before it may end */
    float hallway_half_mm;       /* contest hallways are 46 cm: turn in the middle */
    float turn_tol_deg;

    /* lines, rooms */
    float line_holdoff_mm;       /* one line per this much travel              */
    float room_line_max_mm;      /* give up looking for the doorway line       */
    float room_entry_mm;         /* drive in this far past the doorway line    */
    float room_exit_mm;          /* and out this far past it                   */
    float home_advance_mm;       /* past the home circle line, then stop       */

    /* flame */
    float flame_detect;          /* counts, sum of both sensors: a flame seen  */
    float flame_out;             /* counts, sum below this: flame is out       */
    float flame_steer_deg;       /* heading offset for full left/right imbalance */
    float approach_stop_mm;      /* CF closer than this: stop approaching      */
    float guard_side_mm;         /* approach: steer off walls nearer than this beside the body */
    float guard_stop_mm;         /* approach: stop for a wall this near the front corners       */
    uint32_t fan_timeout_ms;     /* fans on at most this long per attempt      */
    uint32_t flame_out_confirm_ms;
    uint32_t verify_ms;          /* fans off, watch the flame this long        */
    uint8_t fan_attempts;
    uint8_t scan_dir;            /* 0 = counter-clockwise, 1 = clockwise       */
    uint8_t route_len;
    uint8_t home_wall_side;      /* the route's first direction, from home (home_orient.c):
                                  * open ahead with a wall close on this side:
                                  * FFR_HOME_WALL_LEFT/RIGHT; FFR_HOME_WALL_ANY: walls on
                                  * the most sides; FFR_HOME_AS_PLACED: no orientation,
                                  * the robot is placed facing it */

    ffr_step_t route[FFR_ROUTE_MAX];
    uint8_t return_start[FFR_ROOMS_MAX]; /* route index of the way home from room k+1 */
    uint8_t start_area;          /* FFR_START_HOME (the route program) or FFR_START_HALLWAY
                                  * (the arbitrary start mode: explore.c) */
    uint8_t reserved1[3];
};

/* ------------------------------------------------------------------ */
/* Our states (ffr_outputs_t.state; names: ffr_names(FFR_NAMES_STATE)).  */
/* ------------------------------------------------------------------ */
typedef enum {
    FFR_ST_IDLE = 0,
    FFR_ST_FOLLOW = 1,
    FFR_ST_TURN = 2,
    FFR_ST_FORWARD = 3,
    FFR_ST_ENTER = 4,
    FFR_ST_SCAN = 5,
    FFR_ST_APPROACH = 6,
    FFR_ST_EXTINGUISH = 7,
    FFR_ST_VERIFY = 8,
    FFR_ST_TO_DOOR = 9,
    FFR_ST_EXIT = 10,
    FFR_ST_HOMING = 11,
    FFR_ST_DONE = 12,
    FFR_ST_FAILED = 13,
    FFR_ST_ORIENT = 14, /* at home: a turn in place to learn which way it faces (home_orient.c) */
    FFR_ST_COUNT = 15
} ffr_state_code_t;

/* ------------------------------------------------------------------ */
/* Behaviour states (one per file in src/).                             */
/* ------------------------------------------------------------------ */
typedef struct {
    int32_t last_enc[2];
    uint8_t primed;
    float x_mm, y_mm, heading_rad; /* heading unwrapped                       */
    float dist_mm;                 /* path length of the origin               */
    float v_mm_s[2];               /* filtered wheel speeds                   */
    float dpos_mm[2];              /* wheel travel in the last tick           */
    float turn_scale;              /* learned: true rotation per odometry's raw rotation (turn_calibration.c) */
    float rot_raw_rad;             /* raw rotation since the walls last told the heading */
    float turn_w;                  /* what taught the scale so far: sum of rotation^2 (rad^2) */
} ffr_odometry_t;

typedef struct {
    float v_ref[2];                /* ramped speed references, mm/s           */
    float pos_err_mm[2];           /* integral of (reference - measured)      */
} ffr_speed_ctl_t;

typedef struct {
    float last_edge_mm;            /* odometry distance at the last edge      */
    uint8_t level;                 /* debounced line level                    */
    uint8_t count;
    uint8_t edge;                  /* 1 on the tick of a new line             */
    uint8_t run;                   /* consecutive ticks reading white         */
} ffr_line_counter_t;              /* the bytes together: 8, not 12 (the state is full, FFR_STATE_MAX) */

typedef struct {
    uint8_t seen[2];               /* side wall seen long enough (L, R)       */
    uint8_t opened[2];             /* then it ended: latched for the step     */
    uint8_t front_saw[2];          /* the front corner ranger saw it this step */
    uint8_t rear_ok[2];            /* the rear ranger's wall stayed beside     */
    float rear_lat0_mm[2];         /* its distance to the side when first seen */
    float front_lat_mm[2];         /* the front ranger's wall: its distance to the side (running), -1 none */
    float seen_mm[2];              /* travel with the wall seen               */
    float open_mm[2];              /* travel with the side open               */
    float rear_open_mm[2];         /* travel with the rear ranger open too    */
    float open_at_mm[2];           /* odometry distance where it opened       */
    float rear_at_mm[2];           /* where the rear ranger last saw the wall */
    float since_open_mm[2];        /* travel since the side last read open    */
    /* whole openings (GAP events): the front ranger alone, from the step's start */
    uint8_t gap_open[2];           /* the side reads open now (confirmed)     */
    uint8_t gaps[2];               /* openings seen whole (open, then a wall) */
    uint8_t gap_track[2];          /* the far edge of the last one still seen: refined */
    float gap_run_mm[2];           /* travel of the current run (wall or open) */
    float gap_first_mm[2];         /* where the current run of wall hits began */
    float gap_end_mm[2];           /* the last whole opening's far edge (the wall after it) */
    float gap_since_mm[2];         /* travel since the far edge was last refined */
} ffr_openings_t;

typedef struct {
    float heading_ref_rad;         /* corridor heading the robot should hold  */
    float target_rad;              /* turn target                             */
    float start_mm;                /* odometry distance at step start         */
    float goal_mm;                 /* distance goal (FORWARD, wrap-around)    */
    int16_t case_turn_deg;         /* turn chosen by the wall case            */
    uint8_t phase;
    uint8_t pc;                    /* route program counter                   */
    float exit_wall_rad;           /* out of a room: a wall alongside the way out, its angle to
                                      the held heading off square (route.c); FFR_EXIT_WALL_NONE none */
    float follow_mm;               /* HOME: the followed wall kept this far, the hallway's middle as
                                      read (route.c, home_middle); 0: wall_target_mm */
} ffr_route_state_t;

/* One side ranger's hits in odometry's frame over a stretch of travel
 * (wall_direction.c): the line through them is the wall's direction. */
typedef struct {
    float s0_mm;                   /* odometry distance at the window's start */
    float h0_rad;                  /* heading then                            */
    float x0_mm, y0_mm;            /* the first hit: sums are relative to it  */
    float sx, sy, sxx, syy, sxy;
    uint16_t n;                    /* hits in the window (0: none yet)        */
    uint8_t reserved[2];
} ffr_hit_window_t;

/* What walls teach over stretches of travel: the followed side's two-ranger
 * window and each side's learned tilt (wall_calibration.c), and each side
 * ranger's hit window (wall_direction.c). */
typedef struct {
    float s0_mm;                   /* odometry distance at the window's start */
    float h0_rad;                  /* heading at the window's start           */
    float d0_mm;                   /* the wall's distance at its first tick   */
    /* sums over the window's ticks, relative to its start: travel s, the
     * wall's distance d (least squares of d on s), heading h, and a = h plus
     * the two rangers' wall angle (constant along one straight wall) */
    float sum_s, sum_d, sum_ss, sum_sd, sum_dd;
    float sum_h;
    float sum_a, sum_aa;
    uint16_t n;                    /* ticks in the window                     */
    int8_t side;                   /* -1: no window                           */
    uint8_t reserved;
    ffr_hit_window_t hits[4];      /* LF, RF, LR, RR (ranger index - 1)       */
    float bias_rad[2];             /* learned error of the two-ranger wall angle, L, R */
    uint8_t bias_n[2];             /* windows that taught it (saturates)      */
    uint8_t reserved2[2];
} ffr_wall_cal_t;

/* A scan's walls (turn_calibration.c): each ranger's successive hits in
 * odometry's frame, their stretches' direction modulo 90 degrees summed in
 * FFR_SQ_PARTS parts of the turn (by raw rotation): how odometry's heading
 * error grows over the turn is the turn scale's error, and where it has got
 * to is the heading error now. */
#define FFR_SQ_PARTS 3
typedef struct {
    float raw_rad;                 /* raw rotation since the scan began       */
    float ax_mm[FFR_IR_COUNT];     /* each ranger's last hit (odometry frame) */
    float ay_mm[FFR_IR_COUNT];
    float c4[FFR_SQ_PARTS], s4[FFR_SQ_PARTS]; /* sum of len x (cos, sin)(4 x stretch direction) */
    float w[FFR_SQ_PARTS], wt[FFR_SQ_PARTS];  /* sum of len, of len x raw rotation */
    float last_mm[FFR_IR_COUNT];   /* each ranger's last reading: a new one is a new measurement */
    uint8_t anchor_ok[FFR_IR_COUNT];
    uint8_t reserved[3];
} ffr_scan_square_t;

/* What the rangers saw in a room (obstacle_avoid.c): a bit per 64 mm cell of
 * a 1.54 m square in odometry's frame, centred a little beyond where the
 * first scan is made (kept small: the state must fit FFR_STATE_MAX; a row of
 * cells is three bytes). */
#define FFR_OBST_CELLS 24          /* cells a side                             */
#define FFR_OBST_VIA 3             /* turning points of a detour, kept to back out by */
typedef struct {
    int16_t ox_mm, oy_mm;          /* odometry position of the grid's corner   */
    uint8_t bits[FFR_OBST_CELLS * FFR_OBST_CELLS / 8];
    int16_t via_x_mm[FFR_OBST_VIA]; /* where the approach turned (its trail)    */
    int16_t via_y_mm[FFR_OBST_VIA];
    float trail_rad;               /* the heading when the last turning point was kept */
    int16_t free_mm;               /* the detour's corridor: clear this far (mm) */
    int16_t best_free_mm;          /* the search under way: its best corridor's clearance */
    int8_t offset;                 /* the detour's offset from the flame now (steps, + left) */
    int8_t best;                   /* the search under way: its best offset so far */
    int8_t first;                  /* the search under way: the side it tries first (+-1; 0: none) */
    uint8_t next;                  /* the search under way: the next heading it looks along */
    uint8_t n_via;
    uint8_t retrace;               /* backing out: 0 not decided, 1 by the turning points, 2 straight */
    uint8_t aside_next;            /* the last room's third point: the next heading its search looks along (room.c) */
    uint8_t reserved;
} ffr_obstacles_t;

typedef struct {
    uint8_t phase;
    uint8_t room;
    uint8_t attempts;
    uint8_t flame_found;
    float entry_heading_rad;
    float scan_x_mm, scan_y_mm;    /* odometry pose where the scan was made   */
    float line_x_mm, line_y_mm;    /* odometry position where the doorway line was met */
    float start_heading_rad;
    float best_signal;
    float best_heading_rad;
    float phase_start_mm;
    uint32_t phase_start_ms;
    uint32_t below_since_ms;
    float flame_f;                 /* flame sum, filtered: is it out?          */
    float best_front_mm;           /* the wall ahead at the best heading (front distance) */
    float exit_heading_rad;        /* the way out of the door (route.c takes it as its heading reference) */
    uint32_t lost_since_ms;        /* the approached flame lost since (0: not lost) */
    uint8_t flame_near;            /* the approach has seen the flame near (room.c FLAME_NEAR) */
    uint8_t scan_trail;            /* the scan began with the flame on its trailing side (room_entry.c) */
    uint8_t scan_lead;             /* the scan has seen the flame strong on its leading side (room.c) */
    uint8_t fans_early;            /* the approach has the fans on: the flame within their reach (room.c) */
    ffr_scan_square_t square;      /* the walls seen in the scan (turn_calibration.c) */
    float entry_flame;             /* the strongest flame sum driving in (room.c) */
    int16_t deeper_mm;             /* how far the second scan point is beyond the first */
    uint8_t scans;                 /* scan points used in this room (1; 2: deeper in; 3: aside, the last room) */
    uint8_t closer_steps;          /* steps closer made after a strength stop's fans failed (room.c) */
    ffr_obstacles_t obst;          /* the room's obstacles (obstacle_avoid.c)  */
    float entry_peak;              /* the entry's strongest flame signal so far (room_entry.c) */
    int16_t ahead_min_mm;          /* the approach's nearest front ranger reading so far (room_entry.c) */
    int16_t ahead_min_at_mm;       /* odometry's distance driven in the approach when it was read */
} ffr_room_state_t;

/* The rangers' geometry in the body frame (x ahead, y left; ir_calibration.c):
 * each beam's direction, from the configuration (set by ffr_init), and where
 * this tick's readings put the hits, worked out once per tick for every
 * behaviour that uses them (openings, wall direction, wall line, guards).
 * A hit is meaningful only for a valid reading (ffr_ir_valid). */
typedef struct {
    float beam_cos[FFR_IR_COUNT];  /* cos, sin of ir_angle_deg                */
    float beam_sin[FFR_IR_COUNT];
    float hit_x_mm[FFR_IR_COUNT];  /* this tick's hit points                  */
    float hit_y_mm[FFR_IR_COUNT];
} ffr_ir_geom_t;

/* Orientation at home (home_orient.c): a turn in place, every ranger's hits
 * in odometry's frame; the walls' direction (mod 90 degrees) from short
 * stretches of one ranger's hits, and the nearest hit per direction bin. */
#define FFR_ORIENT_BINS 36         /* 10 degrees each                         */
typedef struct {
    uint8_t phase;                 /* sweep, centre, shift turn, shift drive, aim, turn, done, clear, escape */
    uint8_t anchors;               /* rangers (bit i) whose last hit anchors a stretch of wall; bit 7: a move back watched (rear_passed) */
    uint8_t reverse;               /* the shift (or escape leg) is driven backwards */
    uint8_t escapes;               /* moves made to get room to turn in place */
    uint8_t leg;                   /* the escape's leg: 0 straight, 1-3 the S and the way back, 4 the probe's way back, 5 straight back, 6 a fold move, 7 a fold move turned back, 8 straight back for the S's floor, 9 the S's first arc begun gently, 10 unfold_front's probe's way back, 11 unfold_front's moves back */
    uint8_t trusted;               /* rangers (bit i) whose short reading grew as the robot moved away: no fold-back */
    uint8_t probed;                /* rangers the last escape moved away from, whose reading it watches */
    uint8_t probe_done;            /* the probe for fold-back made since the robot last looked afresh */
    uint8_t folded;                /* rangers (bit i) the probe or a fold move saw folded back */
    int8_t sweep_side;             /* the sweep turns: +1 left, -1 right, 0 toward home_wall_side */
    uint8_t after_shift;           /* room to turn looked for after the shift: its move ends in the aim */
    uint8_t slant_watch;           /* this straight escape began clear of a wall across it at a slant: it stops short of one */
    float back_chord_mm;           /* the rear pair's chord behind when this straight leg began (rear_chord_room) */
    float leg_mm;                  /* the escape's arc legs' length; a fold move's length */
    float near_mm;                 /* nearest wall line seen in the sweep, from where it stands; a shift
                                      forward toward a wall across: its measure (65535: none) */
    float near_x_mm, near_y_mm;    /* its nearest point (odometry, from the robot) */
    float x0_mm, y0_mm, h0_rad;    /* odometry pose where the sweep began     */
    float dir0_rad;                /* the walls' direction (odometry), mod 90 degrees */
    float target_rad;              /* heading of the current turn             */
    float goal_mm;                 /* odometry distance where the shift ends  */
    float anchor_x_mm[FFR_IR_COUNT];
    float anchor_y_mm[FFR_IR_COUNT];
    float c4, s4, w;               /* sum of len * (cos, sin)(4 * segment direction), sum of len */
    uint16_t bin_mm[FFR_ORIENT_BINS]; /* nearest hit from the sweep's centre per bin (0xFFFF none) */
    float bin_x_mm[FFR_ORIENT_BINS];  /* and where it is, from the sweep's centre; from the centre's
                                         tick on, in the walls' frame and the aim's order
                                         (ffr_orient_to_walls; bin_mm as swept) */
    float bin_y_mm[FFR_ORIENT_BINS];
    float probe_mm[FFR_IR_COUNT];  /* the probed rangers' readings when the last escape began (a fold move: every
                                      ranger's, lead_grew watches the front ones); a ranger looking back
                                      and not probed: its shortest reading on this move backward (rear_passed); in
                                      the sweep, how far the line of each ranger's last stretch of hits passes
                                      from the axle (0: none; ffr_orient_record, sweep_side_at_bottom) */
} ffr_home_orient_t;

/* The explorer (explore.c, the arbitrary start mode): one wall followed
 * through the hallways, every doorway on that side searched, home found by
 * its circle's two lines. */
typedef struct {
    uint8_t phase;                 /* follow, wrap, turn, probe, room, home, back */
    uint8_t side;                  /* the wall followed: FFR_SIDE_LEFT/RIGHT  */
    uint8_t after;                 /* the phase after the current turn        */
    uint8_t homes;                 /* home circles crossed so far             */
    uint8_t bent;                  /* a turn since the last line edge         */
    uint8_t rooms_at_flip;         /* rooms_searched when the walls last changed */
    uint8_t backing;               /* wrap: backing to an opening's middle passed */
    uint8_t flips;                 /* the walls changed so far (a loop's rooms searched, no flame) */
    float start_mm;                /* odometry distance where the phase began (a follow: its leg, the probe before it included) */
    float goal_mm;                 /* distance goal (wrap, home, back; backing: along the held heading) */
    float edge_mm;                 /* where the last line edge was crossed (-1: none to pair) */
    float target_rad;              /* the current turn's target               */
    float home_mm;                 /* where the home circle was last recognised */
} ffr_explore_t;

struct ffr_state {
    ffr_config_t cfg;
    ffr_odometry_t odo;
    ffr_speed_ctl_t speed;
    ffr_line_counter_t lines;
    ffr_openings_t open;
    ffr_route_state_t route;
    ffr_wall_cal_t wall_cal;
    ffr_room_state_t room;
    ffr_home_orient_t orient;
    ffr_explore_t explore;
    float ir_mm[FFR_IR_COUNT];     /* last calibrated ranges (ir_max_mm+1 = none) */
    ffr_ir_geom_t ir_geom;         /* and their hit points                    */
    uint32_t t_ms;
    uint32_t last_t_ms;
    uint8_t state;                 /* ffr_state_code_t                        */
    uint8_t started;
    uint8_t flags;
    uint8_t rooms_searched;
    uint8_t returning;             /* executing a way home                    */
    uint8_t fail_code;
    uint8_t fan;
    uint8_t reserved;
    float cmd_v_mm_s;              /* motion command of this tick             */
    float cmd_w_rad_s;
    float flame_ema;               /* both flame sensors, slowly filtered     */
    float flame_dark;              /* the lowest of that: no flame in view    */
};

/* Failure codes in ffr_outputs_t.fail_code. */
enum {
    FFR_FAIL_NONE = 0,
    FFR_FAIL_NO_FLAME = 1,      /* route ended, no flame found               */
    FFR_FAIL_NOT_OUT = 2,       /* fans did not put the flame out            */
    FFR_FAIL_NO_LINE = 3,       /* doorway line not found                    */
    FFR_FAIL_BAD_ROUTE = 4,     /* route program invalid                     */
    FFR_FAIL_LOST_FLAME = 5
};

/* ------------------------------------------------------------------ */
/* API: the contract's functions (ffr_contract.h) and our extras        */
/* ------------------------------------------------------------------ */
/* Batch step for sweeps: n independent robots (our extra; the harness uses
 * it when a library has it and never requires it). */
void ffr_step_many(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out, uint32_t n);

/* Our sub-struct in the layout table (the route program's steps) and our own
 * name tables (index = the code): route ops, sides, events. */
enum { FFR_S_ROUTE_STEP = FFR_S_OWN };
enum { FFR_NAMES_OPS = FFR_NAMES_OWN, FFR_NAMES_SIDES = FFR_NAMES_OWN + 1, FFR_NAMES_EVENTS = FFR_NAMES_OWN + 2 };

#ifdef __cplusplus
}
#endif
#endif /* FFR_H */
