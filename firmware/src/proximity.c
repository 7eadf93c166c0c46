/* Moving forward by the proximity sensors: slow down as a wall comes ahead. */
#include "ffr_internal.h"

float ffr_front_distance(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT])
{
    float d = ir_mm[FFR_IR_CF];
    if (!ffr_ir_valid(cfg, d)) {
        return 1.0e6f;
    }
    return d + cfg->ir_x_mm[FFR_IR_CF]; /* measured from the origin */
}

/*
 * The wall ahead where it is now, not where the reading saw it: a GP2D12's
 * output is the measurement of its last period, so it is one to two periods
 * (38.3 +- 9.6 ms each, datasheet) old when read. The robot has driven on
 * since; odometry's forward speed times FFR_IR_AGE_MS comes off (never adds:
 * a robot backing away keeps the reading).
 */
float ffr_front_now(const ffr_config_t *cfg, const ffr_odometry_t *o, const float ir_mm[FFR_IR_COUNT])
{
    float d = ffr_front_distance(cfg, ir_mm);
    float v = 0.5f * (o->v_mm_s[0] + o->v_mm_s[1]);
    if (d >= 1.0e6f || v <= 0.0f) {
        return d;
    }
    return d - v * (0.001f * FFR_IR_AGE_MS);
}

float ffr_proximity_speed(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float cruise)
{
    float d = ffr_front_distance(cfg, ir_mm);
    float span = cfg->front_slow_mm - cfg->front_stop_mm;
    float k;
    if (span <= 1.0f) {
        return cruise;
    }
    k = ffr_clampf((d - cfg->front_stop_mm) / span, 0.0f, 1.0f);
    /* never crawl: the front event stops the robot, not a vanishing speed */
    return cruise * (0.35f + 0.65f * k);
}
