/*
 * states.c - the behaviours and the state table that wires them.
 *
 * Each behaviour sets this tick's motion command (st->cmd_v, st->cmd_w) and
 * returns an event; the table below says where each event leads. To change
 * the robot's plan, change the table; to change how it does a thing, change
 * one handler.
 */
#include "wall_follower.h"

static float clampf(float v, float lo, float hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

static float absf(float v)
{
    return v < 0.0f ? -v : v;
}

static float since_mm(const ffr_state_t *st)
{
    return st->dist_mm - st->entered_mm;
}

static uint32_t since_ms(const ffr_state_t *st)
{
    return st->t_ms - st->entered_ms;
}

/* Turn in place towards target_rad; 1 when there. */
static int turn_to(ffr_state_t *st, float rate_deg_s)
{
    const struct ffr_config *c = &st->cfg;
    float err = wf_wrap(st->target_rad - st->heading_rad);
    float lim = rate_deg_s * WF_DEG;
    st->cmd_v = 0.0f;
    st->cmd_w = clampf(c->heading_kp * err, -lim, lim);
    if (absf(err) < 1.5f * WF_DEG) {
        st->cmd_w = 0.0f;
        return 1;
    }
    return 0;
}

/* Hold heading target_rad at speed v. */
static void hold(ffr_state_t *st, float v)
{
    const struct ffr_config *c = &st->cfg;
    float lim = c->max_yaw_deg_s * WF_DEG;
    st->cmd_v = v;
    st->cmd_w = clampf(c->heading_kp * wf_wrap(st->target_rad - st->heading_rad), -lim, lim);
}

static int front_blocked(const ffr_state_t *st, const wf_sense_t *s)
{
    return s->ir_mm[FFR_IR_CF] < st->cfg.front_mm;
}

static float cruise(const ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float f = (s->ir_mm[FFR_IR_CF] - c->front_mm) / 250.0f;
    return c->cruise_mm_s * clampf(f, 0.4f, 1.0f);
}

/* ---- entry actions ---------------------------------------------------- */

static void keep_heading(ffr_state_t *st)
{
    st->target_rad = st->heading_rad;
}

/* A new wall to follow (not the same one after a dropout or a scan): note
 * where its run began. Back from a flame, the wall runs on for as long as
 * the robot had followed it when it scanned. */
static void follow_entry(ffr_state_t *st)
{
    if (st->prev_state == WF_ARC || st->prev_state == WF_TURN_AWAY || st->prev_state == WF_FIND_WALL) {
        st->follow_from_mm = st->dist_mm;
    }
    if (st->pending_run_mm >= 0.0f) {
        st->end_at_mm = st->dist_mm + st->pending_run_mm;
        st->follow_from_mm = st->dist_mm;
        st->pending_run_mm = -1.0f;
    }
}

static void start_turn(ffr_state_t *st)
{
    st->target_rad = wf_wrap(st->heading_rad + st->cfg.start_turn_deg * WF_DEG);
}

static void turn_away(ffr_state_t *st)
{
    st->target_rad = wf_wrap(st->heading_rad - st->side * 0.5f * WF_PI);
    st->end_at_mm = st->dist_mm; /* the wall ahead becomes the followed one: it may end right here */
}

static void scan_start(ffr_state_t *st)
{
    st->best_sum = 0.0f;
    st->best_rad = st->heading_rad;
    st->scan_dist_mm = st->dist_mm;
    st->doors_at_scan = st->doors;
    st->scan_x_mm = st->x_mm;
    st->scan_y_mm = st->y_mm;
    st->scan_at_mm = -1.0f;
    st->target_rad = 0.0f; /* the scan's accumulated rotation */
    if (st->rooms < 255u) {
        st->rooms++;
    }
}

static void aim(ffr_state_t *st)
{
    st->target_rad = st->best_rad;
}

static void resume(ffr_state_t *st)
{
    st->target_rad = st->resume_rad;
}

static void extinguish(ffr_state_t *st)
{
    st->below_ms = 0u;
    st->flags = (uint8_t)(st->flags | FFR_FLAG_FLAME_SEEN);
}

/* The flame is out: back to where it was seen, then follow the other wall:
 * the way in, backwards, leads home. */
static void back_to_scan(ffr_state_t *st)
{
    st->flags = (uint8_t)(st->flags | FFR_FLAG_EXTINGUISHED);
    st->goal_x_mm = st->scan_x_mm;
    st->goal_y_mm = st->scan_y_mm;
    st->resume_rad = wf_wrap(st->resume_rad + WF_PI);
    st->resume_state = WF_FOLLOW;
    st->pending_run_mm = st->scan_dist_mm - st->follow_from_mm;
    st->doors_back = 0u;
    st->side = -st->side;
}



static void done(ffr_state_t *st)
{
    st->flags = (uint8_t)(st->flags | FFR_FLAG_DONE);
}

static void failed(ffr_state_t *st)
{
    st->flags = (uint8_t)(st->flags | FFR_FLAG_FAILED);
}

/* ---- behaviours ------------------------------------------------------- */

static wf_event_t idle_tick(ffr_state_t *st, const wf_sense_t *s)
{
    (void)s;
    st->cmd_v = 0.0f;
    st->cmd_w = 0.0f;
    return WF_EV_NONE; /* ffr_step starts the mission on inputs.start */
}

static wf_event_t turn_tick(ffr_state_t *st, const wf_sense_t *s)
{
    (void)s;
    return turn_to(st, st->cfg.turn_deg_s) ? WF_EV_DONE : WF_EV_NONE;
}

/* Follow the wall on st->side: its distance and angle from the two rangers. */
static wf_event_t follow_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float lim = c->max_yaw_deg_s * WF_DEG;
    if (front_blocked(st, s)) {
        st->cmd_v = 0.0f;
        st->cmd_w = 0.0f;
        return WF_EV_FRONT;
    }
    if (s->side_front_mm >= c->open_mm) {
        st->cmd_v = cruise(st, s);
        st->cmd_w = 0.0f;
        return WF_EV_OPEN;
    }
    /* where the front ranger meets the wall: when it ends, its end is about there */
    if (s->side_front_mm < c->open_mm) {
        st->end_at_mm = st->dist_mm + s->side_hit_x_mm;
    }
    st->cmd_v = cruise(st, s);
    if (s->side_ok && absf(s->side_deg) < 10.0f && absf(s->side_mm - c->wall_mm) < 60.0f) {
        /* the contest's walls meet at right angles, and the start faces along one: a straight
         * wall beside tells odometry's heading, whatever the turns before got wrong */
        float wall = st->heading_rad + st->side * s->side_deg * WF_DEG;
        float quarter = 0.5f * WF_PI;
        float k = wall / quarter;
        float snapped = quarter * (float)(int)(k + (k < 0.0f ? -0.5f : 0.5f));
        st->heading_rad = wf_wrap(st->heading_rad + c->heading_learn * wf_wrap(snapped - wall));
    }
    if (s->side_ok) {
        float w = c->wall_kp * (s->side_mm - c->wall_mm) + c->angle_kp * s->side_deg;
        st->cmd_w = st->side * clampf(w * WF_DEG, -lim, lim);
    } else { /* only the front ranger sees it: keep its hit wall_mm to the side */
        float w = c->wall_kp * (s->side_hit_y_mm - c->wall_mm);
        st->cmd_w = st->side * clampf(w * WF_DEG, -lim, lim);
    }
    return WF_EV_NONE;
}

/* The followed wall ended: straight on until the robot is abreast of its end. */
static wf_event_t corner_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    if (front_blocked(st, s)) {
        return WF_EV_FRONT;
    }
    hold(st, cruise(st, s));
    /* the wall back beside (a dropout, not an end): hysteresis against FOLLOW's open_mm */
    if (s->side_ok && s->side_front_mm < 0.7f * c->open_mm && absf(s->side_deg) < 20.0f && since_mm(st) > 80.0f) {
        return WF_EV_WALL;
    }
    return st->dist_mm >= st->end_at_mm + c->corner_mm ? WF_EV_DONE : WF_EV_NONE;
}

/* Round the wall's end on a circle of radius wall_mm until the wall is beside again. */
static wf_event_t arc_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float turned = absf(since_mm(st)) / c->wall_mm; /* rad */
    if (front_blocked(st, s)) {
        return WF_EV_FRONT;
    }
    st->cmd_v = c->cruise_mm_s * 0.6f;
    st->cmd_w = st->side * st->cmd_v / c->wall_mm;
    if (turned > 45.0f * WF_DEG && s->side_ok && absf(s->side_deg) < 30.0f) {
        return WF_EV_WALL;
    }
    if (turned > 80.0f * WF_DEG && s->side_front_mm < 0.7f * c->open_mm) {
        return WF_EV_WALL; /* the front ranger sees the wall's next face (a door behind: the rear does not) */
    }
    return turned > c->arc_max_deg * WF_DEG ? WF_EV_DONE : WF_EV_NONE;
}

/* Open floor: straight on until a wall is beside or ahead. */
static wf_event_t find_tick(ffr_state_t *st, const wf_sense_t *s)
{
    if (front_blocked(st, s)) {
        return WF_EV_FRONT;
    }
    hold(st, cruise(st, s));
    return s->side_ok ? WF_EV_WALL : WF_EV_NONE;
}

/* A full turn on the spot; remember the brightest heading. */
static wf_event_t scan_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float rate = c->scan_deg_s * WF_DEG;
    if (s->flame_sum > st->best_sum) {
        st->best_sum = s->flame_sum;
        st->best_rad = st->heading_rad;
    }
    st->cmd_v = 0.0f;
    st->cmd_w = rate;
    st->target_rad += wf_wrap(st->heading_rad - st->entered_rad); /* turned so far */
    st->entered_rad = st->heading_rad;
    if (st->target_rad < 2.0f * WF_PI) {
        return WF_EV_NONE;
    }
    st->cmd_w = 0.0f;
    return st->best_sum >= c->flame_detect ? WF_EV_FLAME : WF_EV_NO_FLAME;
}

/* Towards the flame, steering by the two sensors' imbalance. */
static wf_event_t approach_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float lim = c->max_yaw_deg_s * WF_DEG;
    float bal = s->flame_sum > 1.0f ? s->flame_diff / s->flame_sum : 0.0f;
    float w = c->flame_steer_deg_s * bal;
    /* a door's edge or a wall beside the way: the corner rangers push the robot off it */
    if (s->ir_mm[FFR_IR_LF] < c->guard_mm) {
        w -= c->guard_kp * (c->guard_mm - s->ir_mm[FFR_IR_LF]);
    }
    if (s->ir_mm[FFR_IR_RF] < c->guard_mm) {
        w += c->guard_kp * (c->guard_mm - s->ir_mm[FFR_IR_RF]);
    }
    st->cmd_v = c->approach_mm_s;
    st->cmd_w = clampf(w * WF_DEG, -lim, lim);
    if (s->flame_sum >= c->flame_near || s->ir_mm[FFR_IR_CF] < c->approach_stop_mm) {
        st->flame_ref = s->flame_sum; /* how bright it is when the fans start */
        return WF_EV_NEAR;
    }
    if (s->flame_sum < c->flame_detect) {
        if (st->below_ms == 0u) {
            st->below_ms = st->t_ms | 1u;
        } else if (st->t_ms - st->below_ms > 500u) {
            st->below_ms = 0u;
            if (++st->attempts > c->scan_attempts) {
                st->fail_code = WF_FAIL_LOST;
                return WF_EV_FAIL;
            }
            return WF_EV_LOST;
        }
    } else {
        st->below_ms = 0u;
    }
    return WF_EV_NONE;
}

/* Fans on, facing the flame, until it stays out. */
static wf_event_t extinguish_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float bal = s->flame_sum > 1.0f ? s->flame_diff / s->flame_sum : 0.0f;
    st->cmd_v = 0.0f;
    st->cmd_w = clampf(c->flame_steer_deg_s * WF_DEG * bal, -0.5f, 0.5f);
    /* out: below flame_out, or (ambient light, an offset) below out_fraction of the start */
    float out = c->out_fraction * st->flame_ref;
    if (s->flame_sum < (out > c->flame_out ? out : c->flame_out)) {
        st->cmd_w = 0.0f;
        if (st->below_ms == 0u) {
            st->below_ms = st->t_ms | 1u;
        } else if (st->t_ms - st->below_ms >= c->out_confirm_ms) {
            return WF_EV_OUT;
        }
    } else {
        st->below_ms = 0u;
    }
    if (since_ms(st) > c->fan_max_ms) {
        st->fail_code = WF_FAIL_NOT_OUT;
        return WF_EV_FAIL;
    }
    return WF_EV_NONE;
}

/* To the odometry point goal, in a straight line: forwards when it lies
 * ahead, backwards when behind (back along the way the robot came: after the
 * flame, no turn on the spot where the walls may be close). */
static wf_event_t goto_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float dx = st->goal_x_mm - st->x_mm;
    float dy = st->goal_y_mm - st->y_mm;
    float d = wf_sqrt(dx * dx + dy * dy);
    float bearing = wf_atan2(dy, dx);
    float err = wf_wrap(bearing - st->heading_rad);
    float dir = 1.0f;
    (void)s;
    if (d < 15.0f) {
        st->cmd_v = 0.0f;
        st->cmd_w = 0.0f;
        return WF_EV_DONE;
    }
    if (absf(err) > 0.5f * WF_PI) { /* behind: back up, the rear towards it */
        dir = -1.0f;
        err = wf_wrap(err + WF_PI);
    }
    if (d < 40.0f && absf(err) > 30.0f * WF_DEG) { /* passed it */
        st->cmd_v = 0.0f;
        st->cmd_w = 0.0f;
        return WF_EV_DONE;
    }
    st->target_rad = wf_wrap(st->heading_rad + err);
    if (absf(err) > 25.0f * WF_DEG) { /* far off the line: turn first */
        (void)turn_to(st, c->turn_deg_s);
        return WF_EV_NONE;
    }
    hold(st, dir * clampf(d * 2.0f, 40.0f, c->approach_mm_s));
    return WF_EV_NONE;
}

/* Home's circle: its ring is a white line. The line sensor crossed it once
 * (entering); straight on to the crossing out: the middle of that chord is
 * inside the circle whatever the chord. */
static void sensor_xy(const ffr_state_t *st, float *x, float *y)
{
    *x = st->x_mm + st->cfg.line_sensor_x_mm * wf_cos(st->heading_rad);
    *y = st->y_mm + st->cfg.line_sensor_x_mm * wf_sin(st->heading_rad);
}

static void home(ffr_state_t *st)
{
    sensor_xy(st, &st->goal_x_mm, &st->goal_y_mm);
    st->target_rad = st->heading_rad;
    st->home_phase = 0u;
}

static wf_event_t home_tick(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    if (st->home_phase == 0u) {
        hold(st, 0.5f * c->approach_mm_s);
        if ((s->line_edge && since_mm(st) > 40.0f) || front_blocked(st, s) || since_mm(st) > 400.0f) {
            float x, y;
            sensor_xy(st, &x, &y);
            st->goal_x_mm = 0.5f * (st->goal_x_mm + x);
            st->goal_y_mm = 0.5f * (st->goal_y_mm + y);
            st->home_phase = 1u;
        }
        return WF_EV_NONE;
    }
    return goto_tick(st, s);
}

static wf_event_t stop_tick(ffr_state_t *st, const wf_sense_t *s)
{
    (void)s;
    st->cmd_v = 0.0f;
    st->cmd_w = 0.0f;
    return WF_EV_NONE;
}

/* ---- the table -------------------------------------------------------- */

/* Events every travelling state shares: home, give up. A line's scan waits
 * for FOLLOW (the only row with a LINE transition), beside a straight wall
 * with room to turn on the spot. */
#define TRAVEL [WF_EV_HOME] = WF_HOME, [WF_EV_FAIL] = WF_FAILED

static const wf_state_row_t k_table[WF_STATE_COUNT] = {
    [WF_IDLE] = {0, idle_tick, {[WF_EV_DONE] = WF_START_TURN, [WF_EV_FAIL] = WF_FAILED}},
    [WF_START_TURN] = {start_turn, turn_tick,
                       {[WF_EV_DONE] = WF_FIND_WALL, [WF_EV_FAIL] = WF_FAILED}},
    [WF_FOLLOW] = {follow_entry, follow_tick,
                   {[WF_EV_FRONT] = WF_TURN_AWAY, [WF_EV_OPEN] = WF_CORNER, [WF_EV_LINE] = WF_SCAN, TRAVEL}},
    [WF_CORNER] = {keep_heading, corner_tick,
                   {[WF_EV_DONE] = WF_ARC, [WF_EV_WALL] = WF_FOLLOW, [WF_EV_FRONT] = WF_TURN_AWAY, TRAVEL}},
    [WF_ARC] = {0, arc_tick,
                {[WF_EV_WALL] = WF_FOLLOW, [WF_EV_DONE] = WF_FIND_WALL, [WF_EV_FRONT] = WF_TURN_AWAY, TRAVEL}},
    [WF_TURN_AWAY] = {turn_away, turn_tick, {[WF_EV_DONE] = WF_FOLLOW, TRAVEL}},
    [WF_FIND_WALL] = {keep_heading, find_tick,
                      {[WF_EV_WALL] = WF_FOLLOW, [WF_EV_FRONT] = WF_TURN_AWAY, TRAVEL}},
    [WF_SCAN] = {scan_start, scan_tick,
                 {[WF_EV_FLAME] = WF_AIM, [WF_EV_NO_FLAME] = WF_RESUME, [WF_EV_FAIL] = WF_FAILED}},
    [WF_AIM] = {aim, turn_tick, {[WF_EV_DONE] = WF_APPROACH, [WF_EV_FAIL] = WF_FAILED}},
    [WF_APPROACH] = {0, approach_tick,
                     {[WF_EV_NEAR] = WF_EXTINGUISH, [WF_EV_LOST] = WF_SCAN, [WF_EV_FAIL] = WF_FAILED}},
    [WF_EXTINGUISH] = {extinguish, extinguish_tick,
                       {[WF_EV_OUT] = WF_GOTO, [WF_EV_FAIL] = WF_FAILED}},
    [WF_GOTO] = {back_to_scan, goto_tick, {[WF_EV_DONE] = WF_RESUME, [WF_EV_FAIL] = WF_FAILED}},
    [WF_RESUME] = {resume, turn_tick, {[WF_EV_DONE] = WF_RESUME_PREV, [WF_EV_FAIL] = WF_FAILED}},
    [WF_HOME] = {home, home_tick, {[WF_EV_DONE] = WF_DONE, [WF_EV_FAIL] = WF_FAILED}},
    [WF_DONE] = {done, stop_tick, {0}},
    [WF_FAILED] = {failed, stop_tick, {0}},
};

/* outputs.state's names (ffr_names(FFR_NAMES_STATE)), in wf_state_code_t order. */
static const char *const k_names[WF_STATE_COUNT] = {
    [WF_IDLE] = "IDLE", [WF_START_TURN] = "START_TURN", [WF_FOLLOW] = "FOLLOW", [WF_CORNER] = "CORNER",
    [WF_ARC] = "ARC", [WF_TURN_AWAY] = "TURN_AWAY", [WF_FIND_WALL] = "FIND_WALL", [WF_SCAN] = "SCAN",
    [WF_AIM] = "AIM", [WF_APPROACH] = "APPROACH", [WF_EXTINGUISH] = "EXTINGUISH",
    [WF_GOTO] = "GOTO", [WF_RESUME] = "RESUME", [WF_HOME] = "HOME", [WF_DONE] = "DONE", [WF_FAILED] = "FAILED",
};

const wf_state_row_t *wf_state_table(void)
{
    return k_table;
}

const char *const *wf_state_names(void)
{
    return k_names;
}
