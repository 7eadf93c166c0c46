/*
 * The walls' direction in odometry's frame, from each side ranger's hits.
 *
 * Every tick a side ranger sees a wall beside, its hit point is placed in
 * odometry's frame (position and heading of this tick). Over a stretch of
 * travel the points of one ranger on one straight wall lie on a line whose
 * direction is the wall's, whatever the part's calibration: an offset error
 * moves every point by the same few centimetres along the beam, which does
 * not turn the line (as long as the body keeps its heading within a few
 * degrees); a gain error only scales how the distance changes, a small angle.
 * One ranger is enough, so this works on short legs and where the other
 * ranger of the side looks into an opening.
 *
 * Contest walls meet at right angles and the robot starts square to its
 * hallway: a wall's direction off a multiple of 90 degrees is odometry's
 * heading error (track slip in turns and scans adds up), which the corridor
 * driver takes off odometry and the corridor heading (drive.c).
 */
#include "ffr_internal.h"

/* a window: this much travel, the body turning less than this meanwhile */
#define HIT_WINDOW_MM 120.0f
#define HIT_TURN_DEG 8.0f
/* a line: spread along it at least this (rms, mm: ~85 mm of wall), off it at
 * most this (rms, mm; the datasheet parts with typical noise stay under half
 * of it, a hit on another wall goes far over) */
#define HIT_ALONG_RMS_MM 25.0f
#define HIT_ACROSS_RMS_MM 3.0f
/* and running along the travel within this: not the end face of a wall */
#define HIT_ALONG_DEG 20.0f

static void restart(ffr_hit_window_t *hw)
{
    hw->s0_mm = hw->h0_rad = 0.0f;
    hw->x0_mm = hw->y0_mm = 0.0f;
    hw->sx = hw->sy = hw->sxx = hw->syy = hw->sxy = 0.0f;
    hw->n = 0u;
    hw->reserved[0] = hw->reserved[1] = 0u;
}

void ffr_wall_dir_reset(ffr_wall_cal_t *c)
{
    int i;
    for (i = 0; i < 4; ++i) {
        restart(&c->hits[i]);
    }
}

/* A closed window's wall direction (odometry frame, rad, within 90 degrees
 * of the heading), or 0 if its points are not one straight wall along the travel. */
static int line_of(const ffr_hit_window_t *hw, float heading, float *dir)
{
    float n = (float)hw->n;
    float mx = hw->sx / n, my = hw->sy / n;
    float cxx = hw->sxx / n - mx * mx;
    float cyy = hw->syy / n - my * my;
    float cxy = hw->sxy / n - mx * my;
    /* principal axes of the points' spread */
    float half_tr = 0.5f * (cxx + cyy);
    float half_df = 0.5f * (cxx - cyy);
    float r = ffr_sqrtf(half_df * half_df + cxy * cxy);
    float along = half_tr + r, across = half_tr - r;
    float a, rel;
    if (along < HIT_ALONG_RMS_MM * HIT_ALONG_RMS_MM || across > HIT_ACROSS_RMS_MM * HIT_ACROSS_RMS_MM) {
        return 0;
    }
    a = 0.5f * ffr_atan2f(2.0f * cxy, cxx - cyy);
    /* a line has two directions: the one along the travel */
    rel = ffr_wrap_pi(a - heading);
    if (rel > 0.5f * FFR_PI) {
        rel -= FFR_PI;
    } else if (rel < -0.5f * FFR_PI) {
        rel += FFR_PI;
    }
    if (ffr_absf(rel) > HIT_ALONG_DEG * FFR_DEG) {
        return 0;
    }
    *dir = heading + rel;
    return 1;
}

int ffr_wall_dir_update(ffr_wall_cal_t *c, const ffr_config_t *cfg, const ffr_odometry_t *o,
                        const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT], float *wall_dir)
{
    int i, found = 0;
    float sum = 0.0f;
    const float ch = ffr_cosf(o->heading_rad);
    const float sh = ffr_sinf(o->heading_rad);
    for (i = FFR_IR_LF; i <= FFR_IR_RR; ++i) {
        ffr_hit_window_t *hw = &c->hits[i - 1];
        float bx, by, x, y, dir;
        if (!ffr_hit_beside(cfg, g, ir_mm, i, &bx, &by)) {
            restart(hw);
            continue;
        }
        x = o->x_mm + ch * bx - sh * by;
        y = o->y_mm + sh * bx + ch * by;
        if (hw->n > 0u && ffr_absf(o->heading_rad - hw->h0_rad) > HIT_TURN_DEG * FFR_DEG) {
            restart(hw);
        }
        if (hw->n == 0u) {
            hw->s0_mm = o->dist_mm;
            hw->h0_rad = o->heading_rad;
            hw->x0_mm = x;
            hw->y0_mm = y;
        }
        /* relative to the first hit: small numbers, float32 keeps them exact enough */
        x -= hw->x0_mm;
        y -= hw->y0_mm;
        hw->sx += x;
        hw->sy += y;
        hw->sxx += x * x;
        hw->syy += y * y;
        hw->sxy += x * y;
        hw->n = (uint16_t)(hw->n + 1u);
        if (o->dist_mm - hw->s0_mm >= HIT_WINDOW_MM) {
            if (line_of(hw, o->heading_rad, &dir)) {
                sum += dir - o->heading_rad;
                ++found;
            }
            restart(hw);
        }
    }
    if (found == 0) {
        return 0;
    }
    *wall_dir = o->heading_rad + sum / (float)found;
    return found;
}
