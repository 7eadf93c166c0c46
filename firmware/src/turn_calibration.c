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
