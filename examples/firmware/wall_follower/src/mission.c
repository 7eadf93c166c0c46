/*
 * mission.c - ffr_init and ffr_step: sense, run the current state's
 * behaviour, follow the state table, drive.
 */
#include "wall_follower.h"

void wf_enter(ffr_state_t *st, uint8_t state)
{
    const wf_state_row_t *row;
    if (state == WF_RESUME_PREV) {
        state = st->resume_state;
    }
    if (state >= WF_STATE_COUNT) {
        state = WF_FAILED;
    }
    row = &wf_state_table()[state];
    st->prev_state = st->state;
    st->state = state;
    st->entered_ms = st->t_ms;
    st->entered_mm = st->dist_mm;
    st->entered_rad = st->heading_rad;
    st->below_ms = 0u;
    st->fan = state == WF_EXTINGUISH ? 1u : 0u;
    if (row->entry != 0) {
        row->entry(st);
    }
}

void ffr_init(ffr_state_t *st, const ffr_config_t *cfg)
{
    uint8_t *p = (uint8_t *)st;
    uint32_t i;
    for (i = 0; i < (uint32_t)sizeof(*st); i++) {
        p[i] = 0u;
    }
    st->cfg = *cfg;
    st->side = 1.0f;
    st->scan_at_mm = -1.0f;
    st->pending_run_mm = -1.0f;
    st->last_line_mm = -1.0e6f;
    st->state = WF_IDLE;
}

/* Beside a straight wall at about wall_mm, nothing close ahead: turning on
 * the spot hits nothing the rangers could see. */
static int room_to_turn(const ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float e = s->side_mm - c->wall_mm;
    return s->side_ok && e > -30.0f && e < 60.0f && s->side_deg < 15.0f && s->side_deg > -15.0f
           && s->ir_mm[FFR_IR_CF] > c->front_mm + 80.0f;
}

/* Events that do not depend on the behaviour: a line (scan it after
 * entry_mm, or it is home's circle), the scan falling due, the clock. */
static wf_event_t common_event(ffr_state_t *st, const wf_sense_t *s)
{
    const struct ffr_config *c = &st->cfg;
    float r = wf_sqrt(st->x_mm * st->x_mm + st->y_mm * st->y_mm);
    const wf_state_row_t *row = &wf_state_table()[st->state];
    if (r > st->max_away_mm) {
        st->max_away_mm = r;
    }
    if (st->t_ms > c->mission_max_ms) {
        st->fail_code = WF_FAIL_TIMEOUT;
        return WF_EV_FAIL;
    }
    /* lines met driving forward only: turning on the spot, the sensor ahead of
     * the wheels sweeps a circle and may cross a line it has just crossed */
    if (s->line_edge && st->cmd_v > 1.0f && st->dist_mm - st->last_line_mm > c->line_holdoff_mm) {
        st->last_line_mm = st->dist_mm;
        if (st->lines < 255u) {
            st->lines++;
        }
        if (row->next[WF_EV_HOME] == 0u) {
            return WF_EV_NONE; /* approaching, backing: a candle's ring, not a doorway */
        }
        if (st->flags & FFR_FLAG_EXTINGUISHED) {
            /* the way back crosses the way in's doorways again: the line after them is home's
             * ring (odometry drifts; counting does not), or one near the start by odometry */
            st->doors_back++;
            st->flags = (uint8_t)(st->flags ^ FFR_FLAG_IN_ROOM);
            return st->doors_back > st->doors_at_scan || r < c->home_zone_mm ? WF_EV_HOME : WF_EV_NONE;
        }
        if (r < c->home_zone_mm) {
            if (st->max_away_mm <= c->away_mm) {
                return WF_EV_NONE; /* leaving home */
            }
            st->fail_code = WF_FAIL_NO_FLAME;
            return WF_EV_FAIL;
        }
        /* a doorway: the follower goes in and out of each room by the same door */
        st->doors++;
        if (st->doors & 1u) {
            st->flags = (uint8_t)(st->flags | FFR_FLAG_IN_ROOM);
            if (!(st->flags & FFR_FLAG_EXTINGUISHED)) {
                st->scan_at_mm = st->dist_mm + c->entry_mm;
            }
        } else {
            st->flags = (uint8_t)(st->flags & ~FFR_FLAG_IN_ROOM);
            st->scan_at_mm = -1.0f; /* never scan a room from outside its door */
        }
    }
    if (st->scan_at_mm >= 0.0f && st->dist_mm >= st->scan_at_mm && row->next[WF_EV_LINE] != 0u
        && room_to_turn(st, s)) {
        return WF_EV_LINE;
    }
    return WF_EV_NONE;
}

void ffr_step(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out)
{
    wf_sense_t s;
    wf_event_t ev, common;
    const wf_state_row_t *row;
    st->t_ms = in->t_ms;
    wf_odometry(st, in->enc);
    wf_sense(st, in, &s);
    if (st->state == WF_IDLE && in->start) {
        wf_enter(st, WF_START_TURN);
    }
    row = &wf_state_table()[st->state];
    common = common_event(st, &s);
    ev = row->tick(st, &s);
    if (common != WF_EV_NONE && row->next[common] != 0u) {
        ev = common;
    }
    if (ev != WF_EV_NONE && row->next[ev] != 0u) {
        uint8_t next = row->next[ev];
        if (ev == WF_EV_LINE) { /* a scan: come back to this behaviour (an arc: to following), this heading */
            st->resume_state = st->state == WF_ARC ? WF_FOLLOW : st->state;
            st->resume_rad = st->heading_rad;
        }
        wf_enter(st, next);
        if (st->state == WF_DONE || st->state == WF_FAILED) {
            st->cmd_v = 0.0f;
            st->cmd_w = 0.0f;
        }
    }
    wf_drive(st, st->cmd_v, st->cmd_w, out->pwm);
    if (st->state == WF_DONE || st->state == WF_FAILED || st->state == WF_IDLE) {
        out->pwm[0] = 0;
        out->pwm[1] = 0;
        st->v_ref[0] = 0.0f;
        st->v_ref[1] = 0.0f;
    }
    out->seq = in->seq;
    out->fan = st->fan;
    out->state = st->state;
    out->room = 0u;
    out->rooms_searched = st->rooms;
    out->line_count = st->lines;
    out->flags = st->flags;
    out->step = 0u;
    out->fail_code = st->fail_code;
    out->odo_x_mm = (int16_t)st->x_mm;
    out->odo_y_mm = (int16_t)st->y_mm;
    out->odo_heading_cdeg = (int16_t)(st->heading_rad / WF_DEG * 100.0f);
    out->reserved = 0;
}
