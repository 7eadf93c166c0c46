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
#define WALL_SNAP_DEAD_DEG 3.0f
/* the wall's direction measured over this much straight travel, then this
 * share of what it says applied */
#define WALL_WINDOW_MM 100.0f
#define WALL_WINDOW_TURN_DEG 3.0f
#define WALL_WINDOW_GAIN 0.3f

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

/* Lateral distance (mm) of ranger i's hit, or -1 if it is not a wall beside. */
static float beside_mm(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], int i)
{
    if (!ffr_hit_beside(cfg, i, ir_mm[i])) {
        return -1.0f;
    }
    return ffr_absf(cfg->ir_y_mm[i] + ir_mm[i] * ffr_sinf(cfg->ir_angle_deg[i] * FFR_DEG));
}

/* Correct a heading (rad) by a measured error toward a right angle, past a dead zone. */
static float snap_error(float wall_dir)
{
    float q = 0.5f * FFR_PI;
    float snap = (float)(int32_t)(wall_dir / q + (wall_dir >= 0.0f ? 0.5f : -0.5f)) * q;
    return wall_dir - snap;
}

/*
 * The followed wall's direction, for keeping the corridor heading and
 * odometry true. Not from the angle between the front and rear rangers' hits:
 * two parts of opposite calibration spread make that several degrees off,
 * and it would steer the held heading off with it. Instead, from how the
 * wall's distance (the mean of both rangers' hits, so a small turn of the
 * body cancels out) changes over a window of straight travel: each part's
 * offset cancels in the difference, its gain error only scales a small angle.
 *
 * Contest walls meet at right angles and the robot starts square to its
 * hallway, so a straight wall runs at a multiple of 90 degrees of the start
 * heading: what it is off by beyond a few degrees is odometry's heading error
 * (track slip in turns adds up), and odometry itself is corrected.
 */
static void track_wall(ffr_state_t *st, int side)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_route_state_t *rs = &st->route;
    int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
    int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
    float df = beside_mm(cfg, st->ir_mm, f);
    float dr = beside_mm(cfg, st->ir_mm, r);
    float d, ds, turned;
    if (df < 0.0f || dr < 0.0f) {
        rs->win_side = -1;
        return;
    }
    d = 0.5f * (df + dr);
    if (rs->win_side != side) {
        rs->win_side = (int8_t)side;
        rs->win_s_mm = st->odo.dist_mm;
        rs->win_d_mm = d;
        rs->win_h_rad = st->odo.heading_rad;
        return;
    }
    ds = st->odo.dist_mm - rs->win_s_mm;
    turned = st->odo.heading_rad - rs->win_h_rad;
    if (ds < WALL_WINDOW_MM) {
        return;
    }
    if (ffr_absf(turned) < WALL_WINDOW_TURN_DEG * FFR_DEG) {
        /* moving away from a left wall means it runs to the left of the heading */
        float slope = ffr_clampf((d - rs->win_d_mm) / ds, -0.5f, 0.5f);
        float rel = (side == FFR_SIDE_LEFT ? 1.0f : -1.0f) * slope; /* asin(x) ~ x here */
        float wall_dir = rs->win_h_rad + 0.5f * turned + rel;
        float err = snap_error(wall_dir);
        float dead = WALL_SNAP_DEAD_DEG * FFR_DEG;
        float e2 = err > dead ? err - dead : (err < -dead ? err + dead : 0.0f);
        if (ffr_absf(err) < WALL_SNAP_MAX_DEG * FFR_DEG) {
            st->odo.heading_rad -= WALL_WINDOW_GAIN * e2 * (cfg->wall_align_gain > 0.0f ? 1.0f : 0.0f);
        }
        (void)wall_dir;
    }
    rs->win_s_mm = st->odo.dist_mm;
    rs->win_d_mm = d;
    rs->win_h_rad = st->odo.heading_rad;
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
            /* the corridor heading follows the wall's angle, quickly; what the
             * angle is off by (parts of opposite spread) stays within 12 deg */
            float diff = ffr_wrap_pi(st->odo.heading_rad + w.angle_rad - st->route.heading_ref_rad);
            if (ffr_absf(diff) < 12.0f * FFR_DEG) {
                st->route.heading_ref_rad += cfg->wall_align_gain * diff;
            }
        }
        track_wall(st, use);
        st->cmd_v_mm_s = v;
        st->cmd_w_rad_s = ffr_wall_follow_yaw(cfg, &w, use);
    } else {
        ffr_drive_heading(st, st->route.heading_ref_rad, v);
    }
}
