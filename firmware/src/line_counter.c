/*
 * Counting white lines. A rising edge of the line sensor is a new line unless
 * the robot has moved less than line_holdoff_mm since the last one: the 2.5 cm
 * line is under the sensor for several ticks, and a ring crossed at a slant
 * can flicker. White must read on LINE_CONFIRM_TICKS ticks in a row: a 2.5 cm
 * line crossed at cruise speed stays under the sensor for about ten, while a
 * misread (a speck, a reflection) lasts one.
 */
#include "ffr_internal.h"

#define LINE_CONFIRM_TICKS 3u

void ffr_lines_reset(ffr_line_counter_t *l)
{
    l->run = 0;
    l->level = 0;
    l->count = 0;
    l->last_edge_mm = -1.0e9f;
    l->edge = 0;
}

void ffr_lines_update(ffr_line_counter_t *l, const ffr_config_t *cfg, uint8_t line, float dist_mm)
{
    uint8_t now;
    l->run = line ? (uint8_t)(l->run < 255u ? l->run + 1u : 255u) : 0u;
    now = l->run >= LINE_CONFIRM_TICKS ? 1u : 0u;
    l->edge = 0;
    if (now && !l->level && dist_mm - l->last_edge_mm >= cfg->line_holdoff_mm) {
        l->edge = 1;
        l->count = (uint8_t)(l->count + 1u);
        l->last_edge_mm = dist_mm;
    }
    if (now) {
        l->last_edge_mm = l->edge ? dist_mm : l->last_edge_mm;
    }
    l->level = now;
}
