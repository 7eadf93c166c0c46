/*
 * The six wall cases of the paper's Fig. 9 (plus plain corridor and open
 * floor), classified from the rangers, and the turn each one calls for.
 * Forced cases need no plan; in the others (T junction, side branches) the
 * route program's preferred side decides.
 */
#include "ffr_internal.h"

ffr_wall_case_t ffr_wall_case(int front, int lo, int ro)
{
    if (front) {
        if (lo && ro) {
            return FFR_CASE_T;
        }
        if (lo) {
            return FFR_CASE_CORNER_LEFT;
        }
        if (ro) {
            return FFR_CASE_CORNER_RIGHT;
        }
        return FFR_CASE_DEAD_END;
    }
    if (lo && ro) {
        return FFR_CASE_OPEN;
    }
    if (lo) {
        return FFR_CASE_BRANCH_LEFT;
    }
    if (ro) {
        return FFR_CASE_BRANCH_RIGHT;
    }
    return FFR_CASE_CORRIDOR;
}

ffr_wall_case_t ffr_wall_case_sensed(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT],
                                     const ffr_openings_t *op)
{
    int front = ffr_front_distance(cfg, ir_mm) < cfg->front_slow_mm;
    /* open if it read open within a hallway's width of travel: nearing a
     * junction the corner ranger sees the side open before the wall ahead */
    const float recent = 2.0f * cfg->hallway_half_mm;
    int lo = op->since_open_mm[FFR_SIDE_LEFT] < recent || !(ir_mm[FFR_IR_LF] < cfg->open_mm);
    int ro = op->since_open_mm[FFR_SIDE_RIGHT] < recent || !(ir_mm[FFR_IR_RF] < cfg->open_mm);
    return ffr_wall_case(front, lo, ro);
}

int16_t ffr_wall_case_turn(ffr_wall_case_t c, uint8_t prefer)
{
    switch (c) {
    case FFR_CASE_CORNER_LEFT:
        return 90;
    case FFR_CASE_CORNER_RIGHT:
        return -90;
    case FFR_CASE_DEAD_END:
        return 180;
    case FFR_CASE_T:
        return prefer == FFR_SIDE_RIGHT ? -90 : 90;
    case FFR_CASE_BRANCH_LEFT:
        return prefer == FFR_SIDE_LEFT ? 90 : 0;
    case FFR_CASE_BRANCH_RIGHT:
        return prefer == FFR_SIDE_RIGHT ? -90 : 0;
    case FFR_CASE_CORRIDOR:
    case FFR_CASE_OPEN:
    default:
        return 0;
    }
}
