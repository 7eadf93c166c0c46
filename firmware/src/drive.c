/*
 * Corridor driving, shared by the route steps: forward at a speed set by the
 * proximity sensors, steering by the wall on the preferred side, else the
 * other side, else the heading held by odometry. A wall seen by two rangers
 * also re-aligns the held heading, so odometry drift never accumulates
 * between walls.
 */
#include "ffr_internal.h"

void ffr_stop(ffr_state_t *st)
{
    st->cmd_v_mm_s = 0.0f;
    st->cmd_w_rad_s = 0.0f;
}

float ffr_stopping_speed(float remaining_mm, float top)
{
    return ffr_clampf(2.0f * remaining_mm + 60.0f, 60.0f, top);
}

void ffr_drive_heading(ffr_state_t *st, float heading, float speed)
{
    st->cmd_v_mm_s = speed;
    st->cmd_w_rad_s = ffr_heading_hold_yaw(&st->cfg, st->odo.heading_rad, heading);
}

void ffr_drive_corridor(ffr_state_t *st, uint8_t side, float speed)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_wall_t w;
    int use = -1;
    float v = ffr_proximity_speed(cfg, st->ir_mm, speed);
    if (side == FFR_SIDE_LEFT || side == FFR_SIDE_RIGHT) {
        w = ffr_wall_estimate(cfg, st->ir_mm, side);
        if (w.valid && w.dist_mm < cfg->open_mm) {
            use = side;
        } else {
            w = ffr_wall_estimate(cfg, st->ir_mm, 1 - side);
            if (w.valid && w.dist_mm < cfg->open_mm) {
                use = 1 - side;
            }
        }
    }
    if (use >= 0) {
        /* what this tick teaches about odometry's heading and the pair's tilt,
         * from the angle as measured; then the tilt taken off it */
        st->odo.heading_rad -= ffr_wall_cal_update(&st->wall_cal, cfg, &w, use, st->odo.heading_rad,
                                                   st->odo.dist_mm);
        ffr_wall_cal_correct(&st->wall_cal, &w, use);
        if (!w.angle_valid) {
            /* one ranger gives the distance but not the wall's direction: take the
             * wall to run along the corridor heading, so the steering keeps its
             * heading feedback (without it, a distance error turns the robot
             * steadily until the one ranger sees something else) */
            w.angle_rad = ffr_wrap_pi(st->route.heading_ref_rad - st->odo.heading_rad);
        } else {
            /* the corridor heading follows the wall's angle (its tilt taken
             * off), quickly; a larger difference is not this wall */
            float diff = ffr_wrap_pi(st->odo.heading_rad + w.angle_rad - st->route.heading_ref_rad);
            if (ffr_absf(diff) < 12.0f * FFR_DEG) {
                st->route.heading_ref_rad += cfg->wall_align_gain * diff;
            }
        }
        st->cmd_v_mm_s = v;
        st->cmd_w_rad_s = ffr_wall_follow_yaw(cfg, &w, use);
    } else {
        ffr_wall_cal_restart(&st->wall_cal);
        ffr_drive_heading(st, st->route.heading_ref_rad, v);
    }
}
