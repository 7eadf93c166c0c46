/*
 * Corridor driving, shared by the route steps: forward at a speed set by the
 * proximity sensors, steering by the wall on the preferred side, else the
 * other side, else the heading held by odometry. A wall seen by two rangers
 * also re-aligns the held heading, so odometry drift never accumulates
 * between walls.
 */
#include "ffr_internal.h"

/* odometry heading correction from a wall's direction: within this of a right
 * angle, past this dead zone, this share per window (none when
 * wall_align_gain is 0); the corridor heading then this share of the way to
 * the wall's direction, if within this of it */
#define SNAP_MAX_DEG 25.0f
#define SNAP_DEAD_DEG 1.5f
#define SNAP_GAIN 0.5f
#define REF_MAX_DEG 15.0f
#define REF_GAIN 0.5f
/* the corridor heading follows a two-ranger wall's direction only within
 * this of it (chosen; was 12: docs/firmware.md, "The held heading in the
 * hallway to room 2") */
#ifndef FOLLOW_REF_MAX_DEG
#define FOLLOW_REF_MAX_DEG 5.0f
#endif

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

/*
 * Odometry's heading and the corridor heading kept true by the walls beside
 * (wall_direction.c): a wall's direction off a right angle, past a dead zone
 * for the measurement's noise, is odometry's error; a share of it comes off
 * odometry, and the corridor heading (in odometry's frame) moves with it and
 * then toward the wall's direction.
 */
static void true_up_heading(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    float dir, err, corr, diff;
    if (!ffr_wall_dir_update(&st->wall_cal, cfg, &st->odo, &st->ir_geom, st->ir_mm, &dir) || cfg->wall_align_gain <= 0.0f) {
        return;
    }
    err = ffr_off_square(dir);
    if (ffr_absf(err) < SNAP_MAX_DEG * FFR_DEG) {
        ffr_turn_cal_learn(&st->odo, err);
    }
    corr = 0.0f;
    if (ffr_absf(err) < SNAP_MAX_DEG * FFR_DEG) {
        float dead = SNAP_DEAD_DEG * FFR_DEG;
        corr = SNAP_GAIN * (err > dead ? err - dead : (err < -dead ? err + dead : 0.0f));
    }
    st->odo.heading_rad -= corr;
    st->route.heading_ref_rad -= corr;
    diff = ffr_wrap_pi(dir - corr - st->route.heading_ref_rad);
    if (ffr_absf(diff) < REF_MAX_DEG * FFR_DEG) {
        st->route.heading_ref_rad += REF_GAIN * diff;
    }
}

/*
 * Straight on the held heading, trued up by the walls beside as a corridor
 * leg is (true_up_heading), without steering by them: the explorer's legs to
 * an opening's middle, into a doorway and out, and home. Held by odometry
 * alone, a robot whose two sides differ (one track 1 % larger than the
 * other turns it 0.01 x 1000 / 170 rad, 3.4 degrees, a metre, unseen by the
 * encoders) drifted off the hallway's line, and the turn ending the leg met
 * a jamb or a wall (docs/firmware.md, "The explorer's straight legs").
 */
void ffr_drive_held(ffr_state_t *st, float speed)
{
    true_up_heading(st);
    ffr_drive_heading(st, st->route.heading_ref_rad, speed);
}

void ffr_drive_corridor(ffr_state_t *st, uint8_t side, float speed)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_wall_t w;
    int use = -1;
    float v = ffr_proximity_speed(cfg, st->ir_mm, speed);
    true_up_heading(st);
    if (side == FFR_SIDE_LEFT || side == FFR_SIDE_RIGHT) {
        w = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, side);
        if (w.valid && w.dist_mm < cfg->open_mm) {
            use = side;
        } else {
            w = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, 1 - side);
            if (w.valid && w.dist_mm < cfg->open_mm) {
                use = 1 - side;
            }
        }
    }
    if (use >= 0) {
        /* what this tick teaches about the pair's tilt, from the angle as
         * measured; then the tilt taken off it */
        ffr_wall_cal_update(&st->wall_cal, &w, use, st->odo.heading_rad, st->odo.dist_mm);
        ffr_wall_cal_correct(&st->wall_cal, &w, use);
        if (!w.angle_valid) {
            /* one ranger gives the distance but not the wall's direction: take the
             * wall to run along the corridor heading, so the steering keeps its
             * heading feedback (without it, a distance error turns the robot
             * steadily until the one ranger sees something else) */
            w.angle_rad = ffr_wrap_pi(st->route.heading_ref_rad - st->odo.heading_rad);
        } else {
            /* the corridor heading follows the wall's angle (its tilt taken
             * off), quickly; a larger difference is not this wall: at a
             * junction's mouth the two rangers hit two walls (a corner
             * beyond, a wall nearer) and their line runs several degrees off;
             * odometry's own drift is the walls' fixes' (true_up_heading) */
            float diff = ffr_wrap_pi(st->odo.heading_rad + w.angle_rad - st->route.heading_ref_rad);
            if (ffr_absf(diff) < FOLLOW_REF_MAX_DEG * FFR_DEG) {
                st->route.heading_ref_rad += cfg->wall_align_gain * diff;
            }
        }
        st->cmd_v_mm_s = v;
        /* HOME's hallway middle (route.c, home_middle), else wall_target_mm */
        st->cmd_w_rad_s = ffr_wall_follow_yaw(cfg, &w, use,
                                              st->route.follow_mm > 0.0f ? st->route.follow_mm : cfg->wall_target_mm);
    } else {
        ffr_wall_cal_restart(&st->wall_cal);
        ffr_drive_heading(st, st->route.heading_ref_rad, v);
    }
    ffr_corridor_guard(st);
}

/*
 * A front corner about to touch a wall beside it: the corner is steered off
 * the wall its ranger sees beside the front half at least as fast as
 * room_guards.c's leaving law says (this tick's hits). A held
 * heading 10-20 deg off after a room's exit and the turn out of it (slipping
 * tracks) let the wall following run the corner into a jamb or a room's
 * corner before any wall fix took the error off (docs/firmware.md, "A front
 * corner kept off the walls on the way").
 */
void ffr_corridor_guard(ffr_state_t *st)
{
    float g = ffr_leave_guard(st);
    /* at least the guard's push away from the wall: steering already turning
     * the corner off it as fast is left alone */
    if (g < 0.0f && st->cmd_w_rad_s > g) {
        st->cmd_w_rad_s = g;
    } else if (g > 0.0f && st->cmd_w_rad_s < g) {
        st->cmd_w_rad_s = g;
    }
}
