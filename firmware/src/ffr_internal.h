/* Internal interfaces between the firmware's behaviours (one file each). */
#ifndef FFR_INTERNAL_H
#define FFR_INTERNAL_H

#include "ffr.h"

#define FFR_PI 3.14159265358979f
#define FFR_DEG 0.0174532925199433f /* rad per degree */

/* The smallest helpers are inline: each is called dozens of times a tick,
 * and as a call into another translation unit it cost the target (-Os, no
 * LTO) several times its own few instructions. Same arithmetic either way. */
static inline float ffr_absf(float x) { return x < 0.0f ? -x : x; }
static inline float ffr_clampf(float x, float lo, float hi)
{
    if (x < lo) {
        return lo;
    }
    if (x > hi) {
        return hi;
    }
    return x;
}

/* fmath.c: portable math, bit-identical on glibc and newlib targets. */
float ffr_wrap_pi(float a);
float ffr_sinf(float x);
float ffr_cosf(float x);
float ffr_atan2f(float y, float x);
float ffr_sqrtf(float x);
void ffr_add_dir4(float dx, float dy, float len, float *c4, float *s4);

/* ir_calibration.c: GP2D12 mV -> distance from the sensor, mm. */
#define FFR_IR_NONE(cfg) ((cfg)->ir_max_mm + 1.0f)
float ffr_ir_mv_to_mm(const ffr_config_t *cfg, uint16_t mv);
static inline int ffr_ir_valid(const ffr_config_t *cfg, float d_mm) { return d_mm <= cfg->ir_max_mm; }
/* The rangers' beam directions from cfg (once: ffr_init), then each tick
 * where the readings ir_mm put the hits, in the body frame (x ahead, y left), mm. */
void ffr_ir_geom_init(ffr_ir_geom_t *g, const ffr_config_t *cfg);
void ffr_ir_geom_update(ffr_ir_geom_t *g, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT]);

/* odometry.c */
void ffr_odometry_reset(ffr_odometry_t *o);
void ffr_odometry_update(ffr_odometry_t *o, const ffr_config_t *cfg, const int32_t enc[2], float dt_s);

/* speed_control.c: wheel speed loops, (v, w) -> PWM. */
void ffr_speed_reset(ffr_speed_ctl_t *s);
void ffr_speed_control(ffr_speed_ctl_t *s, const ffr_config_t *cfg, const ffr_odometry_t *o,
                       float v_mm_s, float w_rad_s, float dt_s, int16_t pwm[2]);

/* proximity.c: forward speed from the front ranger. */
float ffr_front_distance(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT]);
float ffr_proximity_speed(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float cruise);
/* The front distance less the travel since the reading was measured (its age,
 * chosen: one datasheet period, 38.3 ms, rounded up; the reading is one to two
 * periods old with the part's latency, and a stop anticipated by a period
 * costs a nominal robot 13 mm at cruise speed). */
#define FFR_IR_AGE_MS 40.0f
float ffr_front_now(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT]);

/* wall_follow.c (Fig. 10): wall line from two rangers on one side. */
typedef struct {
    uint8_t valid;       /* distance known                          */
    uint8_t angle_valid; /* both rangers saw the same straight wall  */
    float dist_mm;       /* origin to the wall line                  */
    float angle_rad;     /* wall direction relative to the heading   */
} ffr_wall_t;
/* g: the hits of the readings ir_mm (ffr_ir_geom_update). */
ffr_wall_t ffr_wall_estimate(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                             int side);
/* Does ranger i's hit (reading ir_mm[i], its point in g) lie on a wall beside
 * the robot (not across an opening)? The hit's body-frame point is left in
 * *px, *py when the reading is valid. (Inline: up to a dozen calls a tick.)
 *
 * A hit farther to the side than open_mm is across an opening (a crossing
 * hallway's far wall, a room beyond its door), not the wall beside the
 * robot. The limit keeps the two apart for every GP2D12 within its datasheet
 * limits: a wall at the wanted distance (230 mm) reads at most ~30 % long,
 * more on a robot that has drifted a few centimetres out; a crossing
 * hallway's far wall (~690 mm to the side) at least ~25 % short (~520 mm).
 * open_mm (400) sits between them with margin both ways; halfway to the
 * wanted distance (315 mm), as it was, turned a long-reading part's wall into
 * an opening (measured with the wall calibration in place: 98.4 -> 99.5 %
 * of 800 missions over 200 robots, docs/robustness.md).
 */
static inline int ffr_hit_beside(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                                 int i, float *px, float *py)
{
    if (!ffr_ir_valid(cfg, ir_mm[i])) {
        return 0;
    }
    *px = g->hit_x_mm[i];
    *py = g->hit_y_mm[i];
    return ffr_absf(*py) < cfg->open_mm;
}
/* Yaw rate (rad/s) that brings the robot to target_mm from the wall (wall_target_mm,
 * or HOME's hallway middle), parallel to it. */
float ffr_wall_follow_yaw(const ffr_config_t *cfg, const ffr_wall_t *w, int side, float target_mm);
/* Yaw rate (rad/s) that holds heading_ref. */
float ffr_heading_hold_yaw(const ffr_config_t *cfg, float heading, float heading_ref);

/* wall_direction.c: the walls' direction in odometry's frame from each side
 * ranger's hits. Returns how many windows closed this tick (their mean
 * direction in *wall_dir, within 90 degrees of the heading), 0 on most ticks. */
void ffr_wall_dir_reset(ffr_wall_cal_t *c);
int ffr_wall_dir_update(ffr_wall_cal_t *c, const ffr_config_t *cfg, const ffr_odometry_t *o,
                        const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT], float *wall_dir);
/* What a direction (rad) is off the nearest multiple of 90 degrees. */
float ffr_off_square(float dir);

/* wall_calibration.c: each side's two-ranger wall angle, calibrated from travel. */
void ffr_wall_cal_reset(ffr_wall_cal_t *c);   /* everything, the learned tilts and hit windows too */
void ffr_wall_cal_restart(ffr_wall_cal_t *c); /* a new window; the tilts stay      */
/* One tick beside the wall on `side` (w as measured, uncorrected). */
void ffr_wall_cal_update(ffr_wall_cal_t *c, const ffr_wall_t *w, int side, float heading_rad, float dist_mm);
/* Take the side's learned tilt off a two-ranger wall angle. */
void ffr_wall_cal_correct(const ffr_wall_cal_t *c, ffr_wall_t *w, int side);
/* The side rangers' hits (a copy of g) with the pair's tilt split between them. */
void ffr_wall_cal_split(const ffr_wall_cal_t *c, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT],
                        ffr_ir_geom_t *g);

/* wall_cases.c (Fig. 9): the six wall cases and the turn each asks for. */
typedef enum {
    FFR_CASE_CORRIDOR = 0,     /* walls both sides, open ahead: go on      */
    FFR_CASE_CORNER_LEFT = 1,  /* wall ahead and right: turn left          */
    FFR_CASE_CORNER_RIGHT = 2, /* wall ahead and left: turn right          */
    FFR_CASE_T = 3,            /* wall ahead, both sides open: preference  */
    FFR_CASE_DEAD_END = 4,     /* walls ahead, left, right: turn around    */
    FFR_CASE_BRANCH_LEFT = 5,  /* open ahead and left: preference or on    */
    FFR_CASE_BRANCH_RIGHT = 6, /* open ahead and right: preference or on   */
    FFR_CASE_OPEN = 7          /* nothing seen anywhere                    */
} ffr_wall_case_t;
ffr_wall_case_t ffr_wall_case(int front_wall, int left_open, int right_open);
/* The case where the robot stands: front from the front ranger, sides from
 * the openings seen on the way in (or a side ranger seeing nothing now). */
ffr_wall_case_t ffr_wall_case_sensed(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT],
                                     const ffr_openings_t *op);
/* Degrees to turn (+ left) for a case; prefer = FFR_SIDE_LEFT/RIGHT/NONE. */
int16_t ffr_wall_case_turn(ffr_wall_case_t c, uint8_t prefer);

/* turn_calibration.c: odometry's turn scale learned from the walls. `err` is
 * what a wall just showed odometry's heading to be off (rad, + = too far
 * counter-clockwise); with enough rotation since the last such fix, the
 * scale moves toward the one that explains it. Resets the rotation count. */
void ffr_turn_cal_learn(ffr_odometry_t *o, float err);
/* A scan in place measured against the room's walls (turn_calibration.c):
 * reset when it begins, record every tick of it (after odometry's update),
 * and at its end fix: 1 if the walls told how odometry's heading error grew
 * per raw radian of the turn (*grow; the scan added grow x q->raw_rad), which
 * also teaches odometry's turn scale; 0: too short a turn or too little wall
 * seen to tell, nothing changed. */
void ffr_scan_sq_reset(ffr_scan_square_t *q);
void ffr_scan_sq_record(ffr_scan_square_t *q, const ffr_config_t *cfg, const ffr_odometry_t *o,
                        const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT]);
int ffr_scan_sq_fix(const ffr_scan_square_t *q, ffr_odometry_t *o, float *grow);

/* turn.c: turning in place by odometry. */
float ffr_turn_yaw(const ffr_config_t *cfg, float heading, float target);
/* how fast the body turns (rad/s, unsigned) by odometry's wheel speeds */
float ffr_turn_spin(const ffr_config_t *cfg, const ffr_odometry_t *o);
int ffr_turn_done(const ffr_config_t *cfg, const ffr_odometry_t *o, float target);
/* chosen: the contest hallway leaves 230 mm from its middle to a wall, the
 * default body's corner radius is 156 mm; 60 mm keeps the nominal route's
 * turns (at a wall ahead: front_stop_mm = 230 mm) out of it */
#define FFR_TURN_MARGIN_MM 60.0f
/* chosen (turn.c, ffr_turn_onset): a turn near a wall ahead counts on the
 * body rolling on this long (the realistic profile's slipping tracks: ~40 mm
 * from 200 mm/s), and waits for it to slow below FFR_TURN_ROLL_MM_S */
#ifndef FFR_TURN_ROLL_S
#define FFR_TURN_ROLL_S 0.2f
#endif
#ifndef FFR_TURN_ROLL_MM_S
#define FFR_TURN_ROLL_MM_S 30.0f
#endif
float ffr_turn_room_v(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT]);
float ffr_turn_onset(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT]);
/* A turn in place onto target_rad (the route's TURN and the explorer's):
 * each tick's commands, and, once ffr_turn_done, the stop and the corridor
 * heading reference set to the target. */
void ffr_turn_toward(ffr_state_t *st, float target_rad);
void ffr_turn_finish(ffr_state_t *st, float target_rad);

/* line_counter.c */
void ffr_lines_reset(ffr_line_counter_t *l);
void ffr_lines_update(ffr_line_counter_t *l, const ffr_config_t *cfg, uint8_t line, float dist_mm);

/* openings.c: a side wall seen, then ending. pend_side: the side whose
 * opening ends the route's current step (ffr_route_open_side), -1 none. */
void ffr_openings_reset(ffr_openings_t *op);
void ffr_openings_update(ffr_openings_t *op, const ffr_config_t *cfg, const ffr_ir_geom_t *g,
                         const float ir_mm[FFR_IR_COUNT], float dist_mm, float step_mm, int pend_side);
int ffr_opening(const ffr_openings_t *op, int side);
/* the side's opening taken back: its wall watched afresh (seen again before an end counts) */
void ffr_opening_forget(ffr_openings_t *op, int side);
/* 1 once the n-th (0 or 1: the first) whole opening on a side has been seen
 * this step; where its middle is, as an odometry distance. */
int ffr_gap(const ffr_openings_t *op, int side, uint8_t n);
/* Each tick after ffr_openings_update: the whole openings' front-ranger
 * count; yaw_rad = the heading minus the corridor's (route.heading_ref_rad). */
void ffr_gaps_update(ffr_openings_t *op, const ffr_config_t *cfg, const ffr_ir_geom_t *g,
                     const float ir_mm[FFR_IR_COUNT], float dist_mm, float step_mm, float yaw_rad);
float ffr_gap_middle_mm(const ffr_openings_t *op, const ffr_config_t *cfg, int side);
float ffr_open_middle_mm(const ffr_openings_t *op, const ffr_config_t *cfg, int side);

/* room.c: the room task (Fig. 11) and the flame task (Fig. 12), one handler
 * a phase. It writes no route state: what route.c must do, it returns. */
typedef enum {
    FFR_ROOM_BUSY = 0,       /* still in the room                                      */
    FFR_ROOM_FACING_OUT = 1, /* turned to the door: the route's heading reference is
                              * now st->room.exit_heading_rad (the corridor reversed) */
    FFR_ROOM_LEFT = 2        /* out across the doorway line and clear of it           */
} ffr_room_result_t;
/* chosen: a flame the approach saw near (4 x flame_detect), lost and not
 * found again by a re-scan for this long (ms) without being put out: the
 * mission fails "flame lost" (FFR_FAIL_LOST_FLAME). Longer than a flicker or
 * a draught's gust (well under a second), shorter than one scan at the
 * default scan_rate_deg_s (150: 2.4 s a turn), so there the re-scan's one
 * turn decides; a faster scan turns on until this has passed. */
#ifndef FFR_FLAME_LOST_MS
#define FFR_FLAME_LOST_MS 2000u
#endif
/* entry_heading_rad: the heading the room is entered on (the route's reference). */
void ffr_room_begin(ffr_state_t *st, uint8_t room, float entry_heading_rad);
ffr_room_result_t ffr_room_step(ffr_state_t *st, const ffr_inputs_t *in);

/* room_guards.c: the room task's geometry guards, where the robot is
 * relative to the doorway it came in by and the walls near it. */
/* The heading's and the entry heading's cosine and sine, worked out once a
 * tick for every ffr_depth_in of that tick. */
typedef struct {
    float c, s;   /* heading       */
    float ce, se; /* entry heading */
} ffr_door_frame_t;
ffr_door_frame_t ffr_door_frame(const ffr_state_t *st);
/* A body-frame point (bx ahead, by left, mm) relative to where the doorway
 * line was crossed: depth into the room (along the entry heading), returned,
 * and the lateral offset in *lateral (if not NULL), mm. */
float ffr_depth_in(const ffr_state_t *st, const ffr_door_frame_t *f, float bx, float by, float *lateral);
/* Is a flame seen in direction `dir` (rad) from the scan point outside the
 * room, seen through the door the robot came in by? The doorway line runs
 * through the point where it was crossed, square to the entry heading; a ray
 * that leaves through it within half a hallway of that point leaves by the
 * door. No candle can stand on the short stretch of that ray inside the room:
 * the contest keeps the candle circle 33 cm clear of the doorway. */
int ffr_through_door(const ffr_state_t *st, float dir);
/* Is the robot's nose at the doorway it came in by (its line, or about to
 * reach it)? Approaching a flame, that means the flame is out there. */
int ffr_nose_in_doorway(const ffr_state_t *st, const ffr_door_frame_t *f);
/* The door's wall as a virtual wall: a yaw rate (rad/s, + left) away from it
 * as a front corner nears its line, *stop set when one reaches it; bal is the
 * flame's balance (+ left), the push kept small when it would lose the flame. */
float ffr_door_wall_guard(const ffr_state_t *st, const ffr_door_frame_t *f, float bal, int *stop);
/* The rangers' walls by the front half alone (the approach guard without the
 * door's wall): a yaw rate away from them, *stop and *near as below. */
float ffr_ranger_guard(const ffr_state_t *st, int *stop, int *near);
/* The approach's guard: the rangers' walls by the front half and the door's
 * wall. A yaw rate away from them; *stop: a front corner about to touch one;
 * *near: a wall beside the front half. */
float ffr_approach_guard(const ffr_state_t *st, const ffr_door_frame_t *f, float bal, int *stop, int *near);
/* Leaving a room: the yaw rate (rad/s, + left) that steers a front corner off
 * a wall its ranger sees beside the front half (this tick's hits). */
float ffr_leave_guard(const ffr_state_t *st);
/* Driving in: a heading offset (rad, + left) away from a side wall nearer
 * than the scan's turn in place needs (the body's corner radius + a margin). */
float ffr_scan_room_offset(const ffr_state_t *st);

/* obstacle_avoid.c: what the rangers saw in a room, as a bit grid in
 * odometry's frame (st->room.obst), and the approach's detour around it. */
/* An empty grid centred on (cx, cy) mm, no detour, no points to back out by. */
void ffr_obst_reset(ffr_obstacles_t *o, float cx_mm, float cy_mm);
/* Mark the cell under (x, y) mm; outside the grid: nothing. */
void ffr_obst_mark(ffr_obstacles_t *o, float x_mm, float y_mm);
int ffr_obst_at(const ffr_obstacles_t *o, float x_mm, float y_mm);
/* This tick's ranger hits (valid, within 60 cm) marked. */
void ffr_obst_record(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, const ffr_ir_geom_t *g,
                     const float ir_mm[FFR_IR_COUNT]);
/* The corridor the body sweeps from (x, y) heading dir_rad: how far (mm, past
 * the body's front, up to reach_mm) it is clear; marks within 6 cm of the
 * line of sight flame_rad are the candle's. *lat_mm (if not NULL): where
 * across (+ left) the first mark in it is. */
float ffr_obst_free_mm(const ffr_obstacles_t *o, const ffr_config_t *cfg, float x_mm, float y_mm, float dir_rad,
                       float flame_rad, float reach_mm, float *lat_mm);
/* The heading offset (rad, + left) from the flame's line of sight flame_rad
 * whose corridor is clear for reach_mm (0: the straight one is), else the one
 * clear farthest; *free_mm: how far that is. */
float ffr_obst_detour(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, float flame_rad,
                      float reach_mm, float *free_mm);
/* The approach's trail, for backing out the way it came: each tick of an
 * approach (begin: its first), the position is kept (o->via_*, three at
 * most) where the heading has turned 15 degrees since the last kept. */
void ffr_obst_trail(ffr_obstacles_t *o, const ffr_odometry_t *odo, int begin);
/* The trail begins anew here, this position its first point (room.c: the
 * third scan point, which the way back runs through). */
void ffr_obst_trail_from(ffr_obstacles_t *o, const ffr_odometry_t *odo);
/* The nearest marked cell's centre from (x, y), mm; radius_mm if none nearer. */
float ffr_obst_nearest_mm(const ffr_obstacles_t *o, float x_mm, float y_mm, float radius_mm);

/* room_entry.c: a candle near the door the robot came in by (issue 13,
 * doorcandle). The scan's first signal is the tail of a flame behind the
 * scan's way of turning when the flame sensors' balance (left - right over
 * their sum) puts it on the trailing side: 1, and then a fall from it is no
 * peak passed. dir: +1 the scan turns left (CCW), -1 right. */
int ffr_scan_starts_trailing(const ffr_config_t *cfg, float dir, float left, float right, float sig);
/* 1 when the entry drives past a near flame: its signal, once near (at
 * least 8 x flame_detect), has fallen off its peak (kept in *peak, 0 at the
 * entry's start) -- the flame leaves the sensors' view to the side, the
 * candle beside the robot's way in: the entry ends here, before the body
 * comes alongside it (the scan turns in place). moved_mm is the entry's
 * travel since the line sensor met the doorway line: the answer stays 0
 * until the axle is far enough past the line for that turn to clear the
 * door's jambs (room_entry.c ENTRY_AXLE_IN_MM). */
int ffr_entry_passing_flame(const ffr_config_t *cfg, float *peak, float sig, float moved_mm);
/* The approach's front ranger watch: reset at the approach's start. */
void ffr_ahead_reset(ffr_room_state_t *r);
/* 1 when an object stands at the fans' reach ahead: the front ranger at the
 * bottom of its span, or reading farther again after a near reading while
 * the robot drove on toward it (a GP2D12 folds back below ~8 cm). Only with
 * the flame near (sig at least 4 x flame_detect, room.c FLAME_NEAR): a wall ahead
 * with the flame far away is the guards' business. */
int ffr_ahead_at_reach(const ffr_config_t *cfg, ffr_room_state_t *r, float ir_cf_mm, float dist_mm, float sig);
/* how far (mm) the line sensor is past the doorway line met on the way in,
 * along the way out (room.c exit_heading_rad); < 0: still inside */
float ffr_leave_past_line_mm(const ffr_state_t *st);

/* drive.c: corridor driving shared by the route steps. */
void ffr_drive_corridor(ffr_state_t *st, uint8_t side, float speed);
/* A front corner's ranger seeing a wall beside the front half: the yaw
 * command (cmd_w_rad_s) plus the leaving guard's push off it, within the
 * turn rate. Called by the corridor driving and the route's last stretches. */
void ffr_corridor_guard(ffr_state_t *st);
/* route.exit_wall_rad when no wall alongside the way out was seen */
#define FFR_EXIT_WALL_NONE 10.0f
/* route.c: the wall alongside the way out of a room, watched (exit_wall_rad) */
void ffr_exit_wall_watch(ffr_state_t *st);
/* route.c: out of a room, odometry's heading set square to the wall ahead
 * when far off it, else to the wall alongside unless the wall ahead
 * disagrees; exit_wall_rad consumed */
void ffr_square_out_of_room(ffr_state_t *st);
void ffr_drive_heading(ffr_state_t *st, float heading, float speed);
/* straight on route.heading_ref_rad, it and odometry trued up by the walls beside */
void ffr_drive_held(ffr_state_t *st, float speed);
void ffr_stop(ffr_state_t *st);
/* Speed (mm/s) for `remaining_mm` to a stopping point: slows into the stop
 * so it is short, never below a crawl that still overcomes friction. */
float ffr_stopping_speed(float remaining_mm, float top);

/* home_orient.c: before the route, which way the robot faces at home. */
void ffr_orient_begin(ffr_state_t *st);
/* what an escape's leg watches, set as it begins (home_orient.c) */
void ffr_orient_watch_leg(ffr_state_t *st);
/* Returns 1 once the robot faces the route's first direction and odometry's
 * frame is square to the walls with heading 0 along it. */
int ffr_orient_step(ffr_state_t *st);
/* The walls' direction (rad, in (-pi/4, pi/4]) from the segment sums, and the
 * free distance (mm) toward `dir` (rad, odometry) in a band of band_mm each
 * side from (cx, cy), mm from the sweep's centre (65535: nothing seen). */
float ffr_orient_square(const ffr_home_orient_t *o);
float ffr_orient_free_mm(const ffr_home_orient_t *o, float band_mm, float dir, float cx, float cy);
/* The same toward dir0 + k * 90 degrees, k = 0..3, in one pass. */
void ffr_orient_free4(const ffr_home_orient_t *o, float band_mm, float dir0, float cx, float cy, float free_mm[4]);
/* The centre's view of bins in the walls' frame (ffr_orient_to_walls), from
 * (cu, cv) in that frame: free_mm[k] toward dir0 + k * 90 degrees, the
 * nearest hit within CENTRE_BAND_MM of the axis, or with none there the
 * nearer of the nearest hits either side of it within 15 degrees when they
 * are as far along it (a wall across it); 65535: neither. */
void ffr_orient_across4(const ffr_home_orient_t *o, float cu, float cv, float free_mm[4]);
/* The route's first direction: k (0..3) of the four directions square to
 * the walls, dir0 + k * 90 degrees, by the home_wall_side rule; -1 none open. */
int ffr_orient_choose(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                      float cy);
/* the bins into the walls' frame (x along dir0, y along dir0 + 90 degrees;
 * a bin without a hit far off both), in place: done once on the centre's
 * tick, so that the aim's tick turns none */
void ffr_orient_to_walls(ffr_home_orient_t *o, float dir0);
/* ffr_orient_choose of bins already in the walls' frame (ffr_orient_to_walls);
 * (cx, cy) as there, in odometry's frame */
int ffr_orient_aim(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                   float cy);
/* Where to stand before setting off: (dx, dy) mm from (cx, cy) that puts a wall
 * straight across an axis, within a hallway's width of the body's side
 * (2 x wall_target_mm + body_half_width_mm), at wall_target_mm (the nearer
 * of two), along each of the two square axes. */
void ffr_orient_centre(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float cx, float cy,
                       float *dx, float *dy);
/* the same of bins already in the walls' frame, (cx, cy) in odometry's (the firmware's tick);
 * toward_mm: the wall's distance as measured, when the shift runs along one axis (within 15
 * degrees) toward a wall across it, else 0 */
void ffr_orient_centre_walls(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float cx, float cy,
                             float *dx, float *dy, float *toward_mm);
/* Record one tick's hits (the sweep). */
void ffr_orient_record(ffr_home_orient_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo,
                       const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT]);
void ffr_orient_reset(ffr_home_orient_t *o, const ffr_odometry_t *odo);
int ffr_orient_sweep_side(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT]);
void ffr_orient_after_shift(ffr_state_t *st);
int ffr_orient_square_wall(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT], float walls,
                           float *dist_mm, float *nx, float *ny);
/* the body's farthest corner from the axle midpoint (it sweeps this circle turning in place) */
/* the route's first direction k (as ffr_orient_aim, bins in the walls'
 * frame, from where the shift (dx, dy) would end) if that shift is at most
 * skip_mm across it and SHIFT_TOL_MM along it, so not worth making; else -1 */
int ffr_orient_skip(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                    float cy, float dx, float dy, float skip_mm);
float ffr_orient_turn_radius_mm(const ffr_config_t *cfg);
/* the nearest wall seen by the rangers now, in the body's frame: 1 if any,
 * its distance from the axle midpoint and the unit vector toward it (single
 * hits, and the line through two rangers' hits on one wall) */
int ffr_orient_clearance(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                         float *dist_mm, float *nx, float *ny);
/* the same, the rangers in `folded` (bit i) that read within the GP2D12's
 * fold-back span (ir_min_mm .. FFR_FOLD_MAX_MM) taken as at the bottom of
 * their span (the wall may be 3-5.5 cm off the ranger, read as 10-18.5 cm);
 * no line through two rangers both in `not_both`, nor through one in
 * `not_any` unless the other reads at its span's bottom */
#define FFR_FOLD_MAX_MM 160.0f
/* The orientation's moves away from walls before its sweep goes ahead
 * regardless (home_orient.c; the tests set the count spent). 4 until 2 Dec
 * 2026; 8 since: more starts near a wall get clear before they turn
 * (docs/robustness.md, "More tries before the sweep goes ahead") */
#define FFR_ORIENT_ESCAPE_TRIES 8u
/* A front corner ranger's beam leaves the body through its side 42 mm from
 * the ranger ((half width - 70 mm) / sin 45 degrees, the default layout): a
 * wall folded back nearer than that would be inside the body, and one that
 * far reads 125 mm through the GP2D12's curve (its fold-back branch: 2,026
 * mV; tests/sim_plant/test_gp2d12.py). A reading above it is a wall as far
 * as read (ffr_orient_sweep_side). */
#define FFR_FOLD_CORNER_MAX_MM 125.0f
/* the fold-back rules at the start built in: readings up to this many mm
 * are suspects (FFR_FOLD_MAX_MM when on); 0, the default: off, the
 * orientation as before (docs/firmware.md: the stress sweep lost missions) */
#ifndef FFR_HOME_FOLD_MM
#define FFR_HOME_FOLD_MM 0.0f
#endif
int ffr_orient_clearance_fold(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                              uint8_t folded, uint8_t not_both, uint8_t not_any, float *dist_mm, float *nx,
                              float *ny);
/* the rangers (bit i) whose reading lies in the fold-back span (above
 * ir_min_mm, up to max_mm): it may be a wall far off or one nearly touching */
uint8_t ffr_orient_fold_suspects(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float max_mm);
/* of the rangers `probed` (a move went away from each's wall since it read
 * before_mm), those whose reading grew: their walls are as far as read */
/* what a short straight move (backward or not) told of the suspect rangers
 * (bit i) that read before_mm before it and ir_mm now: a wall as far as read
 * (genuine) or folded back (folded); rangers looking across the move tell
 * nothing */
void ffr_orient_probe_tell(const ffr_config_t *cfg, const ffr_ir_geom_t *g, int backward, uint8_t suspects,
                           const float before_mm[FFR_IR_COUNT], const float ir_mm[FFR_IR_COUNT], uint8_t *genuine,
                           uint8_t *folded);
/* the probe's way for these suspects: 1 backward (only the front may be
 * near), 0 forward */
int ffr_orient_probe_back(const ffr_ir_geom_t *g, uint8_t suspects);
uint8_t ffr_orient_probe_trust(const ffr_config_t *cfg, uint8_t probed, const float before_mm[FFR_IR_COUNT],
                               const float ir_mm[FFR_IR_COUNT]);

/* route.c: the route program interpreter. */
void ffr_route_begin(ffr_state_t *st, uint8_t pc);
/* route.c: the side whose opening the route's current step follows to
 * (FOLLOW ... OPEN_L/R), -1 for any other step or the explorer */
int ffr_route_open_side(const ffr_state_t *st);
/* route.c: 1 when the current step searches the route's last room (a ROOM
 * step with no other ROOM before END): the rooms before it had no flame, so
 * the candle is in it. 0 on a way home and for the explorer. */
int ffr_route_last_room(const ffr_state_t *st);
/* explore.c: 1 once the walk has come round a loop whose rooms it searched
 * with no flame found (the walls changed): a candle hidden in a room it
 * passed; every room searched from then on is searched harder (room.c) */
int ffr_explore_searched_round(const ffr_state_t *st);
void ffr_route_step(ffr_state_t *st, const ffr_inputs_t *in);

/* explore.c: the arbitrary start mode (cfg->start_area == FFR_START_HALLWAY).
 * Begin once the robot is square to the walls (home_orient.c), facing open
 * with the followed wall beside it; then one step a tick until DONE/FAILED. */
void ffr_explore_reset(ffr_explore_t *e);
void ffr_explore_begin(ffr_state_t *st);
void ffr_explore_step(ffr_state_t *st, const ffr_inputs_t *in);
/* Two line edges chord_mm of travel apart are the home circle's two sides if
 * the chord is no longer than FFR_HOME_CHORD_MM; then *to_middle_mm is the
 * origin's travel from the second edge to where the line sensor's chord has
 * its middle (negative: already past it). */
#define FFR_HOME_CHORD_MM 400.0f
int ffr_explore_is_circle(float chord_mm, float line_sensor_x_mm, float *to_middle_mm);
/* The multiple of 90 degrees nearest to rad (the turns' targets in a frame
 * square to the walls). */
float ffr_explore_square(float rad);
/* Out of a door: the quarter turn's degrees on along the hallway, toward
 * the followed side (e->side) unless a wall stands along that side within
 * the front corner's turning circle and not along the other (a door in a
 * hallway's end, beside its corner): then away from it. */
int ffr_explore_way_out(const ffr_state_t *st);

/* mission.c */
void ffr_fail(ffr_state_t *st, uint8_t code);

#endif
