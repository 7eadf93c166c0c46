/* Dead reckoning from the two wheel encoders (the paper's eqs. (1)-(3)). */
#include "ffr_internal.h"

void ffr_odometry_reset(ffr_odometry_t *o)
{
    o->last_enc[0] = 0;
    o->last_enc[1] = 0;
    o->primed = 0;
    o->x_mm = 0.0f;
    o->y_mm = 0.0f;
    o->heading_rad = 0.0f;
    o->dist_mm = 0.0f;
    o->v_mm_s[0] = 0.0f;
    o->v_mm_s[1] = 0.0f;
    o->dpos_mm[0] = 0.0f;
    o->dpos_mm[1] = 0.0f;
    o->turn_scale = 1.0f;
    o->rot_raw_rad = 0.0f;
    o->turn_w = 0.0f;
}

void ffr_odometry_update(ffr_odometry_t *o, const ffr_config_t *cfg, const int32_t enc[2], float dt_s)
{
    const float mm_per_tick = 2.0f * FFR_PI * cfg->wheel_radius_mm / cfg->encoder_ticks_per_rev;
    float ds;
    float dth;
    float mid;
    int i;
    if (!o->primed) {
        /* the first reading only sets the zero: encoders may start anywhere */
        o->last_enc[0] = enc[0];
        o->last_enc[1] = enc[1];
        o->primed = 1;
    }
    for (i = 0; i < 2; ++i) {
        /* difference in 32-bit two's complement: counter wrap-around is harmless */
        int32_t d = (int32_t)((uint32_t)enc[i] - (uint32_t)o->last_enc[i]);
        o->last_enc[i] = enc[i];
        o->dpos_mm[i] = (float)d * mm_per_tick;
        o->v_mm_s[i] = 0.6f * o->v_mm_s[i] + 0.4f * (o->dpos_mm[i] / dt_s);
    }
    ds = 0.5f * (o->dpos_mm[0] + o->dpos_mm[1]);
    dth = (o->dpos_mm[1] - o->dpos_mm[0]) / cfg->track_width_mm;
    o->rot_raw_rad += dth;
    dth *= o->turn_scale; /* the turn scale the walls taught (turn_calibration.c) */
    mid = o->heading_rad + 0.5f * dth;
    o->x_mm += ds * ffr_cosf(mid);
    o->y_mm += ds * ffr_sinf(mid);
    o->heading_rad += dth;
    o->dist_mm += ffr_absf(ds);
}
