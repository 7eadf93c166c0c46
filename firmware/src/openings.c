/*
 * Side openings: a wall seen on one side for wall_seen_mm of travel, then
 * gone for open_confirm_mm; latched until the next route step. The front
 * corner ranger looks ahead, so where the wall ends is known: its last hit
 * point, ahead of the origin. At a junction the corner rangers end up seeing
 * the junction's own corners, so what they saw on the way in is what counts.
 */
#include "ffr_internal.h"

void ffr_openings_reset(ffr_openings_t *op)
{
    int i;
    for (i = 0; i < 2; ++i) {
        op->seen[i] = 0;
        op->opened[i] = 0;
        op->seen_mm[i] = 0.0f;
        op->open_mm[i] = 0.0f;
        op->open_at_mm[i] = 0.0f;
        op->since_open_mm[i] = 1.0e9f; /* never, in this step */
    }
}

void ffr_openings_update(ffr_openings_t *op, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT],
                         float dist_mm, float step_mm)
{
    int side;
    for (side = 0; side < 2; ++side) {
        int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        float d = ir_mm[f];
        if (d < cfg->open_mm) {
            op->seen_mm[side] += step_mm;
            if (op->seen_mm[side] >= cfg->wall_seen_mm) {
                op->seen[side] = 1;
            }
            op->open_mm[side] = 0.0f;
            op->since_open_mm[side] += step_mm;
            if (!op->opened[side]) {
                /* where the wall ends if the next reading is open: the hit point ahead */
                op->open_at_mm[side] = dist_mm + cfg->ir_x_mm[f] + d * ffr_cosf(cfg->ir_angle_deg[f] * FFR_DEG);
            }
        } else {
            op->open_mm[side] += step_mm;
            op->since_open_mm[side] = 0.0f;
            if (!op->seen[side]) {
                op->seen_mm[side] = 0.0f;
            } else if (op->open_mm[side] >= cfg->open_confirm_mm) {
                op->opened[side] = 1;
            }
        }
    }
}

int ffr_opening(const ffr_openings_t *op, int side) { return op->opened[side] != 0; }
