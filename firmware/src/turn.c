/* Turning in place by odometry: the encoders tell how far the robot has rotated. */
#include "ffr_internal.h"

float ffr_turn_yaw(const ffr_config_t *cfg, float heading, float target)
{
    float err = target - heading; /* unwrapped: the turn goes the asked way round */
    float lim = cfg->turn_rate_deg_s * FFR_DEG;
    float w = ffr_clampf(cfg->heading_kp * err, -lim, lim);
    /* keep a minimum rate until the tolerance: below it the tracks stall */
    float w_min = 25.0f * FFR_DEG;
    if (ffr_absf(err) > 0.5f * cfg->turn_tol_deg * FFR_DEG && ffr_absf(w) < w_min) {
        w = err > 0.0f ? w_min : -w_min;
    }
    return w;
}

float ffr_turn_spin(const ffr_config_t *cfg, const ffr_odometry_t *o)
{
    return ffr_absf(o->v_mm_s[1] - o->v_mm_s[0]) / cfg->track_width_mm;
}

int ffr_turn_done(const ffr_config_t *cfg, const ffr_odometry_t *o, float target)
{
    float err = ffr_absf(target - o->heading_rad);
    return err < cfg->turn_tol_deg * FFR_DEG && ffr_turn_spin(cfg, o) < 20.0f * FFR_DEG;
}

/*
 * Room to turn in place: the front corners sweep a circle of the body's corner
 * radius. A wall ahead closer than that radius + FFR_TURN_MARGIN_MM (the
 * front distance projected over the reading's age) is backed away from while
 * the turn goes on, the farther inside the faster (30 to 120 mm/s). A robot
 * that braked late or slid on after its stop (tracks slipping on the floor)
 * would otherwise swing a corner into the wall. Forward speed for the turn:
 * 0 or negative.
 */
float ffr_turn_room_v(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT])
{
    float r = ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm);
    float in = r + FFR_TURN_MARGIN_MM - ffr_front_now(cfg, o, ir_mm);
    if (in <= 0.0f) {
        return 0.0f;
    }
    return -ffr_clampf(4.0f * in, 30.0f, 120.0f);
}

/*
 * A turn in place begun while the robot still rolls on (the step before it
 * stopped on an event at speed) drives the wheel that must reverse forward
 * until its speed loop has turned it round, and the body goes on into the
 * turn (~40 mm from 200 mm/s with slipping tracks). If rolling on for
 * FFR_TURN_ROLL_S more at odometry's forward speed would bring the wall ahead
 * within the corner radius + half FFR_TURN_MARGIN_MM, the turn's rate
 * is held back while that speed is above FFR_TURN_ROLL_MM_S:
 * full below it, none 100 mm/s above it. Elsewhere the turn starts at once.
 * Returns the factor on the turn's rate, 0..1.
 */
float ffr_turn_onset(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT])
{
    float r = ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm);
    float v = 0.5f * (o->v_mm_s[0] + o->v_mm_s[1]);
    /* where the front would be after rolling on for FFR_TURN_ROLL_S more */
    if (ffr_front_now(cfg, o, ir_mm) - (v > 0.0f ? v : 0.0f) * FFR_TURN_ROLL_S > r + 0.5f * FFR_TURN_MARGIN_MM) {
        return 1.0f;
    }
    return ffr_clampf(1.0f - (v - FFR_TURN_ROLL_MM_S) / 100.0f, 0.0f, 1.0f);
}

void ffr_turn_toward(ffr_state_t *st, float target_rad)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_stop(st);
    st->cmd_v_mm_s = ffr_turn_room_v(cfg, &st->odo, st->ir_mm);
    st->cmd_w_rad_s = ffr_turn_yaw(cfg, st->odo.heading_rad, target_rad) * ffr_turn_onset(cfg, &st->odo, st->ir_mm);
}

void ffr_turn_finish(ffr_state_t *st, float target_rad)
{
    st->route.heading_ref_rad = target_rad;
    ffr_stop(st);
}
