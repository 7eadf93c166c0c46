/*
 * A candle beside the door the robot came in by (issue 13, doorcandle).
 *
 * The 2001 plan's rule lets a candle circle reach the doorway line, so the
 * entry can end with the candle beside the robot or already under its nose:
 *
 * - The entry may drive past the candle: the flame, near, falls off its
 *   peak as it leaves the sensors' view to the side; the entry ends there,
 *   before the body comes alongside the candle and the scan's turn in place
 *   sweeps a corner into it (ffr_entry_passing_flame), but not before the
 *   body is far enough in for that turn to clear the door's jambs.
 * - The scan then may begin just past the flame: its first reading is the
 *   tail of a flame behind the scan's way of turning, and the signal only
 *   falls. That fall is no peak passed; the flame sensors' balance at the
 *   start tells which side the flame is on (ffr_scan_starts_trailing).
 * - The approach may begin inside the candle circle: no line edge comes,
 *   and the front ranger, nearer than its span, reads at its bottom and
 *   then, nearer still, folds back (a GP2D12's output falls again below
 *   ~8 cm) and reads far. Either, with the flame near, means the candle's
 *   base stands at the fans' reach ahead (ffr_ahead_at_reach).
 * - The scan point may lie so near the doorway line that, turned to face
 *   out, the line sensor (ahead of the origin) is already past the line: it
 *   meets no line on the way out. Odometry tells how far past the line met
 *   on the way in it is (ffr_leave_past_line_mm).
 */
#include "ffr_internal.h"

/* chosen: the entry's flame signal fallen below this share of its peak is
 * passing by (the scan's own rule, room.c SCAN_PAST_PEAK): a flame's
 * flicker (the realistic profile) moves it by 30 % at most in the traces */
#define ENTRY_PAST_PEAK 0.6f
/* chosen: ...a peak at least this strong (x flame_detect): the flame within
 * the fans' reach (room.c: ~8 x at 30 cm at the edge of the sensors' view);
 * a weaker one passed is left to the scan */
#define ENTRY_NEAR_X 8.0f
/* chosen: a passed flame ends the entry only once the axle is this far past
 * the doorway line (mm; the line sensor met it line_sensor_x_mm ahead of
 * the axle). The scan turns in place there and its front corners sweep the
 * body's corner radius (156 mm): 100 mm past the line, 90 mm past the
 * jamb's face (walls ~2 cm thick), clears a jamb 127 mm or more to the side,
 * a robot up to 10 cm off a 46 cm door's middle. Sooner, the scan's turn
 * swept a corner into the jamb (2001 plan, +-2.5 cm jitter, candles beside
 * the door: the flame passed with the axle 63 mm past the line;
 * docs/robustness.md) */
#define ENTRY_AXLE_IN_MM 100.0f
/* chosen: the balance (left - right over the sum) beyond which the flame is
 * on one side; the sensors' views overlap straight ahead, where it is ~0 */
#define TRAIL_BAL 0.25f
/* chosen: the scan's first reading at least this (x flame_detect: a flame
 * detected) for its side to count. Only asked after an entry that passed
 * the flame near (room.c): a flame 50-60 degrees to the side, at the edge
 * of the sensors' view, reads 1.4-2.2 x there (2001 plan, room 3's candles
 * beside the door); at 2 x those scans stopped at once, 50 degrees off */
#define TRAIL_SIG_X 1.0f
/* the flame near, x flame_detect (room.c FLAME_NEAR) */
#define AHEAD_FLAME_X 4.0f
/* chosen: a reading up to this (mm off the ranger) is near enough to watch
 * for the fold-back: folded, the candle's base 1-3 cm off the ranger read
 * 150-240 mm in the 2001 arena's traces */
#define AHEAD_WATCH_MM 200.0f
/* chosen: the reading grown this much over its minimum... */
#define AHEAD_GROW_MM 30.0f
/* ...while the robot drove on at least this far since: folded back (noise
 * at 10-20 cm is ~10 mm, datasheet profile) */
#define AHEAD_MOVED_MM 10.0f
/* no minimum yet */
#define AHEAD_NONE 30000

int ffr_entry_passing_flame(const ffr_config_t *cfg, float *peak, float sig, float moved_mm)
{
    if (sig > *peak) {
        *peak = sig;
    }
    return *peak >= ENTRY_NEAR_X * cfg->flame_detect && sig < ENTRY_PAST_PEAK * *peak
           && moved_mm >= cfg->line_sensor_x_mm + ENTRY_AXLE_IN_MM;
}

int ffr_scan_starts_trailing(const ffr_config_t *cfg, float dir, float left, float right, float sig)
{
    float bal;
    if (sig < TRAIL_SIG_X * cfg->flame_detect) {
        return 0; /* no flame near enough to matter: a far one at the side
                   * the approach steers to by the balance (the 2004 arena's
                   * room 4, table1: 1.4 x at the scan's start) */
    }
    bal = (left - right) / sig;
    return dir * bal < -TRAIL_BAL;
}

void ffr_ahead_reset(ffr_room_state_t *r)
{
    r->ahead_min_mm = AHEAD_NONE;
    r->ahead_min_at_mm = 0;
}

int ffr_ahead_at_reach(const ffr_config_t *cfg, ffr_room_state_t *r, float ir_cf_mm, float dist_mm, float sig)
{
    int near;
    if (!ffr_ir_valid(cfg, ir_cf_mm)) {
        return 0;
    }
    near = sig >= AHEAD_FLAME_X * cfg->flame_detect;
    /* kept as whole mm, the distance from the approach's start (the state
     * must fit FFR_STATE_MAX) */
    dist_mm -= r->phase_start_mm;
    if (ir_cf_mm < (float)r->ahead_min_mm) {
        r->ahead_min_mm = (int16_t)(ir_cf_mm + 0.5f);
        r->ahead_min_at_mm = (int16_t)ffr_clampf(dist_mm + 0.5f, -30000.0f, 30000.0f);
    }
    if (!near) {
        return 0;
    }
    if (ir_cf_mm <= cfg->ir_min_mm + 0.5f) {
        return 1; /* at the bottom of the span: within ~10 cm */
    }
    return (float)r->ahead_min_mm <= AHEAD_WATCH_MM && ir_cf_mm >= (float)r->ahead_min_mm + AHEAD_GROW_MM
           && dist_mm - (float)r->ahead_min_at_mm >= AHEAD_MOVED_MM;
}

float ffr_leave_past_line_mm(const ffr_state_t *st)
{
    const ffr_room_state_t *r = &st->room;
    float h = st->odo.heading_rad;
    float sx = st->odo.x_mm + st->cfg.line_sensor_x_mm * ffr_cosf(h);
    float sy = st->odo.y_mm + st->cfg.line_sensor_x_mm * ffr_sinf(h);
    return (sx - r->line_x_mm) * ffr_cosf(r->exit_heading_rad) + (sy - r->line_y_mm) * ffr_sinf(r->exit_heading_rad);
}
