/*
 * Inverse GP2D12 calibration: mV -> distance from the sensor in mm.
 * The datasheet's typical curve is close to V = k / (d + d0) + offset
 * (k = 33.2 V cm, d0 = 4 cm, offset = 15 mV), so d = k / (V - offset) - d0.
 * Readings past the valid range (too weak: far or no wall) map to "none".
 * Below 10 cm the sensor folds back and reads like a far wall; the robot's
 * layout keeps walls beyond 10 cm, which is why rangers sit inside the body.
 */
#include "ffr_internal.h"

float ffr_ir_mv_to_mm(const ffr_config_t *cfg, uint16_t mv)
{
    float v = (float)mv;
    float d;
    if (v < cfg->ir_min_mv || v <= cfg->ir_offset_mv) {
        return FFR_IR_NONE(cfg);
    }
    d = cfg->ir_k_mv_mm / (v - cfg->ir_offset_mv) - cfg->ir_d0_mm;
    if (d > cfg->ir_max_mm) {
        return FFR_IR_NONE(cfg);
    }
    if (d < cfg->ir_min_mm) {
        d = cfg->ir_min_mm;
    }
    return d;
}

void ffr_ir_geom_init(ffr_ir_geom_t *g, const ffr_config_t *cfg)
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float a = cfg->ir_angle_deg[i] * FFR_DEG;
        g->beam_cos[i] = ffr_cosf(a);
        g->beam_sin[i] = ffr_sinf(a);
        g->hit_x_mm[i] = cfg->ir_x_mm[i];
        g->hit_y_mm[i] = cfg->ir_y_mm[i];
    }
}

/* Every ranger's, valid or not: cheaper than asking which (a few
 * multiply-adds each), and the mounting angles' trig is not redone. */
void ffr_ir_geom_update(ffr_ir_geom_t *g, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        g->hit_x_mm[i] = cfg->ir_x_mm[i] + ir_mm[i] * g->beam_cos[i];
        g->hit_y_mm[i] = cfg->ir_y_mm[i] + ir_mm[i] * g->beam_sin[i];
    }
}
