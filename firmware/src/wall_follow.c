/*
 * Wall following with two rangers on one side (the paper's Fig. 10). Each
 * ranger's hit point is placed in the body frame from its mounting pose; the
 * two points give the wall line: its distance from the origin and its angle
 * to the heading. One valid ranger still gives the distance (wall assumed
 * parallel), so the robot keeps following through short gaps.
 */
#include "ffr_internal.h"

/* a front hit within this of the wall ahead (forward, mm) is on that wall */
#define AHEAD_MARGIN_MM 70.0f

ffr_wall_t ffr_wall_estimate(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                             int side)
{
    ffr_wall_t w;
    int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
    int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
    float fx = 0.0f, fy = 0.0f, rx = 0.0f, ry = 0.0f;
    int fv = ffr_hit_beside(cfg, g, ir_mm, f, &fx, &fy);
    int rv = ffr_hit_beside(cfg, g, ir_mm, r, &rx, &ry);
    w.valid = 0;
    w.angle_valid = 0;
    w.dist_mm = 0.0f;
    w.angle_rad = 0.0f;
    /* nearing a corner, the front ranger's beam reaches the wall ahead before
     * the side wall ends: a hit about as far ahead as the centre ranger puts
     * that wall is on it. Steering away from it turned the robot off its wall
     * before the FRONT event could stop it (a centre part reading long lets
     * the robot that close). */
    if (fv && ffr_ir_valid(cfg, ir_mm[FFR_IR_CF])
        && fx > ir_mm[FFR_IR_CF] + cfg->ir_x_mm[FFR_IR_CF] - AHEAD_MARGIN_MM) {
        fv = 0;
    }
    if (fv && rv) {
        float wx = fx - rx;
        float wy = fy - ry;
        float len = ffr_sqrtf(wx * wx + wy * wy);
        float ang;
        /* both hits on one straight wall: beside the robot at similar offsets
         * (a rear ranger looking into a side hallway hits another wall) */
        if (len > 50.0f && wx > 0.0f && ffr_absf(ffr_absf(fy) - ffr_absf(ry)) < 100.0f) {
            ang = ffr_atan2f(wy, wx);
            /* a steep line is a corner or two different walls, not one wall */
            if (ffr_absf(ang) < 35.0f * FFR_DEG) {
                w.valid = 1;
                w.angle_valid = 1;
                w.angle_rad = ang;
                w.dist_mm = ffr_absf(wx * ry - wy * rx) / len;
                return w;
            }
        }
    }
    /* one ranger (the front one preferred): distance only */
    if (fv && (!rv || ffr_absf(fy) <= ffr_absf(ry))) {
        w.valid = 1;
        w.dist_mm = ffr_absf(fy);
    } else if (rv) {
        w.valid = 1;
        w.dist_mm = ffr_absf(ry);
    }
    return w;
}

float ffr_heading_hold_yaw(const ffr_config_t *cfg, float heading, float heading_ref)
{
    float err = ffr_wrap_pi(heading_ref - heading);
    float lim = cfg->turn_rate_deg_s * FFR_DEG;
    return ffr_clampf(cfg->heading_kp * err, -lim, lim);
}

float ffr_wall_follow_yaw(const ffr_config_t *cfg, const ffr_wall_t *w, int side, float target_mm)
{
    /* wanted heading relative to the wall: toward it when too far */
    float sign = side == FFR_SIDE_LEFT ? 1.0f : -1.0f;
    float lim = cfg->turn_rate_deg_s * FFR_DEG;
    /* one ranger's distance (no wall angle) is the least sure: steer by it gently,
     * so a part that reads long or short does not swing the robot off the wall */
    float max_deg = w->angle_valid ? cfg->wall_max_deg : 0.4f * cfg->wall_max_deg;
    float want = ffr_clampf(cfg->wall_kp_deg_per_mm * (w->dist_mm - target_mm),
                            -max_deg, max_deg) * FFR_DEG * sign;
    /* the robot's heading relative to the wall is -angle */
    float err = want + w->angle_rad;
    return ffr_clampf(cfg->heading_kp * err, -lim, lim);
}
