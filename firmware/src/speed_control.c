/*
 * Motor speed control: each wheel follows a ramped speed reference with
 * feed-forward (the motor's steady-state PWM for that speed), a proportional
 * term on the filtered speed, and an integral on position error. The encoder
 * measures position exactly but speed only to one count per tick (~50 mm/s at
 * 10 ms), so integrating the position error gives a clean integral term.
 */
#include "ffr_internal.h"

void ffr_speed_reset(ffr_speed_ctl_t *s)
{
    s->v_ref[0] = 0.0f;
    s->v_ref[1] = 0.0f;
    s->pos_err_mm[0] = 0.0f;
    s->pos_err_mm[1] = 0.0f;
}

void ffr_speed_control(ffr_speed_ctl_t *s, const ffr_config_t *cfg, const ffr_odometry_t *o,
                       float v_mm_s, float w_rad_s, float dt_s, int16_t pwm[2])
{
    const float half_track = 0.5f * cfg->track_width_mm;
    const float dv_max = cfg->accel_mm_s2 * dt_s;
    const float lim = (float)cfg->pwm_limit;
    float target[2];
    int i;
    target[0] = v_mm_s - w_rad_s * half_track;
    target[1] = v_mm_s + w_rad_s * half_track;
    for (i = 0; i < 2; ++i) {
        float u;
        s->v_ref[i] += ffr_clampf(target[i] - s->v_ref[i], -dv_max, dv_max);
        s->pos_err_mm[i] += s->v_ref[i] * dt_s - o->dpos_mm[i];
        s->pos_err_mm[i] = ffr_clampf(s->pos_err_mm[i], -40.0f, 40.0f);
        u = cfg->ff_gain_permille_per_mm_s * s->v_ref[i];
        if (s->v_ref[i] > 1.0f) {
            u += cfg->ff_offset_permille;
        } else if (s->v_ref[i] < -1.0f) {
            u -= cfg->ff_offset_permille;
        }
        u += cfg->speed_kp * (s->v_ref[i] - o->v_mm_s[i]) + cfg->speed_ki * s->pos_err_mm[i];
        u = ffr_clampf(u, -lim, lim);
        /* round half away from zero, portable */
        pwm[i] = (int16_t)(u >= 0.0f ? (int32_t)(u + 0.5f) : -(int32_t)(-u + 0.5f));
    }
}
