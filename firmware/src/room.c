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

static float flame_sum(const ffr_inputs_t *in) { return (float)in->flame[0] + (float)in->flame[1]; }

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
    phase(st, RP_SCAN);
}

void ffr_room_begin(ffr_state_t *st, uint8_t room)
{
    st->room.room = room;
    st->room.attempts = 0;
    st->room.flame_found = 0;
    st->room.below_since_ms = 0;
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

/* keep off the side walls while driving freely inside a room */
static float side_repulsion(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    float w = 0.0f;
    float near = cfg->body_half_width_mm + 60.0f;
    int side;
    for (side = 0; side < 2; ++side) {
        ffr_wall_t wall = ffr_wall_estimate(cfg, st->ir_mm, side);
        if (wall.valid && wall.dist_mm < near) {
            float push = (near - wall.dist_mm) * 0.02f; /* rad/s per mm */
            w += side == FFR_SIDE_LEFT ? -push : push;
        }
    }
    return w;
}

int ffr_room_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    const float sig = flame_sum(in);
    const float moved = st->odo.dist_mm - r->phase_start_mm;
    const uint32_t elapsed = st->t_ms - r->phase_start_ms;

    switch (r->phase) {
    case RP_ENTER_LINE:
        if (st->lines.edge) {
            st->flags |= FFR_FLAG_IN_ROOM;
            phase(st, RP_ENTER_IN);
        } else if (moved > cfg->room_line_max_mm) {
            ffr_fail(st, FFR_FAIL_NO_LINE);
            return 0;
        }
        ffr_drive_heading(st, r->entry_heading_rad, cfg->room_speed_mm_s);
        return 0;
    case RP_ENTER_IN:
        if (moved >= cfg->room_entry_mm || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            r->scan_x_mm = st->odo.x_mm;
            r->scan_y_mm = st->odo.y_mm;
            begin_scan(st);
            return 0;
        }
        ffr_drive_heading(st, r->entry_heading_rad,
                          ffr_clampf(2.0f * (cfg->room_entry_mm - moved) + 60.0f, 60.0f, cfg->room_speed_mm_s));
        return 0;
    case RP_SCAN: {
        float turned = ffr_absf(st->odo.heading_rad - r->start_heading_rad);
        float dir = cfg->scan_dir ? -1.0f : 1.0f;
        if (sig > r->best_signal) {
            r->best_signal = sig;
            r->best_heading_rad = st->odo.heading_rad;
        }
        if (r->best_signal >= cfg->flame_detect && sig < 0.6f * r->best_signal) {
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
        float bal;
        float v;
        if (st->lines.edge || ffr_front_distance(cfg, st->ir_mm) < cfg->approach_stop_mm) {
            ffr_stop(st);
            phase(st, RP_EXTINGUISH);
            return 0;
        }
        if (sig < 0.5f * cfg->flame_detect) {
            /* lost it (or it went out by itself): look again from here */
            begin_scan(st);
            return 0;
        }
        bal = ((float)in->flame[0] - (float)in->flame[1]) / (sig > 1.0f ? sig : 1.0f);
        v = ffr_proximity_speed(cfg, st->ir_mm, cfg->approach_speed_mm_s);
        st->cmd_v_mm_s = v;
        st->cmd_w_rad_s = ffr_clampf(cfg->heading_kp * bal * cfg->flame_steer_deg * FFR_DEG
                                         + side_repulsion(st),
                                     -cfg->turn_rate_deg_s * FFR_DEG, cfg->turn_rate_deg_s * FFR_DEG);
        return 0;
    }
    case RP_EXTINGUISH:
        ffr_stop(st);
        st->fan = 1;
        if (sig < cfg->flame_out) {
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
            phase(st, RP_EXTINGUISH);
        }
        return 0;
    case RP_VERIFY:
        ffr_stop(st);
        st->fan = 0;
        if (sig >= cfg->flame_out) {
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
    case RP_BACK_TURN: {
        float dx = r->scan_x_mm - st->odo.x_mm;
        float dy = r->scan_y_mm - st->odo.y_mm;
        if (dx * dx + dy * dy < 30.0f * 30.0f) {
            phase(st, RP_LEAVE_TURN);
            return 0;
        }
        if (turn_to(st, closest(st->odo.heading_rad, ffr_atan2f(dy, dx)))) {
            phase(st, RP_BACK_DRIVE);
        }
        return 0;
    }
    case RP_BACK_DRIVE: {
        float dx = r->scan_x_mm - st->odo.x_mm;
        float dy = r->scan_y_mm - st->odo.y_mm;
        float dist = ffr_sqrtf(dx * dx + dy * dy);
        float ahead = dx * ffr_cosf(st->odo.heading_rad) + dy * ffr_sinf(st->odo.heading_rad);
        if (dist < 15.0f || ahead <= 0.0f) {
            ffr_stop(st);
            phase(st, RP_LEAVE_TURN);
            return 0;
        }
        ffr_drive_heading(st, closest(st->odo.heading_rad, ffr_atan2f(dy, dx)),
                          ffr_clampf(2.0f * dist + 60.0f, 60.0f, cfg->room_speed_mm_s));
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
        return 0;
    case RP_LEAVE_OUT:
        if (moved >= cfg->room_exit_mm || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            st->rooms_searched = (uint8_t)(st->rooms_searched + 1u);
            return 1;
        }
        ffr_drive_heading(st, st->route.heading_ref_rad,
                          ffr_clampf(2.0f * (cfg->room_exit_mm - moved) + 60.0f, 60.0f, cfg->room_speed_mm_s));
        return 0;
    default:
        ffr_fail(st, FFR_FAIL_BAD_ROUTE);
        return 0;
    }
}
