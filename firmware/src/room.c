/*
 * The room task (the paper's Fig. 11) and the flame task (Fig. 12).
 *
 * Enter: straight through the door until the doorway line, then a little
 * further. Scan: rotate in place and remember the heading of the strongest
 * flame signal; stop once the signal has clearly passed its peak. Approach:
 * drive toward the flame, steering by the two flame sensors' balance, until
 * the line sensor meets the candle circle. Extinguish: fans on until the
 * flame is gone, fans off, watch that it stays out. Leave: back to where the
 * scan was made (odometry inside one room is short and reliable), face the
 * door, drive out across the doorway line.
 */
#include "ffr_internal.h"

enum {
    RP_ENTER_LINE = 0,
    RP_ENTER_IN,
    RP_SCAN,
    RP_TURN_BEST,
    RP_APPROACH,
    RP_EXTINGUISH,
    RP_VERIFY,
    RP_BACK_TURN,
    RP_BACK_DRIVE,
    RP_LEAVE_TURN,
    RP_LEAVE_LINE,
    RP_LEAVE_OUT
};

/* A flame within the fans' reach reads far above the detection threshold:
 * on axis at 30 cm about 20x, at the edge of the sensors' view still ~8x. */
#define FLAME_NEAR 4.0f
/* share of each new flame reading in the filtered signal (a ~40 ms average) */
#define FLAME_FILTER 0.25f
/* contest lines are 2.5 cm wide, walls about 2 cm thick */
#define DOOR_WALL_FACE_MM 25.0f
/* the flame's balance (left - right over both) about 20 degrees off the heading */
#define FLAME_AIM_BAL 0.5f
/* the flame sum (over the dark level) at about 26 cm of the fans, in units
 * of flame_detect: the fans (30 cm reach) put it out from there */
#define FLAME_REACH 14.0f
/* a scan's peak this strong (x flame_detect) is no wall's reflection:
 * chosen, 2 (the realistic profile's reflectance 0.3 gave peaks of 1.2-1.3
 * facing a wall 20 cm away with the flame behind) */
#ifndef SCAN_SURE
#define SCAN_SURE 2.0f
#endif
/* chosen: a wall ahead nearer than this (front distance) can mirror the flame
 * strongly enough to pass for it */
#ifndef SCAN_WALL_MM
#define SCAN_WALL_MM 400.0f
#endif
/* room_state_t.flame_found: none, found, and found with the approach stopped
 * by the flame's strength (FLAME_REACH) beside a wall, then going closer */
enum { FOUND = 1, FOUND_BY_STRENGTH = 2, FOUND_CLOSER = 3 };
/* clearance kept beyond the body's corner radius for the scan's turn in place */
#define SCAN_MARGIN_MM 35.0f

/* flame_detect and flame_out are set for this dark level (2 x 40 counts) */
#define FLAME_DARK_NOMINAL 80.0f

/* both flame sensors, measured from the dark level learned so far (mission.c) */
static float flame_sum(const ffr_state_t *st, const ffr_inputs_t *in)
{
    return (float)in->flame[0] + (float)in->flame[1] - (st->flame_dark - FLAME_DARK_NOMINAL);
}

/* the unwrapped heading closest to `heading` that points the way `dir` does */
static float closest(float heading, float dir) { return heading + ffr_wrap_pi(dir - heading); }

static void phase(ffr_state_t *st, uint8_t p)
{
    static const uint8_t codes[] = {
        FFR_ST_ENTER, FFR_ST_ENTER, FFR_ST_SCAN, FFR_ST_SCAN, FFR_ST_APPROACH, FFR_ST_EXTINGUISH,
        FFR_ST_VERIFY, FFR_ST_TO_DOOR, FFR_ST_TO_DOOR, FFR_ST_EXIT, FFR_ST_EXIT, FFR_ST_EXIT};
    st->room.phase = p;
    st->room.phase_start_mm = st->odo.dist_mm;
    st->room.phase_start_ms = st->t_ms;
    st->state = codes[p];
}

static void begin_scan(ffr_state_t *st)
{
    st->room.start_heading_rad = st->odo.heading_rad;
    st->room.best_signal = 0.0f;
    st->room.best_heading_rad = st->odo.heading_rad;
    st->room.best_front_mm = 0.0f;
    phase(st, RP_SCAN);
}

void ffr_room_begin(ffr_state_t *st, uint8_t room)
{
    st->room.room = room;
    st->room.attempts = 0;
    st->room.flame_found = 0;
    st->room.below_since_ms = 0;
    st->room.flame_f = 0.0f;
    st->room.entry_heading_rad = st->route.heading_ref_rad;
    phase(st, RP_ENTER_LINE);
}

static int turn_to(ffr_state_t *st, float target)
{
    ffr_stop(st);
    st->cmd_w_rad_s = ffr_turn_yaw(&st->cfg, st->odo.heading_rad, target);
    if (ffr_turn_done(&st->cfg, &st->odo, target)) {
        ffr_stop(st);
        return 1;
    }
    return 0;
}

/*
 * Is a flame seen in direction `dir` from the scan point outside the room,
 * seen through the door the robot came in by? The doorway line runs through
 * the point where it was crossed, square to the entry heading; a ray that
 * leaves through it within half a hallway of that point leaves by the door.
 * No candle can stand on the short stretch of that ray inside the room: the
 * contest keeps the candle circle 33 cm clear of the doorway.
 */
static int through_door(const ffr_state_t *st, float dir)
{
    const ffr_room_state_t *r = &st->room;
    float ce = ffr_cosf(r->entry_heading_rad);
    float se = ffr_sinf(r->entry_heading_rad);
    float dx = r->scan_x_mm - r->line_x_mm;
    float dy = r->scan_y_mm - r->line_y_mm;
    float depth = dx * ce + dy * se;  /* how far in the scan point is        */
    float lat = -dx * se + dy * ce;   /* and how far to the side of the path */
    float back = -ffr_cosf(dir - r->entry_heading_rad);
    float t;
    if (back <= 0.05f || depth <= 0.0f) {
        return 0;
    }
    t = depth / back;
    lat += t * ffr_sinf(dir - r->entry_heading_rad);
    return ffr_absf(lat) < st->cfg.hallway_half_mm;
}

/* The heading's and the entry heading's cosine and sine, worked out once a
 * tick for every depth_in of that tick. */
typedef struct {
    float c, s;   /* heading       */
    float ce, se; /* entry heading */
} door_frame_t;

static door_frame_t door_frame(const ffr_state_t *st)
{
    door_frame_t f;
    f.c = ffr_cosf(st->odo.heading_rad);
    f.s = ffr_sinf(st->odo.heading_rad);
    f.ce = ffr_cosf(st->room.entry_heading_rad);
    f.se = ffr_sinf(st->room.entry_heading_rad);
    return f;
}

/* A body-frame point relative to where the doorway line was crossed: depth
 * into the room (along the entry heading) and lateral offset, mm. */
static float depth_in(const ffr_state_t *st, const door_frame_t *f, float bx, float by, float *lateral)
{
    const ffr_room_state_t *r = &st->room;
    float dx = st->odo.x_mm + f->c * bx - f->s * by - r->line_x_mm;
    float dy = st->odo.y_mm + f->s * bx + f->c * by - r->line_y_mm;
    if (lateral) {
        *lateral = -dx * f->se + dy * f->ce;
    }
    return dx * f->ce + dy * f->se;
}

/* Is the robot's nose at the doorway it came in by (its line, or about to
 * reach it)? Approaching a flame, that means the flame is out there. */
static int nose_in_doorway(const ffr_state_t *st, const door_frame_t *f)
{
    float lat;
    float depth = depth_in(st, f, st->cfg.line_sensor_x_mm, 0.0f, &lat);
    return depth < 60.0f && ffr_absf(lat) < st->cfg.hallway_half_mm;
}

/*
 * The wall the door is in: the robot crossed its doorway line, so odometry
 * knows where that wall runs (through the crossing, square to the entry
 * heading). A candle by that wall is approached along it, and the door's jamb
 * is a thin wall end the rangers may not see: stop before a front corner
 * reaches the wall's line, as if it were seen. Odometry inside one room is
 * short and reliable, hence half the rangers' margin. A front corner nearing
 * the line turns the robot toward running along the wall (a yaw returned, as
 * the rangers' guard does): a candle hugging that wall is then approached
 * beside it instead of nose first, which stopped the robot with the fans out
 * of reach.
 */
static float door_wall_guard(const ffr_state_t *st, const door_frame_t *f, float bal, int *stop)
{
    const ffr_config_t *cfg = &st->cfg;
    /* only by the door: farther along, the wall is a wall the rangers see, and
     * the odometry heading's error (a few degrees after a scan) grows with the
     * distance from the crossing point */
    const float reach = cfg->hallway_half_mm + cfg->guard_side_mm;
    float w = 0.0f;
    int k;
    for (k = 0; k < 2; ++k) {
        float lat;
        float d = depth_in(st, f, cfg->body_front_mm, k ? cfg->body_half_width_mm : -cfg->body_half_width_mm, &lat);
        if (ffr_absf(lat) >= reach) {
            continue;
        }
        /* the doorway line lies on the wall's centre line and is first seen at
         * its near edge: the wall's room-side face is about a line width deeper */
        if (d < DOOR_WALL_FACE_MM + 0.5f * cfg->guard_stop_mm) {
            *stop = 1;
        } else if (d < DOOR_WALL_FACE_MM + cfg->guard_side_mm) {
            /* left corner (k = 1) near: turn right, and the other way round;
             * less as the turn takes the flame off toward that side, none
             * with it FLAME_AIM_BAL off: the fans must still reach it */
            float push = (DOOR_WALL_FACE_MM + cfg->guard_side_mm - d) * 0.03f;
            float keep = ffr_clampf(1.0f + (k ? -bal : bal) / FLAME_AIM_BAL, 0.0f, 1.0f);
            w += (k ? -push : push) * keep;
        }
    }
    return w;
}

/*
 * Approach guard: the rangers' hit points near the body. Returns a yaw rate
 * that steers away from a wall beside the front half, and sets *stop when a
 * wall is about to touch a front corner. The GP2D12 folds back under 10 cm,
 * so this must act while the wall is still seen, not at contact.
 */
static float approach_guard(const ffr_state_t *st, const door_frame_t *f, float bal, int *stop, int *near)
{
    const ffr_config_t *cfg = &st->cfg;
    static const int rangers[3] = {FFR_IR_CF, FFR_IR_LF, FFR_IR_RF};
    float w = 0.0f;
    float wd;
    int k;
    *stop = 0;
    *near = 0;
    for (k = 0; k < 3; ++k) {
        int i = rangers[k];
        float d = st->ir_mm[i];
        float px = st->ir_geom.hit_x_mm[i];
        float py = st->ir_geom.hit_y_mm[i];
        float side_gap, front_gap;
        if (!ffr_ir_valid(cfg, d)) {
            continue;
        }
        side_gap = ffr_absf(py) - cfg->body_half_width_mm;
        front_gap = px - cfg->body_front_mm;
        if (px > 0.0f && side_gap < cfg->guard_side_mm && front_gap < cfg->guard_side_mm) {
            float push = (cfg->guard_side_mm - (side_gap > 0.0f ? side_gap : 0.0f)) * 0.03f;
            if (i != FFR_IR_CF) {
                w += py > 0.0f ? -push : push;
                *near = 1;
            }
            if (side_gap < cfg->guard_stop_mm && front_gap < cfg->guard_stop_mm) {
                *stop = 1;
            }
        }
    }
    wd = door_wall_guard(st, f, bal, stop);
    if (wd != 0.0f) {
        *near = 1;
    }
    return w + wd;
}

/*
 * Leaving: the heading back out of the door is odometry's, and a room's scan
 * (one turn or more in place on slipping tracks) can leave it 10-15 degrees
 * off. A front corner ranger's hit beside the front half, nearer the body's
 * side than guard_side_mm, steers away from it (the approach guard's law),
 * so the robot leaves along the jamb instead of into the wall beyond it.
 */
float ffr_leave_guard(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    static const int rangers[2] = {FFR_IR_LF, FFR_IR_RF};
    float w = 0.0f;
    int k;
    for (k = 0; k < 2; ++k) {
        int i = rangers[k];
        float px = st->ir_geom.hit_x_mm[i];
        float py = st->ir_geom.hit_y_mm[i];
        float side_gap = ffr_absf(py) - cfg->body_half_width_mm;
        if (!ffr_ir_valid(cfg, st->ir_mm[i]) || px <= 0.0f || px - cfg->body_front_mm >= cfg->guard_side_mm
            || side_gap >= cfg->guard_side_mm) {
            continue;
        }
        {
            float push = (cfg->guard_side_mm - (side_gap > 0.0f ? side_gap : 0.0f)) * 0.03f;
            w += py > 0.0f ? -push : push;
        }
    }
    return w;
}

/*
 * The scan turns in place, sweeping a circle of the body's corner radius: a
 * robot that came through the door off-centre and has a side wall closer
 * than that edges away from it while it drives in (a heading offset, so the
 * heading hold still applies).
 */
static float scan_room_offset(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    float need = ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm)
                 + SCAN_MARGIN_MM;
    float off = 0.0f;
    int side;
    for (side = 0; side < 2; ++side) {
        ffr_wall_t w = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, side);
        if (w.valid && w.dist_mm < need) {
            /* left wall: turn right (negative), and the other way round */
            off += (side == FFR_SIDE_LEFT ? -1.0f : 1.0f) * (need - w.dist_mm) * 0.5f * FFR_DEG;
        }
    }
    return ffr_clampf(off, -20.0f * FFR_DEG, 20.0f * FFR_DEG);
}

int ffr_room_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    float sig = flame_sum(st, in);
    const float moved = st->odo.dist_mm - r->phase_start_mm;
    /* whether the flame is out is decided on a filtered signal: near the dark
     * level, sensor noise alone crosses flame_out now and then */
    r->flame_f += FLAME_FILTER * (sig - r->flame_f);
    const uint32_t elapsed = st->t_ms - r->phase_start_ms;

    switch (r->phase) {
    case RP_ENTER_LINE:
        if (st->lines.edge) {
            st->flags |= FFR_FLAG_IN_ROOM;
            /* the line is under the line sensor, ahead of the origin */
            r->line_x_mm = st->odo.x_mm + cfg->line_sensor_x_mm * ffr_cosf(st->odo.heading_rad);
            r->line_y_mm = st->odo.y_mm + cfg->line_sensor_x_mm * ffr_sinf(st->odo.heading_rad);
            phase(st, RP_ENTER_IN);
        } else if (moved > cfg->room_line_max_mm) {
            ffr_fail(st, FFR_FAIL_NO_LINE);
            return 0;
        }
        ffr_drive_heading(st, r->entry_heading_rad, cfg->room_speed_mm_s);
        return 0;
    case RP_ENTER_IN:
        /* deep enough that a candle along the door's wall can be approached
         * with room to spare; the candle circle or a wall ahead stops it sooner */
        if (moved >= cfg->room_entry_mm || st->lines.edge
            || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            r->scan_x_mm = st->odo.x_mm;
            r->scan_y_mm = st->odo.y_mm;
            begin_scan(st);
            return 0;
        }
        ffr_drive_heading(st, r->entry_heading_rad + scan_room_offset(st),
                          ffr_stopping_speed(cfg->room_entry_mm - moved, cfg->room_speed_mm_s));
        return 0;
    case RP_SCAN: {
        float turned = ffr_absf(st->odo.heading_rad - r->start_heading_rad);
        float dir = cfg->scan_dir ? -1.0f : 1.0f;
        if (through_door(st, st->odo.heading_rad)) {
            sig = 0.0f; /* a flame out there is not this room's */
        }
        if (sig > r->best_signal) {
            r->best_signal = sig;
            r->best_heading_rad = st->odo.heading_rad;
            r->best_front_mm = ffr_front_distance(cfg, st->ir_mm);
        }
        /* past the peak: stop early, unless a weak peak (below SCAN_SURE x
         * flame_detect) was seen facing a wall near ahead (SCAN_WALL_MM): it
         * may be the flame's image in that wall (white walls reflect) while
         * the flame itself is still behind. Then the whole turn, and the
         * strongest. */
        if (r->best_signal >= cfg->flame_detect && sig < 0.6f * r->best_signal
            && (r->best_signal >= SCAN_SURE * cfg->flame_detect || r->best_front_mm > SCAN_WALL_MM)) {
            r->flame_found = 1;
            st->flags |= FFR_FLAG_FLAME_SEEN;
            phase(st, RP_TURN_BEST);
            ffr_stop(st);
            return 0;
        }
        if (turned >= 2.0f * FFR_PI) {
            if (r->best_signal >= cfg->flame_detect) {
                r->flame_found = 1;
                st->flags |= FFR_FLAG_FLAME_SEEN;
                phase(st, RP_TURN_BEST);
            } else {
                phase(st, RP_LEAVE_TURN);
            }
            ffr_stop(st);
            return 0;
        }
        ffr_stop(st);
        st->cmd_w_rad_s = dir * cfg->scan_rate_deg_s * FFR_DEG;
        return 0;
    }
    case RP_TURN_BEST:
        if (turn_to(st, r->best_heading_rad)) {
            phase(st, RP_APPROACH);
        }
        return 0;
    case RP_APPROACH: {
        /* the flame's balance: + on the left */
        float bal = ((float)in->flame[0] - (float)in->flame[1]) / (sig > 1.0f ? sig : 1.0f);
        float v;
        int guard_stop, guard_near;
        const door_frame_t df = door_frame(st);
        float guard_w = approach_guard(st, &df, bal, &guard_stop, &guard_near);
        /* beside a wall with the flame already within the fans' reach: stop
         * here rather than creep on along the wall; a part reading long
         * lets a front corner reach the wall before the guard stops it */
        int reach_stop = 0;
        if (guard_near && sig >= FLAME_REACH * cfg->flame_detect && r->flame_found != FOUND_CLOSER
            && !guard_stop) {
            reach_stop = 1;
        }
        if (st->lines.edge || guard_stop || reach_stop
            || ffr_front_distance(cfg, st->ir_mm) < cfg->approach_stop_mm) {
            ffr_stop(st);
            /* stopped by the flame's strength alone (nothing else stops it
             * here): if the fans do not put it out, it was farther than its
             * strength said -- flames differ in size -- and the robot goes
             * closer */
            r->flame_found = (reach_stop && !st->lines.edge) ? FOUND_BY_STRENGTH : FOUND;
            if (nose_in_doorway(st, &df) || (!st->lines.edge && sig < FLAME_NEAR * cfg->flame_detect)) {
                /* at the doorway it came in by, or stopped by a wall with the
                 * flame still far: the flame is not in this room but seen
                 * through its door. Back out and search on. */
                r->flame_found = 0;
                phase(st, RP_BACK_DRIVE);
                return 0;
            }
            phase(st, RP_EXTINGUISH);
            return 0;
        }
        if (sig < 0.5f * cfg->flame_detect) {
            /* lost it (or it went out by itself): look again from here */
            begin_scan(st);
            return 0;
        }
        v = ffr_proximity_speed(cfg, st->ir_mm, cfg->approach_speed_mm_s);
        st->cmd_v_mm_s = v;
        st->cmd_w_rad_s = ffr_clampf(cfg->heading_kp * bal * cfg->flame_steer_deg * FFR_DEG + guard_w,
                                     -cfg->turn_rate_deg_s * FFR_DEG, cfg->turn_rate_deg_s * FFR_DEG);
        return 0;
    }
    case RP_EXTINGUISH:
        ffr_stop(st);
        st->fan = 1;
        if (r->flame_f < cfg->flame_out) {
            if (r->below_since_ms == 0u) {
                r->below_since_ms = st->t_ms == 0u ? 1u : st->t_ms;
            }
            if (st->t_ms - r->below_since_ms >= cfg->flame_out_confirm_ms) {
                st->fan = 0;
                phase(st, RP_VERIFY);
            }
        } else {
            r->below_since_ms = 0u;
        }
        if (st->fan && elapsed >= cfg->fan_timeout_ms) {
            r->attempts = (uint8_t)(r->attempts + 1u);
            if (r->attempts >= cfg->fan_attempts) {
                ffr_fail(st, FFR_FAIL_NOT_OUT);
                return 0;
            }
            if (r->flame_found == FOUND_BY_STRENGTH) {
                /* not out from where its strength said it was in reach: on
                 * toward it until the line, a wall or the candle stops the
                 * robot, then the fans again */
                r->flame_found = FOUND_CLOSER;
                st->fan = 0;
                phase(st, RP_APPROACH);
                return 0;
            }
            phase(st, RP_EXTINGUISH);
        }
        return 0;
    case RP_VERIFY:
        ffr_stop(st);
        st->fan = 0;
        if (r->flame_f >= cfg->flame_out) {
            r->below_since_ms = 0u;
            r->attempts = (uint8_t)(r->attempts + 1u);
            if (r->attempts >= cfg->fan_attempts) {
                ffr_fail(st, FFR_FAIL_NOT_OUT);
                return 0;
            }
            phase(st, RP_EXTINGUISH);
        } else if (elapsed >= cfg->verify_ms) {
            st->flags |= FFR_FLAG_EXTINGUISHED;
            phase(st, RP_BACK_TURN);
        }
        return 0;
    case RP_BACK_TURN:
        /* no turning in place by the candle: it may stand by a wall. The scan
         * point is behind (the approach drove away from it), so reverse. */
        phase(st, RP_BACK_DRIVE);
        return 0;
    case RP_BACK_DRIVE: {
        float dx = r->scan_x_mm - st->odo.x_mm;
        float dy = r->scan_y_mm - st->odo.y_mm;
        float dist = ffr_sqrtf(dx * dx + dy * dy);
        float behind = -(dx * ffr_cosf(st->odo.heading_rad) + dy * ffr_sinf(st->odo.heading_rad));
        if (dist < 15.0f || behind <= 0.0f) {
            ffr_stop(st);
            phase(st, RP_LEAVE_TURN);
            return 0;
        }
        /* point the tail at the scan point while backing up */
        ffr_drive_heading(st, closest(st->odo.heading_rad, ffr_atan2f(-dy, -dx)),
                          -ffr_stopping_speed(dist, cfg->room_speed_mm_s));
        return 0;
    }
    case RP_LEAVE_TURN: {
        float target = closest(st->odo.heading_rad, r->entry_heading_rad + FFR_PI);
        if (turn_to(st, target)) {
            /* the corridor heading reversed: later turns stay square to the walls */
            st->route.heading_ref_rad = target;
            phase(st, RP_LEAVE_LINE);
        }
        return 0;
    }
    case RP_LEAVE_LINE:
        if (st->lines.edge) {
            st->flags &= (uint8_t)~FFR_FLAG_IN_ROOM;
            phase(st, RP_LEAVE_OUT);
        } else if (moved > cfg->room_line_max_mm + cfg->room_entry_mm) {
            ffr_fail(st, FFR_FAIL_NO_LINE);
            return 0;
        }
        ffr_drive_heading(st, st->route.heading_ref_rad, cfg->room_speed_mm_s);
        st->cmd_w_rad_s += ffr_leave_guard(st);
        return 0;
    case RP_LEAVE_OUT:
        if (moved >= cfg->room_exit_mm || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            st->rooms_searched = (uint8_t)(st->rooms_searched + 1u);
            return 1;
        }
        ffr_drive_heading(st, st->route.heading_ref_rad,
                          ffr_stopping_speed(cfg->room_exit_mm - moved, cfg->room_speed_mm_s));
        st->cmd_w_rad_s += ffr_leave_guard(st);
        return 0;
    default:
        ffr_fail(st, FFR_FAIL_BAD_ROUTE);
        return 0;
    }
}
