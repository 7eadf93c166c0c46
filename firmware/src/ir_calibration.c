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

int ffr_ir_valid(const ffr_config_t *cfg, float d_mm) { return d_mm <= cfg->ir_max_mm; }

void ffr_ir_hit(const ffr_config_t *cfg, int i, float d_mm, float *px, float *py)
{
    float a = cfg->ir_angle_deg[i] * FFR_DEG;
    *px = cfg->ir_x_mm[i] + d_mm * ffr_cosf(a);
    *py = cfg->ir_y_mm[i] + d_mm * ffr_sinf(a);
}
