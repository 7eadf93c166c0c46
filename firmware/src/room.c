/*
 * The room task (the paper's Fig. 11) and the flame task (Fig. 12).
 *
 * Enter: straight through the door until the doorway line, then a little
 * further. Scan: rotate in place and remember the heading of the strongest
 * flame signal; stop once the signal has clearly passed its peak. Approach:
 * drive toward the flame, steering by the two flame sensors' balance, until
 * the line sensor meets the candle circle. Extinguish: fans on until the
 * flame is gone, fans off, watch that it stays out. Leave: back to where the
 * scan was made (odometry inside one room is short and reliable), face the
 * door, drive out across the doorway line.
 *
 * Organised as a chart's generated code is: one handler a phase, each doing
 * the phase's work for this tick and returning the next phase (RP_STAY: no
 * transition), and a dispatcher that enters the phase returned. The geometry
 * the handlers ask about (the door, its wall, the walls by the body) is in
 * room_guards.c. What the route must do (take the heading out, go on) is
 * returned to route.c, which owns the route's state.
 *
 *   ENTER_LINE --line--> ENTER_IN --deep enough / line / wall--> SCAN
 *   SCAN --peak passed, or a full turn with a flame--> TURN_BEST --> APPROACH
 *   SCAN --a full turn, no flame--> LEAVE_TURN
 *   SCAN --a full turn, the approached flame lost > FFR_FLAME_LOST_MS--> failed (flame lost)
 *   APPROACH --stopped, flame near--> EXTINGUISH;  --at the door / flame far--> BACK_DRIVE
 *   APPROACH --flame lost--> SCAN
 *   EXTINGUISH --strength stop, lit after the dwell--> APPROACH as a step (CLOSER_STEP_MM, CLOSER_STEPS)
 *   EXTINGUISH --out for flame_out_confirm_ms--> VERIFY;  --timeout--> EXTINGUISH,
 *              APPROACH as a creep (stopped by the wall guard alone, CREEP_MM),
 *              APPROACH (stopped by strength alone) or failed (not out)
 *   VERIFY --stays out verify_ms--> BACK_TURN --> BACK_DRIVE --> LEAVE_TURN;  --back--> EXTINGUISH
 *   LEAVE_TURN --facing out--> LEAVE_LINE --line--> LEAVE_OUT --out--> (left)
 *   SCAN --a full turn, no flame, but one seen driving in--> DEEPER --> SCAN (once a room)
 *   a room searched harder (search_harder: the route's last, or the explorer's
 *   second round): SCAN --a full turn, no flame--> DEEPER --> SCAN
 *        --a full turn, no flame--> ASIDE_TURN --> ASIDE --> SCAN --a full turn, no flame--> BACK_TURN
 *        (ASIDE_TURN --no way open--> LEAVE_TURN)
 *
 * Furniture (obstacle_avoid.c): the scan and the approach put the rangers'
 * hits into a grid; the approach detours around what is in the body's way to
 * the flame and backs out through the detour's turning points.
 */
#include "ffr_internal.h"

enum {
    RP_ENTER_LINE = 0,
    RP_ENTER_IN,
    RP_SCAN,
    RP_TURN_BEST,
    RP_APPROACH,
    RP_EXTINGUISH,
    RP_VERIFY,
    RP_BACK_TURN,
    RP_BACK_DRIVE,
    RP_LEAVE_TURN,
    RP_LEAVE_LINE,
    RP_LEAVE_OUT,
    RP_DEEPER,
    RP_ASIDE_TURN,
    RP_ASIDE,
    RP_COUNT
};
/* a handler's "no transition" */
#define RP_STAY 0xFFu

/* A flame within the fans' reach reads far above the detection threshold:
 * on axis at 30 cm about 20x, at the edge of the sensors' view still ~8x. */
#define FLAME_NEAR 4.0f
/* share of each new flame reading in the filtered signal (a ~40 ms average) */
#define FLAME_FILTER 0.25f
/* the flame sum (over the dark level) at about 26 cm of the fans, in units
 * of flame_detect: the fans (30 cm reach) put it out from there */
#define FLAME_REACH 14.0f
/* a scan's peak this strong (x flame_detect) is no wall's reflection:
 * chosen, 2 (the realistic profile's reflectance 0.3 gave peaks of 1.2-1.3
 * facing a wall 20 cm away with the flame behind) */
#ifndef SCAN_SURE
#define SCAN_SURE 2.0f
#endif
/* chosen: a wall ahead nearer than this (front distance) can mirror the flame
 * strongly enough to pass for it */
#ifndef SCAN_WALL_MM
#define SCAN_WALL_MM 400.0f
#endif
/* chosen: the scan's signal fallen below this share of its peak has passed
 * the flame (the sensors' view is ~+-30 degrees wide) */
#define SCAN_PAST_PEAK 0.6f
/* a scan turns in place at most once round before it decides */
#define SCAN_FULL_TURN_RAD (2.0f * FFR_PI)
/* chosen: the approach's flame below this share of flame_detect is lost (or
 * went out by itself); half keeps noise near the threshold from ending it */
#define FLAME_LOST_SHARE 0.5f
/* counts: the flame's balance is taken over at least this sum (no division
 * by a sum near zero) */
#define BAL_MIN_SUM 1.0f
#ifndef SCAN_CROSS_X
#define SCAN_CROSS_X 4.0f
#endif
#ifndef SCAN_CROSS_BAL
#define SCAN_CROSS_BAL 0.25f
#endif
/* room_state_t.scan_trail before the scan's first tick */
#define SCAN_TRAIL_UNKNOWN 2u
/* chosen: a scan begun with the flame on its trailing side (room_entry.c)
 * has passed no peak while its best is still within this of its start */
#define SCAN_TRAIL_RAD (10.0f * FFR_DEG)
/* chosen: facing out, the line sensor this near (mm, along the way out)
 * to the doorway line's middle, or past it, is on it (a line is 25.4 mm
 * wide): no edge will come */
#define LEAVE_ON_LINE_MM 25.0f
/* chosen: ...and only after an entry that passed the flame near: its peak
 * at least this (x flame_detect; the 2001 plan's candles beside the door:
 * 8-13 x; a far flame at the side, 3 x, is left to the approach's steering
 * as before, a full turn costing 2.4 s) */
#define SCAN_TRAIL_ENTRY_X 6.0f
/* chosen: ...or a peak at least this (x flame_detect) that the scan's first
 * reading has fallen below SCAN_PAST_PEAK of: passed and fading (the 2001
 * plan's candles beside room 3's door: peaks of 5.3 x, the scan starting at
 * 2.2 x). A weaker peak not yet fallen is a flame still ahead (the 2004
 * arena's, 14 degrees off: with 4 x alone 121 of 2,000 realistic missions
 * took up to 4.8 s longer, and a fresh +-2.5 cm start lost one) */
#define SCAN_TRAIL_FADED_X 4.0f
/* backing out, the scan point reached within this (mm) */
#define BACK_AT_SCAN_MM 15.0f
/* backing out after a detour: a point passed this near counts as reached
 * (mm), and the tail is first turned toward the next one if it points more
 * than this far off (degrees; chosen) */
#define BACK_VIA_PASSED_MM 60.0f
#define BACK_TURN_FIRST_DEG 30.0f
/* chosen: a flame seen driving in this far (share) from the dark level to
 * flame_detect, and the scan from there finds none: something in the room
 * hides it (furniture), and a second scan is made deeper in. Half way is
 * well clear of the sensors' noise (a few counts) */
#define ENTRY_SEEN_SHARE 0.5f
/* chosen: the second scan point at most this far beyond the first, along the
 * entry heading (a room is 1-1.25 m deep; the first point ~0.4 m in) */
#define DEEPER_MM 400.0f
/* chosen: the third scan point (search_harder), off the entry's line: this
 * far from the second (on up to ASIDE_ON_MM more while a scan there would
 * sweep something the rangers saw), at this angle (or twice it) to the entry
 * heading, only where the grid has at least ASIDE_MIN_MM clear, and
 * ASIDE_SHORT_MM short of the first thing it has: a mark's cell is 64 mm,
 * the thing in it up to half that nearer than its centre (with 20 mm an
 * explorer's front corner met the piece: start seed 18, --furniture 4) */
#define ASIDE_MM 400.0f
#define ASIDE_DEG 45.0f
#define ASIDE_MIN_MM 150.0f
#define ASIDE_ON_MM 150.0f
#define ASIDE_SHORT_MM 60.0f
#define ASIDE_HEADINGS 4u
/* the scan turns in place: nothing the rangers saw within the body's corner
 * radius (156 mm) and this margin of the second scan point (chosen) */
#define DEEPER_CLEAR_MARGIN_MM 35.0f
/* ... going on brings a mark nearer by more than this (mm, of the 40 mm
 * looked ahead): not a wall alongside, whose nearest cell only wavers with
 * the grid's 64 mm cells */
#define DEEPER_CLOSING_MM 15.0f
/* the approach looks for obstacles in its corridor this share of the flame's
 * distance told by its strength (FLAME_REACH at FLAME_REACH_MM; chosen: the
 * strength's distance is good to about +-40 % over the flames' sizes, and
 * the candle and the walls behind it must stay out), and at most this far
 * past the body's front (chosen) */
#define FLAME_REACH_MM 260.0f
#define AVOID_SHARE 0.5f
#define AVOID_LOOK_MM 300.0f
/* driving to the second scan point, the clearance is checked this far ahead
 * (mm, twice: a tick or two of travel at room speed) */
#define AVOID_STEP_AHEAD_MM 20.0f
/* the obstacle grid (1.54 m a side) is centred this far beyond the scan
 * point along the entry heading (chosen: the rangers' kept hits reach 0.7 m
 * round the scan point; the approach goes on into the room, toward the far
 * wall, not back to the door) */
#define GRID_AHEAD_MM 200.0f
/* room_state_t.flame_found: none, found, and found with the approach stopped
 * by the flame's strength (FLAME_REACH) beside a wall, then going closer;
 * found with the approach stopped by the wall guard alone (FOUND_BY_GUARD),
 * then creeping on (FOUND_CREEP) after a failed try of the fans */
enum { FOUND = 1, FOUND_BY_STRENGTH = 2, FOUND_CLOSER = 3, FOUND_BY_GUARD = 4, FOUND_CREEP = 5, FOUND_STEP = 6 };
/* Stopped beside a wall by the flame's strength (FOUND_BY_STRENGTH), the fans
 * blow for a dwell of STEP_DWELL_SHARE x fan_timeout_ms; the flame still lit,
 * the robot goes CLOSER_STEP_MM closer at the creep's speed (FOUND_STEP, the
 * approach's guards and steering) and the fans blow there, up to CLOSER_STEPS
 * times, before the closer approach of old (FOUND_CLOSER, on to the line).
 * A big flame's strength passes FLAME_REACH 33-49 cm from the fans' outlet
 * (realistic strengths up to 1.4, flicker, the wall's reflection); the fans
 * reach 30 cm within 30 degrees. The approach to the line from there ended
 * with the flame 29-36 degrees off the axis or a front corner on the wall:
 * short steps stop in the band between.
 * chosen: 40 mm a step (the band is 10-15 cm deep along the traced approaches),
 * 5 steps (20 mm short of the 49 cm stops' 19 cm), a dwell of 5 s at the default
 * 8 s timeout (fan_timeout_ms is twice the paper's 4 s of air; the dwell
 * leaves the wick's afterglow and the filter's lag on top of those 4 s) */
#define CLOSER_STEP_MM 40.0f
#define CLOSER_STEPS 5u
#define STEP_DWELL_SHARE 0.625f
#define STEP_LIT_SHARE 0.5f
/* chosen: a creep after a failed fan try beside a wall goes at most this far
 * (mm): the traced stops left the flame 33-38 cm from the fans' outlet, 3-8 cm
 * beyond their 30 cm reach */
#ifndef CREEP_MM
#define CREEP_MM 80.0f
#endif
/* chosen: the creep's speed (mm/s), a third of the approach's: the guard's
 * steering acts within a few mm */
#ifndef CREEP_SPEED_MM_S
#define CREEP_SPEED_MM_S 60.0f
#endif

/* flame_detect and flame_out are set for this dark level (2 x 40 counts) */
#define FLAME_DARK_NOMINAL 80.0f

/* What every handler of one tick shares. */
typedef struct {
    const ffr_inputs_t *in;
    float sig;                /* both flame sensors over the dark level   */
    float moved;              /* mm driven since the phase began           */
    uint32_t elapsed;         /* ms since the phase began                  */
    ffr_room_result_t result; /* for route.c                               */
} room_tick_t;

typedef uint8_t (*room_handler_t)(ffr_state_t *st, room_tick_t *t);

/* both flame sensors, measured from the dark level learned so far (mission.c) */
static float flame_sum(const ffr_state_t *st, const ffr_inputs_t *in)
{
    return (float)in->flame[0] + (float)in->flame[1] - (st->flame_dark - FLAME_DARK_NOMINAL);
}

/* the unwrapped heading closest to `heading` that points the way `dir` does */
static float closest(float heading, float dir) { return heading + ffr_wrap_pi(dir - heading); }

/* A room whose candle scans from the entry's line may miss (furniture hides
 * it): the route's last room, where the candle must be if none was found
 * before (route.c), or any room the explorer searches once it has come round
 * a loop with no flame (explore.c). There a second scan point is made with
 * no flame seen driving in, and a third off the entry's line. */
static int search_harder(const ffr_state_t *st)
{
    return st->cfg.start_area == FFR_START_HALLWAY ? ffr_explore_searched_round(st) : ffr_route_last_room(st);
}

/* Enter phase p: its clocks restart, the state reported is its chart state,
 * and the scan starts afresh. */
static void enter(ffr_state_t *st, uint8_t p)
{
    static const uint8_t codes[RP_COUNT] = {
        FFR_ST_ENTER, FFR_ST_ENTER, FFR_ST_SCAN, FFR_ST_SCAN, FFR_ST_APPROACH, FFR_ST_EXTINGUISH,
        FFR_ST_VERIFY, FFR_ST_TO_DOOR, FFR_ST_TO_DOOR, FFR_ST_EXIT, FFR_ST_EXIT, FFR_ST_EXIT, FFR_ST_ENTER,
        FFR_ST_ENTER, FFR_ST_ENTER};
    ffr_room_state_t *r = &st->room;
    if (p == RP_SCAN) {
        r->start_heading_rad = st->odo.heading_rad;
        r->best_signal = 0.0f;
        r->best_heading_rad = st->odo.heading_rad;
        r->best_front_mm = 0.0f;
        ffr_scan_sq_reset(&r->square);
        r->scan_trail = SCAN_TRAIL_UNKNOWN;
        r->scan_lead = 0u;
    }
    if (p == RP_APPROACH) {
        ffr_ahead_reset(r);
    }
    r->fans_early = 0u;
    if (p == RP_ENTER_IN) {
        r->entry_peak = 0.0f;
    }
    r->phase = p;
    r->phase_start_mm = st->odo.dist_mm;
    r->phase_start_ms = st->t_ms;
    st->state = codes[p];
}

void ffr_room_begin(ffr_state_t *st, uint8_t room, float entry_heading_rad)
{
    st->room.room = room;
    st->room.attempts = 0;
    st->room.flame_found = 0;
    st->room.below_since_ms = 0;
    st->room.flame_f = 0.0f;
    st->room.entry_heading_rad = entry_heading_rad;
    st->room.exit_heading_rad = entry_heading_rad;
    st->room.lost_since_ms = 0u;
    st->room.flame_near = 0;
    st->room.entry_flame = 0.0f;
    st->room.deeper_mm = 0;
    st->room.scans = 1u;
    st->room.closer_steps = 0u;
    ffr_obst_reset(&st->room.obst, st->odo.x_mm, st->odo.y_mm);
    st->room.scan_trail = 0;
    st->room.entry_peak = 0.0f;
    ffr_ahead_reset(&st->room);
    enter(st, RP_ENTER_LINE);
}

/* a time stamp that is never 0 (0: not set) */
static uint32_t stamp(const ffr_state_t *st) { return st->t_ms == 0u ? 1u : st->t_ms; }

static int turn_to(ffr_state_t *st, float target)
{
    ffr_stop(st);
    st->cmd_w_rad_s = ffr_turn_yaw(&st->cfg, st->odo.heading_rad, target);
    if (ffr_turn_done(&st->cfg, &st->odo, target)) {
        ffr_stop(st);
        return 1;
    }
    return 0;
}

/* ---- the handlers, one a phase ------------------------------------------ */

static uint8_t on_enter_line(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    uint8_t next = RP_STAY;
    r->entry_flame = t->sig > r->entry_flame ? t->sig : r->entry_flame;
    /* the line's edge, or the line already under the sensor: a turn into
     * the door that ends late (a heading drifted on the way) brings the
     * sensor onto the line as it turns, and no edge comes from a line
     * already under it (realistic robot 5007: "doorway line not found" in
     * 38 of its 40 missions; docs/robustness.md). As the way out counts a
     * line crossed turning (on_leave_turn, LEAVE_ON_LINE_MM) */
    if (st->lines.edge || st->lines.level) {
        st->flags |= FFR_FLAG_IN_ROOM;
        /* the line is under the line sensor, ahead of the origin */
        r->line_x_mm = st->odo.x_mm + cfg->line_sensor_x_mm * ffr_cosf(st->odo.heading_rad);
        r->line_y_mm = st->odo.y_mm + cfg->line_sensor_x_mm * ffr_sinf(st->odo.heading_rad);
        next = RP_ENTER_IN;
    } else if (t->moved > cfg->room_line_max_mm) {
        ffr_fail(st, FFR_FAIL_NO_LINE);
        return RP_STAY;
    }
    ffr_drive_heading(st, r->entry_heading_rad, cfg->room_speed_mm_s);
    return next;
}

static uint8_t on_enter_in(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    /* deep enough that a candle along the door's wall can be approached
     * with room to spare; the candle circle or a wall ahead stops it sooner */
    r->entry_flame = t->sig > r->entry_flame ? t->sig : r->entry_flame;
    int passing = ffr_entry_passing_flame(cfg, &r->entry_peak, t->sig, t->moved);
    if (t->moved >= cfg->room_entry_mm || st->lines.edge || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm
        || passing) {
        ffr_stop(st);
        r->scan_x_mm = st->odo.x_mm;
        r->scan_y_mm = st->odo.y_mm;
        /* the grid's centre a little beyond the scan point, into the room */
        ffr_obst_reset(&r->obst, st->odo.x_mm + GRID_AHEAD_MM * ffr_cosf(r->entry_heading_rad),
                       st->odo.y_mm + GRID_AHEAD_MM * ffr_sinf(r->entry_heading_rad));
        return RP_SCAN;
    }
    ffr_drive_heading(st, r->entry_heading_rad + ffr_scan_room_offset(st),
                      ffr_stopping_speed(cfg->room_entry_mm - t->moved, cfg->room_speed_mm_s));
    return RP_STAY;
}

/* The scan ends: what its turn added to odometry's heading error, told by
 * the room's walls seen in it (turn_calibration.c), comes off the heading,
 * and off the heading of the best flame signal (less by what grew since).
 * The scan's rotation no longer counts toward the next wall fix: its share
 * of the error is gone. */
static void square_up(ffr_state_t *st)
{
    ffr_room_state_t *r = &st->room;
    float grow, raw_best;
    float scale = st->odo.turn_scale; /* before the fix teaches it */
    if (!ffr_scan_sq_fix(&r->square, &st->odo, &grow)) {
        return;
    }
    raw_best = r->square.raw_rad - (st->odo.heading_rad - r->best_heading_rad) / scale;
    st->odo.heading_rad -= grow * r->square.raw_rad;
    r->best_heading_rad -= grow * raw_best;
    st->odo.rot_raw_rad -= r->square.raw_rad;
}

/* the scan has found the flame: face it */
static uint8_t flame_found(ffr_state_t *st)
{
    square_up(st);
    st->room.flame_found = FOUND;
    st->room.lost_since_ms = 0u;
    st->flags |= FFR_FLAG_FLAME_SEEN;
    ffr_stop(st);
    return RP_TURN_BEST;
}

static uint8_t on_scan(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    float sig = t->sig;
    float turned = ffr_absf(st->odo.heading_rad - r->start_heading_rad);
    float dir = cfg->scan_dir ? -1.0f : 1.0f;
    ffr_scan_sq_record(&r->square, cfg, &st->odo, &st->ir_geom, st->ir_mm);
    ffr_obst_record(&r->obst, cfg, &st->odo, &st->ir_geom, st->ir_mm);
    if (ffr_through_door(st, st->odo.heading_rad)) {
        sig = 0.0f; /* a flame out there is not this room's */
    }
    if (r->scan_trail == SCAN_TRAIL_UNKNOWN) {
        /* its first reading: the tail of a flame behind the way it turns? */
        r->scan_trail = (uint8_t)((r->entry_peak >= SCAN_TRAIL_ENTRY_X * cfg->flame_detect
                                   || (r->entry_peak >= SCAN_TRAIL_FADED_X * cfg->flame_detect
                                       && sig < SCAN_PAST_PEAK * r->entry_peak))
                                  && ffr_scan_starts_trailing(cfg, dir, (float)t->in->flame[0],
                                                              (float)t->in->flame[1], sig));
    }
    if (sig > r->best_signal) {
        r->best_signal = sig;
        r->best_heading_rad = st->odo.heading_rad;
        r->best_front_mm = ffr_front_distance(cfg, st->ir_mm);
    }
    {
        /* the flame's balance (+: on the leading side of the turn) */
        float lead = dir * ((float)t->in->flame[0] - (float)t->in->flame[1]) / (sig > BAL_MIN_SUM ? sig : BAL_MIN_SUM);
        if (sig >= SCAN_CROSS_X * cfg->flame_detect) {
            if (lead > SCAN_CROSS_BAL) {
                r->scan_lead = 1u;
            } else if (r->scan_lead && lead < -SCAN_CROSS_BAL) {
                return flame_found(st);
            }
        } else {
            r->scan_lead = 0u;
        }
    }
    /* past the peak: stop early, unless a weak peak (below SCAN_SURE x
     * flame_detect) was seen facing a wall near ahead (SCAN_WALL_MM): it
     * may be the flame's image in that wall (white walls reflect) while
     * the flame itself is still behind. Then the whole turn, and the
     * strongest. */
    if (r->best_signal >= cfg->flame_detect && sig < SCAN_PAST_PEAK * r->best_signal
        && (r->best_signal >= SCAN_SURE * cfg->flame_detect || r->best_front_mm > SCAN_WALL_MM)
        && !(r->scan_trail && ffr_absf(r->best_heading_rad - r->start_heading_rad) < SCAN_TRAIL_RAD)) {
        return flame_found(st);
    }
    if (turned >= SCAN_FULL_TURN_RAD) {
        if (r->best_signal >= cfg->flame_detect) {
            return flame_found(st);
        }
        if (r->lost_since_ms == 0u) {
            ffr_stop(st);
            square_up(st);
            if (r->scans < 2u
                && (r->entry_flame >= FLAME_DARK_NOMINAL + ENTRY_SEEN_SHARE * (cfg->flame_detect - FLAME_DARK_NOMINAL)
                    || search_harder(st))) {
                /* seen driving in, not from here (or a room searched
                 * harder): look again deeper in */
                r->scans = 2u;
                return RP_DEEPER;
            }
            if (r->scans == 2u && search_harder(st)) {
                r->scans = 3u;
                r->obst.aside_next = 0u;
                r->best_front_mm = 0.0f; /* no heading found yet */
                return RP_ASIDE_TURN;
            }
            /* no flame in this room; from a third point, back to the second first */
            return r->scans == 3u ? RP_BACK_TURN : RP_LEAVE_TURN;
        }
        if (st->t_ms - r->lost_since_ms >= FFR_FLAME_LOST_MS) {
            /* the flame approached is gone, not put out, and not found again */
            ffr_fail(st, FFR_FAIL_LOST_FLAME);
            return RP_STAY;
        }
        /* lost only a moment ago: scan on */
    }
    ffr_stop(st);
    st->cmd_w_rad_s = dir * cfg->scan_rate_deg_s * FFR_DEG;
    return RP_STAY;
}

static uint8_t on_turn_best(ffr_state_t *st, room_tick_t *t)
{
    (void)t;
    if (turn_to(st, st->room.best_heading_rad)) {
        ffr_obst_trail(&st->room.obst, &st->odo, 1);
        return RP_APPROACH;
    }
    return RP_STAY;
}

/* How far past the body's front the approach looks for obstacles: a share
 * of the flame's distance as its strength tells it (none once it is near). */
static float avoid_reach(const ffr_state_t *st, float sig)
{
    const ffr_config_t *cfg = &st->cfg;
    float s = sig > 0.5f * cfg->flame_detect ? sig : 0.5f * cfg->flame_detect;
    float d = FLAME_REACH_MM * ffr_sqrtf(FLAME_REACH * cfg->flame_detect / s);
    return ffr_clampf(AVOID_SHARE * d - cfg->body_front_mm, 0.0f, AVOID_LOOK_MM);
}

static uint8_t on_approach(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    const ffr_inputs_t *in = t->in;
    float sig = t->sig;
    /* the flame's balance: + on the left */
    float bal = ((float)in->flame[0] - (float)in->flame[1]) / (sig > BAL_MIN_SUM ? sig : BAL_MIN_SUM);
    int guard_stop, guard_near;
    const ffr_door_frame_t df = ffr_door_frame(st);
    const int creep = r->flame_found == FOUND_CREEP;
    const int step = r->flame_found == FOUND_STEP;
    float guard_w;
    int front_stop;
    if (creep) {
        /* creeping on after a failed fan try: the rangers steer it off walls
         * (and stop it, as in the approach); the door's wall, known by
         * odometry alone (a few cm off on slipping tracks), only steers it */
        int door_stop = 0;
        guard_w = ffr_ranger_guard(st, &guard_stop, &guard_near);
        guard_w += ffr_door_wall_guard(st, &df, bal, &door_stop);
    } else {
        guard_w = ffr_approach_guard(st, &df, bal, &guard_stop, &guard_near);
    }
    float flame_dir = st->odo.heading_rad + bal * cfg->flame_steer_deg * FFR_DEG;
    float free_mm;
    /* near the flame (or going closer or creeping on after the fans) the
     * guards alone, as without furniture: the candle's own base is then in
     * the corridor */
    float reach = (sig >= FLAME_NEAR * cfg->flame_detect || r->flame_near || r->flame_found == FOUND_CLOSER || step || creep)
                      ? 0.0f
                      : avoid_reach(st, sig);
    float detour = ffr_obst_detour(&r->obst, cfg, &st->odo, flame_dir, reach, &free_mm);
    ffr_obst_record(&r->obst, cfg, &st->odo, &st->ir_geom, st->ir_mm);
    ffr_obst_trail(&r->obst, &st->odo, 0);
    /* beside a wall with the flame already within the fans' reach: stop
     * here rather than creep on along the wall; a part reading long
     * lets a front corner reach the wall before the guard stops it */
    int reach_stop = 0;
    int creep_end = 0;
    /* the candle's base at the fans' reach ahead, told by the front ranger
     * (a candle beside the door: the approach may begin inside its circle) */
    int ahead = ffr_ahead_at_reach(cfg, r, st->ir_mm[FFR_IR_CF], st->odo.dist_mm, sig);
    if (sig >= FLAME_NEAR * cfg->flame_detect) {
        r->flame_near = 1;
    }
    if (guard_near && sig >= FLAME_REACH * cfg->flame_detect && r->flame_found != FOUND_CLOSER && !step && !creep
        && !guard_stop) {
        reach_stop = 1;
    }
    front_stop = ffr_front_distance(cfg, st->ir_mm) < cfg->approach_stop_mm;
    /* a step closer after a strength stop ends at its length, as if the
     * strength had stopped it there (nothing else stopping it) */
    if (step && t->moved >= CLOSER_STEP_MM && !guard_stop && !front_stop && !ahead && !st->lines.edge) {
        reach_stop = 1;
    }
    /* a creep ends at its length, or with the nose at the doorway it came
     * in by: the flame is in this room (seen near, the fans tried), so the
     * fans go on there instead of backing out */
    if (creep && (t->moved >= CREEP_MM || ffr_nose_in_doorway(st, &df))) {
        creep_end = 1;
    }
    if (st->lines.edge || guard_stop || reach_stop || ahead || front_stop || creep_end) {
        ffr_stop(st);
        /* stopped by the flame's strength alone (nothing else stops it
         * here): if the fans do not put it out, it was farther than its
         * strength said -- flames differ in size -- and the robot goes
         * closer. Stopped by the wall guard alone (or a creep by its
         * length): if the fans do not put it out, it creeps on. */
        if (reach_stop && !st->lines.edge) {
            r->flame_found = FOUND_BY_STRENGTH;
        } else if (!st->lines.edge && !front_stop && (creep ? t->moved >= CREEP_MM && !guard_stop : guard_stop)) {
            r->flame_found = FOUND_BY_GUARD;
        } else {
            r->flame_found = FOUND;
        }
        if (!step
            && ((!creep && ffr_nose_in_doorway(st, &df)) || (!st->lines.edge && sig < FLAME_NEAR * cfg->flame_detect))) {
            /* at the doorway it came in by, or stopped by a wall with the
             * flame still far: the flame is not in this room but seen
             * through its door. Back out and search on. */
            r->flame_found = 0;
            return RP_BACK_DRIVE;
        }
        st->fan = 1; /* on from this tick: no break in the air */
        return RP_EXTINGUISH;
    }
    if (r->fans_early && sig < FLAME_LOST_SHARE * cfg->flame_detect) {
        /* out under the fans, run since the flame was within their reach:
         * stop; the fans' phase confirms it out and watches it */
        ffr_stop(st);
        st->fan = 1;
        r->flame_found = FOUND;
        return RP_EXTINGUISH;
    }
    if (sig >= FLAME_REACH * cfg->flame_detect || step) {
        /* within the fans' reach by its strength (or a step closer to a flame
         * that strong): on now, and on without a break into the fans' phase
         * (the air counts from here) */
        r->fans_early = 1u;
    }
    st->fan = r->fans_early;
    if (sig < FLAME_LOST_SHARE * cfg->flame_detect) {
        /* lost it (or it went out by itself): look again from here; a flame
         * seen near is watched (FFR_FLAME_LOST_MS) */
        if (r->flame_near && r->lost_since_ms == 0u) {
            r->lost_since_ms = stamp(st);
        }
        return RP_SCAN;
    }
    if (creep || step) {
        st->cmd_v_mm_s = ffr_proximity_speed(cfg, st->ir_mm, CREEP_SPEED_MM_S);
    } else {
        /* slowing for what is ahead to stop at the approach's own front stop
         * (approach_stop_mm), where it is now (the reading's age off): the
         * route's ramp (front_slow_mm to front_stop_mm, 35 % at its end) took
         * the candle's own base, seen by the front ranger from the scan point
         * on, for a wall and crawled the whole approach */
        float ahead_mm = ffr_front_now(cfg, &st->odo, st->ir_mm) - cfg->approach_stop_mm;
        st->cmd_v_mm_s = ffr_stopping_speed(ahead_mm, cfg->approach_speed_mm_s);
    }
    if (detour != 0.0f) {
        /* around an obstacle: the flame's heading offset by the detour, and
         * slower while the corridor is not yet clear */
        float v = ffr_stopping_speed(free_mm, st->cmd_v_mm_s);
        st->cmd_v_mm_s = v < st->cmd_v_mm_s ? v : st->cmd_v_mm_s;
        st->cmd_w_rad_s = ffr_clampf(cfg->heading_kp * (bal * cfg->flame_steer_deg * FFR_DEG + detour) + guard_w,
                                     -cfg->turn_rate_deg_s * FFR_DEG, cfg->turn_rate_deg_s * FFR_DEG);
        return RP_STAY;
    }
    st->cmd_w_rad_s = ffr_clampf(cfg->heading_kp * bal * cfg->flame_steer_deg * FFR_DEG + guard_w,
                                 -cfg->turn_rate_deg_s * FFR_DEG, cfg->turn_rate_deg_s * FFR_DEG);
    return RP_STAY;
}

/* One more try of the fans: the phase to go on with (RP_STAY: failed). */
static uint8_t fans_again(ffr_state_t *st, uint8_t then)
{
    ffr_room_state_t *r = &st->room;
    r->attempts = (uint8_t)(r->attempts + 1u);
    if (r->attempts >= st->cfg.fan_attempts) {
        ffr_fail(st, FFR_FAIL_NOT_OUT);
        return RP_STAY;
    }
    return then;
}

static uint8_t on_extinguish(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    uint8_t next = RP_STAY;
    ffr_stop(st);
    st->fan = 1;
    if (r->flame_f < cfg->flame_out) {
        if (r->below_since_ms == 0u) {
            r->below_since_ms = stamp(st);
        }
        if (st->t_ms - r->below_since_ms >= cfg->flame_out_confirm_ms) {
            st->fan = 0;
            next = RP_VERIFY;
        }
    } else {
        r->below_since_ms = 0u;
    }
    if (st->fan && r->flame_found == FOUND_BY_STRENGTH && r->closer_steps < CLOSER_STEPS
        && r->flame_f >= STEP_LIT_SHARE * FLAME_REACH * cfg->flame_detect
        && (float)t->elapsed >= STEP_DWELL_SHARE * (float)cfg->fan_timeout_ms) {
        /* stopped by the flame's strength and still lit after the dwell: not
         * within the fans' reach (a big flame reads near from farther). One
         * step closer, then the fans again; the steps are no fan attempts.
         * The fans stay on: a step that enters the reach counts from there.
         * Still lit: at least half the strength that stopped it (flicker
         * takes +-15 %); a flame put out reads its wick's glow, which falls
         * to an eighth within the second the dwell leaves after the 4 s */
        r->closer_steps = (uint8_t)(r->closer_steps + 1u);
        r->flame_found = FOUND_STEP;
        return RP_APPROACH;
    }
    if (st->fan && t->elapsed >= cfg->fan_timeout_ms) {
        next = fans_again(st, RP_EXTINGUISH);
        if (next == RP_EXTINGUISH && r->flame_found == FOUND_BY_STRENGTH) {
            /* not out from where its strength said it was in reach: on
             * toward it until the line, a wall or the candle stops the
             * robot, then the fans again */
            r->flame_found = FOUND_CLOSER;
            st->fan = 0;
            next = RP_APPROACH;
        } else if (next == RP_EXTINGUISH && r->flame_found == FOUND_BY_GUARD) {
            /* not out from where the wall guard stopped the approach: the
             * flame hugs that wall, a few cm beyond the fans' reach or at the
             * edge of their cone. Creep on, steering by the flame's balance,
             * the rangers' stop kept, then the fans again */
            r->flame_found = FOUND_CREEP;
            st->fan = 0;
            next = RP_APPROACH;
        }
    }
    return next;
}

static uint8_t on_verify(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    ffr_stop(st);
    st->fan = 0;
    if (r->flame_f >= cfg->flame_out) {
        r->below_since_ms = 0u;
        return fans_again(st, RP_EXTINGUISH);
    }
    if (t->elapsed >= cfg->verify_ms) {
        st->flags |= FFR_FLAG_EXTINGUISHED;
        return RP_BACK_TURN;
    }
    return RP_STAY;
}

static uint8_t on_back_turn(ffr_state_t *st, room_tick_t *t)
{
    /* no turning in place by the candle: it may stand by a wall. The scan
     * point is behind (the approach drove away from it), so reverse. */
    (void)st;
    (void)t;
    return RP_BACK_DRIVE;
}

static uint8_t on_back_drive(ffr_state_t *st, room_tick_t *t)
{
    ffr_room_state_t *r = &st->room;
    /* back the way the approach came: through the points where it turned
     * (last first), then to the scan point */
    uint8_t via = r->obst.n_via;
    float tx = via ? (float)r->obst.via_x_mm[via - 1u] : r->scan_x_mm;
    float ty = via ? (float)r->obst.via_y_mm[via - 1u] : r->scan_y_mm;
    float dx = tx - st->odo.x_mm;
    float dy = ty - st->odo.y_mm;
    float dist = ffr_sqrtf(dx * dx + dy * dy);
    float behind = -(dx * ffr_cosf(st->odo.heading_rad) + dy * ffr_sinf(st->odo.heading_rad));
    (void)t;
    if (via && r->obst.retrace == 0u) {
        /* the approach bent on its way here: back the way it came only if
         * the straight way to the scan point has something the rangers saw
         * in it (else straight, as ever) */
        float sx = r->scan_x_mm - st->odo.x_mm, sy = r->scan_y_mm - st->odo.y_mm;
        float sd = ffr_sqrtf(sx * sx + sy * sy);
        float dir = ffr_atan2f(sy, sx);
        float clear = ffr_obst_free_mm(&r->obst, &st->cfg, st->odo.x_mm, st->odo.y_mm, dir, dir + 0.5f * FFR_PI, sd,
                                       NULL);
        r->obst.retrace = clear < sd ? 1u : 2u;
    }
    if (r->obst.retrace == 2u) {
        via = 0u;
        r->obst.n_via = 0u;
        tx = r->scan_x_mm;
        ty = r->scan_y_mm;
        dx = tx - st->odo.x_mm;
        dy = ty - st->odo.y_mm;
        dist = ffr_sqrtf(dx * dx + dy * dy);
        behind = -(dx * ffr_cosf(st->odo.heading_rad) + dy * ffr_sinf(st->odo.heading_rad));
    }
    if (r->obst.retrace == 1u) {
        /* the point to back to may be off to a side: reached only when near,
         * and the tail turned toward it first */
        float tail = closest(st->odo.heading_rad, ffr_atan2f(-dy, -dx));
        if (dist < BACK_AT_SCAN_MM || (behind <= 0.0f && dist < BACK_VIA_PASSED_MM)) {
            if (via) {
                r->obst.n_via = (uint8_t)(via - 1u);
                return RP_STAY;
            }
            ffr_stop(st);
            return RP_LEAVE_TURN;
        }
        if (ffr_absf(tail - st->odo.heading_rad) > BACK_TURN_FIRST_DEG * FFR_DEG) {
            (void)turn_to(st, tail);
            return RP_STAY;
        }
    } else if (dist < BACK_AT_SCAN_MM || behind <= 0.0f) {
        ffr_stop(st);
        return RP_LEAVE_TURN;
    }
    /* point the tail at the scan point while backing up */
    ffr_drive_heading(st, closest(st->odo.heading_rad, ffr_atan2f(-dy, -dx)),
                      -ffr_stopping_speed(dist, st->cfg.room_speed_mm_s));
    return RP_STAY;
}

static uint8_t on_leave_turn(ffr_state_t *st, room_tick_t *t)
{
    ffr_room_state_t *r = &st->room;
    float target = closest(st->odo.heading_rad, r->entry_heading_rad + FFR_PI);
    if (turn_to(st, target)) {
        /* the corridor heading reversed: route.c takes it as its reference,
         * so later turns stay square to the walls */
        r->exit_heading_rad = target;
        t->result = FFR_ROOM_FACING_OUT;
        if (ffr_leave_past_line_mm(st) >= -LEAVE_ON_LINE_MM) {
            /* facing out from a scan point near the door, the line sensor
             * is already on or beyond the doorway line: it crossed it
             * turning, or no edge comes from the line under it */
            st->flags &= (uint8_t)~FFR_FLAG_IN_ROOM;
            return RP_LEAVE_OUT;
        }
        return RP_LEAVE_LINE;
    }
    return RP_STAY;
}

static uint8_t on_leave_line(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    uint8_t next = RP_STAY;
    if (st->lines.edge) {
        st->flags &= (uint8_t)~FFR_FLAG_IN_ROOM;
        next = RP_LEAVE_OUT;
    } else if (t->moved > cfg->room_line_max_mm + cfg->room_entry_mm + (float)st->room.deeper_mm) {
        ffr_fail(st, FFR_FAIL_NO_LINE);
        return RP_STAY;
    }
    ffr_drive_heading(st, st->room.exit_heading_rad, cfg->room_speed_mm_s);
    st->cmd_w_rad_s += ffr_leave_guard(st);
    ffr_exit_wall_watch(st);
    return next;
}

static uint8_t on_leave_out(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    if (t->moved >= cfg->room_exit_mm || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
        ffr_stop(st);
        t->result = FFR_ROOM_LEFT;
        return RP_STAY;
    }
    ffr_drive_heading(st, st->room.exit_heading_rad, ffr_stopping_speed(cfg->room_exit_mm - t->moved, cfg->room_speed_mm_s));
    st->cmd_w_rad_s += ffr_leave_guard(st);
    ffr_exit_wall_watch(st);
    return RP_STAY;
}

/* How far the nearest thing the rangers saw must be from a scan point for
 * the scan's turn in place there: the body's corner radius and
 * DEEPER_CLEAR_MARGIN_MM (the second and the third scan points) */
static float scan_turn_room(const ffr_config_t *cfg)
{
    return ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm)
           + DEEPER_CLEAR_MARGIN_MM;
}

/* The scan from the door found no flame, but one was seen driving in (a
 * piece of furniture hides it from the scan point): drive on along the entry
 * heading, up to DEEPER_MM, and scan again there. It stops sooner at a line
 * (a candle circle), a wall ahead, or where going on would bring something
 * the rangers saw inside the circle the scan's turn in place sweeps. The
 * way out is then straight back along the same line. */
static uint8_t on_deeper(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    float need = scan_turn_room(cfg);
    float heading = closest(st->odo.heading_rad, r->entry_heading_rad);
    float ax = st->odo.x_mm + 2.0f * AVOID_STEP_AHEAD_MM * ffr_cosf(heading);
    float ay = st->odo.y_mm + 2.0f * AVOID_STEP_AHEAD_MM * ffr_sinf(heading);
    float near_ahead, near_here;
    ffr_obst_record(&r->obst, cfg, &st->odo, &st->ir_geom, st->ir_mm);
    near_here = ffr_obst_nearest_mm(&r->obst, st->odo.x_mm, st->odo.y_mm, need);
    near_ahead = ffr_obst_nearest_mm(&r->obst, ax, ay, need);
    if (t->moved >= DEEPER_MM || st->lines.edge || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm
        || (near_ahead < need && near_ahead < near_here - DEEPER_CLOSING_MM)) {
        ffr_stop(st);
        r->scan_x_mm = st->odo.x_mm;
        r->scan_y_mm = st->odo.y_mm;
        r->deeper_mm = (int16_t)t->moved;
        return RP_SCAN;
    }
    ffr_drive_heading(st, heading, ffr_stopping_speed(DEEPER_MM - t->moved, cfg->room_speed_mm_s));
    return RP_STAY;
}

/* The third scan point of a room searched harder (the route's last, where
 * the candle must be; the explorer's second round), whose candle both scan
 * points on the entry's line missed: off that line, toward the most open of
 * the headings ASIDE_DEG and 2 x ASIDE_DEG either side of the entry heading
 * as the grid has it, looked along a half corridor a tick (a corridor's walk
 * is the tick's costliest work: "What a tick costs", docs/firmware.md); none
 * with ASIDE_MIN_MM clear: no third point, out from here. The heading is
 * kept in best_heading_rad, as TURN_BEST's, and how far to go in
 * best_front_mm (the scan there sets both afresh). */
static uint8_t on_aside_turn(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    (void)t;
    if (r->obst.aside_next < 2u * ASIDE_HEADINGS) {
        /* heading k's corridor in two halves, the near one first (a tick
         * each: a half is about as long as the approach's corridor) */
        uint8_t k = (uint8_t)(r->obst.aside_next / 2u), far = (uint8_t)(r->obst.aside_next & 1u);
        float off = (float)((k & 1u) ? -1 : 1) * (float)(k / 2u + 1u) * ASIDE_DEG * FFR_DEG;
        float dir = r->entry_heading_rad + off;
        float half = 0.5f * (ASIDE_MM + ASIDE_ON_MM), from = far ? half : 0.0f;
        float free_mm = from + ffr_obst_free_mm(&r->obst, cfg, st->odo.x_mm + from * ffr_cosf(dir),
                                                st->odo.y_mm + from * ffr_sinf(dir), dir, dir + 0.5f * FFR_PI,
                                                half, NULL);
        ffr_stop(st);
        if (!far && free_mm >= half) {
            r->obst.aside_next++; /* the near half clear: the far one next tick */
            return RP_STAY;
        }
        if (free_mm > ASIDE_MIN_MM && free_mm - ASIDE_SHORT_MM > r->best_front_mm) {
            r->best_heading_rad = closest(st->odo.heading_rad, dir);
            r->best_front_mm = free_mm - ASIDE_SHORT_MM;
        }
        r->obst.aside_next = (uint8_t)(2u * k + 2u);
        return RP_STAY;
    }
    if (r->best_front_mm <= 0.0f) {
        return RP_LEAVE_TURN;
    }
    return turn_to(st, r->best_heading_rad) ? RP_ASIDE : RP_STAY;
}

/* Drive to the third point, along the corridor the grid has clear (its
 * length kept in best_front_mm, the scan's, which the scan there sets
 * afresh); the point is kept as the first of the trail, so the way back
 * (to the second point, on the entry's line, then out as ever) runs through
 * it. Where the scan's turn in place there would sweep something the
 * rangers saw: no scan, back. */
static uint8_t on_aside(ffr_state_t *st, room_tick_t *t)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_room_state_t *r = &st->room;
    float need = scan_turn_room(cfg);
    float most = r->best_front_mm;
    float len = most < ASIDE_MM ? most : ASIDE_MM;
    int clear;
    ffr_obst_record(&r->obst, cfg, &st->odo, &st->ir_geom, st->ir_mm);
    clear = ffr_obst_nearest_mm(&r->obst, st->odo.x_mm, st->odo.y_mm, need) >= need;
    if ((t->moved >= len && clear) || t->moved >= most || st->lines.edge
        || ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
        ffr_stop(st);
        ffr_obst_trail_from(&r->obst, &st->odo);
        return clear ? RP_SCAN : RP_BACK_TURN;
    }
    ffr_drive_heading(st, r->best_heading_rad,
                      clear ? ffr_stopping_speed(len - t->moved, cfg->room_speed_mm_s) : cfg->room_speed_mm_s);
    return RP_STAY;
}

/* ---- the dispatcher ----------------------------------------------------- */

ffr_room_result_t ffr_room_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    static const room_handler_t handlers[RP_COUNT] = {
        on_enter_line, on_enter_in,  on_scan,       on_turn_best,  on_approach,   on_extinguish,
        on_verify,     on_back_turn, on_back_drive, on_leave_turn, on_leave_line, on_leave_out,
        on_deeper,     on_aside_turn, on_aside};
    ffr_room_state_t *r = &st->room;
    room_tick_t t;
    uint8_t next;
    t.in = in;
    t.sig = flame_sum(st, in);
    t.moved = st->odo.dist_mm - r->phase_start_mm;
    t.elapsed = st->t_ms - r->phase_start_ms;
    t.result = FFR_ROOM_BUSY;
    /* whether the flame is out is decided on a filtered signal: near the dark
     * level, sensor noise alone crosses flame_out now and then */
    r->flame_f += FLAME_FILTER * (t.sig - r->flame_f);
    if (r->phase >= RP_COUNT) {
        ffr_fail(st, FFR_FAIL_BAD_ROUTE);
        return FFR_ROOM_BUSY;
    }
    next = handlers[r->phase](st, &t);
    if (next != RP_STAY) {
        enter(st, next);
    }
    return t.result;
}
