/*
 * Corridor driving, shared by the route steps: forward at a speed set by the
 * proximity sensors, steering by the wall on the preferred side, else the
 * other side, else the heading held by odometry. A wall seen by two rangers
 * also re-aligns the held heading, so odometry drift never accumulates
 * between walls.
 */
#include "ffr_internal.h"

/* odometry heading corrected by walls: within this of a right angle, at this
 * share of wall_align_gain per tick (0 = off) */
#define WALL_SNAP_MAX_DEG 25.0f
#define WALL_SNAP_SHARE 0.4f
#define WALL_SNAP_DEAD_DEG 6.0f

void ffr_stop(ffr_state_t *st)
{
    st->cmd_v_mm_s = 0.0f;
    st->cmd_w_rad_s = 0.0f;
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
        if (!w.angle_valid) {
            /* one ranger gives the distance but not the wall's direction: take the
             * wall to run along the corridor heading, so the steering keeps its
             * heading feedback (without it, a distance error turns the robot
             * steadily until the one ranger sees something else) */
            w.angle_rad = ffr_wrap_pi(st->route.heading_ref_rad - st->odo.heading_rad);
        } else {
            float wall_dir = st->odo.heading_rad + w.angle_rad;
            float diff;
            /* Contest walls meet at right angles and the robot starts square to
             * its hallway: a straight wall runs at a multiple of 90 degrees of
             * the start heading. What it is off by is odometry's heading error
             * (track slip in turns adds up to tens of degrees over a mission):
             * correct odometry itself, slowly, so turns, scans and the way out
             * of a room all use a true heading. */
            float snap = (float)(int32_t)(wall_dir / (0.5f * FFR_PI) + (wall_dir >= 0.0f ? 0.5f : -0.5f)) * 0.5f * FFR_PI;
            float err = wall_dir - snap;
            /* only what a pair of rangers' part spread cannot explain (their
             * wall angle may be a few degrees off): the rest is left to the
             * corridor heading's own re-alignment below */
            float dead = WALL_SNAP_DEAD_DEG * FFR_DEG;
            err = err > dead ? err - dead : (err < -dead ? err + dead : 0.0f);
            if (ffr_absf(err) < WALL_SNAP_MAX_DEG * FFR_DEG) {
                st->odo.heading_rad -= WALL_SNAP_SHARE * cfg->wall_align_gain * err;
                wall_dir -= WALL_SNAP_SHARE * cfg->wall_align_gain * err;
            }
            diff = ffr_wrap_pi(wall_dir - st->route.heading_ref_rad);
            if (ffr_absf(diff) < 12.0f * FFR_DEG) {
                st->route.heading_ref_rad += cfg->wall_align_gain * diff;
            }
        }
        st->cmd_v_mm_s = v;
        st->cmd_w_rad_s = ffr_wall_follow_yaw(cfg, &w, use);
    } else {
        ffr_drive_heading(st, st->route.heading_ref_rad, v);
    }
}
