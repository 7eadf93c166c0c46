/*
 * Odometry's turn scale, learned from the walls. Turning in place, the
 * heading odometry counts is (right - left wheel travel) / track width; a
 * wheel radius or a track width off what the robot was told (a tracked
 * robot's effective track width is not its geometric one) scales every turn
 * by the same factor. wall_direction.c tells odometry's heading error each
 * time a straight wall has been seen over a stretch of travel; the error
 * gathered over a turn of A radians since the last such fix is (scale -
 * true scale) x A, so each fix after at least TURN_CAL_MIN_DEG of rotation
 * tells the true scale, with an error (the wall's direction, slip) that
 * shrinks as A grows. The scale is their mean weighted by A^2 (recursive
 * least squares), with the told scale 1 weighted as TURN_CAL_PRIOR_DEG of
 * rotation: the first 90-degree turn moves it most of the way, a room's
 * scan (a turn or more in place) settles it, and later short turns' noise
 * hardly moves it.
 */
#include "ffr_internal.h"

#define TURN_CAL_MIN_DEG 60.0f  /* rotation since the last fix to learn from    */
#define TURN_CAL_MAX_ERR_DEG 20.0f /* a larger error is not this scale's doing  */
#define TURN_CAL_PRIOR_DEG 60.0f
/* an error within this is the wall measurement's own noise (and slip): it
 * teaches nothing; beyond it, only what exceeds it counts (a 1.5-degree
 * error after a 90-degree turn, taken whole, would set the scale 1.6 %
 * off and a room's scan of two turns 12 degrees off; 2 degrees lost the
 * calibration grid's corners, 0.5 keeps them and a 20 ms tick's slip) */
#define TURN_CAL_DEAD_DEG 0.5f
#define TURN_CAL_MIN 0.8f
#define TURN_CAL_MAX 1.25f

void ffr_turn_cal_learn(ffr_odometry_t *o, float err)
{
    float raw = o->rot_raw_rad;
    float meas, w, prior = TURN_CAL_PRIOR_DEG * FFR_DEG;
    o->rot_raw_rad = 0.0f;
    if (ffr_absf(raw) < TURN_CAL_MIN_DEG * FFR_DEG || ffr_absf(err) > TURN_CAL_MAX_ERR_DEG * FFR_DEG) {
        return;
    }
    if (ffr_absf(err) <= TURN_CAL_DEAD_DEG * FFR_DEG) {
        return;
    }
    err += err > 0.0f ? -TURN_CAL_DEAD_DEG * FFR_DEG : TURN_CAL_DEAD_DEG * FFR_DEG;
    meas = o->turn_scale - err / raw;
    w = raw * raw;
    o->turn_w += w;
    o->turn_scale = ffr_clampf(o->turn_scale + w / (o->turn_w + prior * prior) * (meas - o->turn_scale),
                               TURN_CAL_MIN, TURN_CAL_MAX);
}

/*
 * The turn scale from a room's scan (a turn in place), and the heading error
 * the scan itself added. Contest walls meet at right angles, square to
 * odometry's frame; every ranger's successive hits, placed in odometry's
 * frame, run along the walls it sweeps, so their stretches' direction modulo
 * 90 degrees is odometry's heading error at that moment (plus what the
 * rangers' timing adds: a GP2D12 reading is up to a period or two old, a few
 * degrees of a 150 deg/s scan, the same all the turn). Over the turn that
 * error grows by (scale - true scale) per raw radian: its mean in each third
 * of the turn (by raw rotation), fitted by a line over the raw rotation,
 * gives the growth (the slope), whatever the timing's constant share. The
 * growth times the scan's raw rotation is what the scan added to the heading
 * error; the error it came in with (the entry's) stays, for the walls to
 * take off later. Only a new reading is a new hit (the part measures every
 * ~38 ms, the firmware reads it every tick).
 */
#define SQ_RANGE_MM 600.0f    /* chosen: farther hits are too noisy for a direction    */
#define SQ_SEG_MIN_MM 40.0f   /* a stretch of one ranger's hits: at least this (noise)   */
#define SQ_SEG_MAX_MM 120.0f  /* at most this: longer is a jump to another wall          */
#define SQ_PART_DEG 120.0f    /* the turn's parts                                        */
#define SQ_PART_MIN_MM 150.0f /* chosen: a part with less wall seen tells nothing        */
#define SQ_SPAN_MIN_DEG 180.0f /* parts spread at least this far apart tell the scale    */

void ffr_scan_sq_reset(ffr_scan_square_t *q)
{
    int i;
    q->raw_rad = 0.0f;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        q->ax_mm[i] = q->ay_mm[i] = 0.0f;
        q->last_mm[i] = -1.0f;
        q->anchor_ok[i] = 0u;
    }
    for (i = 0; i < FFR_SQ_PARTS; ++i) {
        q->c4[i] = q->s4[i] = q->w[i] = q->wt[i] = 0.0f;
    }
    q->reserved[0] = q->reserved[1] = q->reserved[2] = 0u;
}

void ffr_scan_sq_record(ffr_scan_square_t *q, const ffr_config_t *cfg, const ffr_odometry_t *o,
                        const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT])
{
    float c = ffr_cosf(o->heading_rad), s = ffr_sinf(o->heading_rad);
    int i, part;
    q->raw_rad += (o->dpos_mm[1] - o->dpos_mm[0]) / cfg->track_width_mm;
    part = (int)(ffr_absf(q->raw_rad) / (SQ_PART_DEG * FFR_DEG));
    if (part >= FFR_SQ_PARTS) {
        part = FFR_SQ_PARTS - 1;
    }
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float px, py, dx, dy, len;
        if (!ffr_ir_valid(cfg, ir_mm[i]) || ir_mm[i] > SQ_RANGE_MM) {
            q->anchor_ok[i] = 0u;
            q->last_mm[i] = -1.0f;
            continue;
        }
        if (ir_mm[i] == q->last_mm[i]) {
            continue; /* the same measurement as last tick */
        }
        q->last_mm[i] = ir_mm[i];
        px = o->x_mm + c * g->hit_x_mm[i] - s * g->hit_y_mm[i];
        py = o->y_mm + s * g->hit_x_mm[i] + c * g->hit_y_mm[i];
        if (!q->anchor_ok[i]) {
            q->anchor_ok[i] = 1u;
            q->ax_mm[i] = px;
            q->ay_mm[i] = py;
            continue;
        }
        dx = px - q->ax_mm[i];
        dy = py - q->ay_mm[i];
        len = ffr_sqrtf(dx * dx + dy * dy);
        if (len < SQ_SEG_MIN_MM) {
            continue;
        }
        if (len <= SQ_SEG_MAX_MM) {
            ffr_add_dir4(dx, dy, len, &q->c4[part], &q->s4[part]);
            q->w[part] += len;
            q->wt[part] += len * q->raw_rad;
        }
        q->ax_mm[i] = px;
        q->ay_mm[i] = py;
    }
}

int ffr_scan_sq_fix(const ffr_scan_square_t *q, ffr_odometry_t *o, float *grow)
{
    float e[FFR_SQ_PARTS], t[FFR_SQ_PARTS], wp[FFR_SQ_PARTS];
    float sw = 0.0f, st = 0.0f, se = 0.0f, stt = 0.0f, ste = 0.0f, prev = 0.0f;
    float k, tmin = 0.0f, tmax = 0.0f;
    int i, n = 0;
    for (i = 0; i < FFR_SQ_PARTS; ++i) {
        if (q->w[i] < SQ_PART_MIN_MM) {
            continue;
        }
        e[n] = 0.25f * ffr_atan2f(q->s4[i], q->c4[i]);
        if (n > 0) {
            /* the error grows smoothly: the direction modulo 90 nearest the last */
            while (e[n] - prev > 0.25f * FFR_PI) {
                e[n] -= 0.5f * FFR_PI;
            }
            while (e[n] - prev < -0.25f * FFR_PI) {
                e[n] += 0.5f * FFR_PI;
            }
        }
        prev = e[n];
        t[n] = q->wt[i] / q->w[i];
        wp[n] = q->w[i];
        tmin = (n == 0 || t[n] < tmin) ? t[n] : tmin;
        tmax = (n == 0 || t[n] > tmax) ? t[n] : tmax;
        sw += wp[n];
        st += wp[n] * t[n];
        se += wp[n] * e[n];
        ++n;
    }
    if (n < 2 || tmax - tmin < SQ_SPAN_MIN_DEG * FFR_DEG) {
        return 0; /* too short a turn, or too little wall, to tell */
    }
    st /= sw;
    se /= sw;
    for (i = 0; i < n; ++i) {
        stt += wp[i] * (t[i] - st) * (t[i] - st);
        ste += wp[i] * (t[i] - st) * (e[i] - se);
    }
    k = ste / stt;
    *grow = k;
    {
        /* the true scale is the one that would not have grown the error */
        float span = tmax - tmin, w = span * span, prior = TURN_CAL_PRIOR_DEG * FFR_DEG;
        o->turn_w += w;
        o->turn_scale = ffr_clampf(o->turn_scale + w / (o->turn_w + prior * prior) * (o->turn_scale - k - o->turn_scale),
                                   TURN_CAL_MIN, TURN_CAL_MAX);
    }
    return 1;
}
