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

int ffr_turn_done(const ffr_config_t *cfg, const ffr_odometry_t *o, float target)
{
    float err = ffr_absf(target - o->heading_rad);
    float spin = ffr_absf(o->v_mm_s[1] - o->v_mm_s[0]) / cfg->track_width_mm;
    return err < cfg->turn_tol_deg * FFR_DEG && spin < 20.0f * FFR_DEG;
}
