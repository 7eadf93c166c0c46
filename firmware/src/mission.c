/*
 * The top of the firmware: ffr_init and ffr_step. One step per tick: read
 * the sensors into engineering units, update odometry and the line counter,
 * run the current route step or room task, and turn its motion command into
 * PWM through the speed loops.
 */
#include "ffr_internal.h"

void ffr_fail(ffr_state_t *st, uint8_t code)
{
    st->state = FFR_ST_FAILED;
    st->fail_code = code;
    st->flags |= FFR_FLAG_FAILED;
    st->fan = 0;
    ffr_stop(st);
}

void ffr_init(ffr_state_t *st, const ffr_config_t *cfg)
{
    int i;
    st->cfg = *cfg;
    ffr_ir_geom_init(&st->ir_geom, &st->cfg);
    ffr_odometry_reset(&st->odo);
    ffr_speed_reset(&st->speed);
    ffr_lines_reset(&st->lines);
    ffr_openings_reset(&st->open);
    st->route.heading_ref_rad = 0.0f;
    st->route.target_rad = 0.0f;
    st->route.start_mm = 0.0f;
    st->route.goal_mm = 0.0f;
    st->route.case_turn_deg = 0;
    st->route.phase = 0;
    st->route.pc = 0;
    st->route.exit_wall_rad = FFR_EXIT_WALL_NONE;
    st->route.follow_mm = 0.0f;
    ffr_wall_cal_reset(&st->wall_cal);
    ffr_orient_reset(&st->orient, &st->odo);
    ffr_explore_reset(&st->explore);
    st->room.phase = 0;
    st->room.room = 0;
    st->room.attempts = 0;
    st->room.flame_found = 0;
    st->room.entry_heading_rad = 0.0f;
    st->room.scan_x_mm = 0.0f;
    st->room.scan_y_mm = 0.0f;
    st->room.line_x_mm = 0.0f;
    st->room.line_y_mm = 0.0f;
    st->room.start_heading_rad = 0.0f;
    st->room.best_signal = 0.0f;
    st->room.best_heading_rad = 0.0f;
    st->room.phase_start_mm = 0.0f;
    st->room.phase_start_ms = 0u;
    st->room.below_since_ms = 0u;
    st->room.flame_f = 0.0f;
    st->room.best_front_mm = 0.0f;
    st->room.exit_heading_rad = 0.0f;
    st->room.lost_since_ms = 0u;
    st->room.flame_near = 0;
    st->room.scan_lead = 0u;
    st->room.fans_early = 0u;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        st->ir_mm[i] = FFR_IR_NONE(cfg);
    }
    st->t_ms = 0u;
    st->last_t_ms = 0u;
    st->state = FFR_ST_IDLE;
    st->started = 0;
    st->flags = 0;
    st->rooms_searched = 0;
    st->returning = 0;
    st->fail_code = FFR_FAIL_NONE;
    st->fan = 0;
    st->reserved = 0;
    st->cmd_v_mm_s = 0.0f;
    st->cmd_w_rad_s = 0.0f;
    st->flame_ema = -1.0f; /* not primed */
    st->flame_dark = 0.0f;
}

static int16_t clamp_i16(float v)
{
    if (v > 32767.0f) {
        return 32767;
    }
    if (v < -32768.0f) {
        return -32768;
    }
    return (int16_t)(v >= 0.0f ? (int32_t)(v + 0.5f) : -(int32_t)(-v + 0.5f));
}

void ffr_step(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out)
{
    const ffr_config_t *cfg = &st->cfg;
    float dt;
    float before;
    int i;

    st->t_ms = in->t_ms;
    dt = st->odo.primed ? (float)(uint32_t)(in->t_ms - st->last_t_ms) * 0.001f : 0.01f;
    dt = ffr_clampf(dt, 0.001f, 0.1f);
    st->last_t_ms = in->t_ms;

    for (i = 0; i < FFR_IR_COUNT; ++i) {
        st->ir_mm[i] = ffr_ir_mv_to_mm(cfg, in->ir_mv[i]);
    }
    ffr_ir_geom_update(&st->ir_geom, cfg, st->ir_mm);
    /* the flame sensors' dark level (amplifier offset plus ambient light):
     * the lowest slowly filtered reading so far, most of it read with no
     * flame in view; room.c measures the flame above it */
    {
        float f = (float)in->flame[0] + (float)in->flame[1];
        if (st->flame_ema < 0.0f) {
            st->flame_ema = f;
            st->flame_dark = f;
        }
        st->flame_ema += 0.05f * (f - st->flame_ema);
        if (st->flame_ema < st->flame_dark) {
            st->flame_dark = st->flame_ema;
        }
    }
    before = st->odo.dist_mm;
    ffr_odometry_update(&st->odo, cfg, in->enc, dt);
    ffr_lines_update(&st->lines, cfg, in->line, st->odo.dist_mm);
    {
        /* the openings from the hits with each pair's tilt split between
         * its two parts (a copy: the rest reads the hits as measured); no
         * copy before a tilt is learned (the orientation's heavy ticks) */
        const ffr_ir_geom_t *og = &st->ir_geom;
        ffr_ir_geom_t split;
        if (st->wall_cal.bias_n[FFR_SIDE_LEFT] != 0u || st->wall_cal.bias_n[FFR_SIDE_RIGHT] != 0u) {
            split = st->ir_geom;
            ffr_wall_cal_split(&st->wall_cal, cfg, st->ir_mm, &split);
            og = &split;
        }
        ffr_openings_update(&st->open, cfg, og, st->ir_mm, st->odo.dist_mm, st->odo.dist_mm - before,
                            ffr_route_open_side(st));
        ffr_gaps_update(&st->open, cfg, og, st->ir_mm, st->odo.dist_mm, st->odo.dist_mm - before,
                        st->odo.heading_rad - st->route.heading_ref_rad);
    }

    st->fan = 0;
    if (!st->started) {
        ffr_stop(st);
        if (in->start) {
            st->started = 1;
            if (cfg->home_wall_side == FFR_HOME_AS_PLACED) {
                st->route.heading_ref_rad = st->odo.heading_rad;
                if (cfg->start_area == FFR_START_HALLWAY) {
                    ffr_explore_begin(st);
                } else {
                    ffr_route_begin(st, 0);
                }
            } else {
                ffr_orient_begin(st);
            }
        }
    }
    if (st->started && st->state == FFR_ST_ORIENT) {
        if (ffr_orient_step(st)) {
            /* odometry's frame now has the route's first direction at 0 */
            st->route.heading_ref_rad = 0.0f;
            if (cfg->start_area == FFR_START_HALLWAY) {
                ffr_explore_begin(st);
            } else {
                ffr_route_begin(st, 0);
            }
        }
    } else if (st->started && st->state != FFR_ST_DONE && st->state != FFR_ST_FAILED) {
        if (cfg->start_area == FFR_START_HALLWAY) {
            ffr_explore_step(st, in);
        } else {
            ffr_route_step(st, in);
        }
    }

    out->seq = in->seq;
    if (st->state == FFR_ST_DONE || st->state == FFR_ST_FAILED || !st->started) {
        /* stopped means stopped: no speed-loop integral left driving the motors */
        ffr_speed_reset(&st->speed);
        st->fan = 0;
        out->pwm[0] = 0;
        out->pwm[1] = 0;
    } else {
        ffr_speed_control(&st->speed, cfg, &st->odo, st->cmd_v_mm_s, st->cmd_w_rad_s, dt, out->pwm);
    }
    out->fan = st->fan;
    out->state = st->state;
    if (cfg->start_area == FFR_START_HALLWAY) {
        out->room = (st->state >= FFR_ST_ENTER && st->state <= FFR_ST_EXIT) ? st->room.room : 0u;
    } else {
        out->room = (st->route.pc < FFR_ROUTE_MAX && cfg->route[st->route.pc].op == FFR_OP_ROOM)
                        ? cfg->route[st->route.pc].arg
                        : 0u;
    }
    out->rooms_searched = st->rooms_searched;
    out->line_count = st->lines.count;
    out->flags = st->flags;
    out->step = cfg->start_area == FFR_START_HALLWAY ? st->explore.phase : st->route.pc;
    out->fail_code = st->fail_code;
    out->odo_x_mm = clamp_i16(st->odo.x_mm);
    out->odo_y_mm = clamp_i16(st->odo.y_mm);
    out->odo_heading_cdeg = clamp_i16(ffr_wrap_pi(st->odo.heading_rad) * (18000.0f / FFR_PI));
    out->reserved = 0;
}

void ffr_step_many(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i) {
        ffr_step(&st[i], &in[i], &out[i]);
    }
}
