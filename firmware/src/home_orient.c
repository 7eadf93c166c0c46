/*
 * Which way does the robot face at home? Before the route starts, it turns
 * in place a little over a quarter turn (ORIENT_SWEEP_DEG, left). Its five
 * rangers look ahead, 45 degrees and 135 degrees either side, so a quarter
 * turn sweeps every direction at least once. Every valid hit is placed in
 * odometry's frame and:
 *
 * - short stretches of one ranger's successive hits (40..120 mm apart) lie
 *   along a wall: their direction, taken modulo 90 degrees (contest walls
 *   meet at right angles), averaged over the sweep, is the walls' direction
 *   in odometry's frame;
 * - the nearest hit per 10-degree direction bin, seen from where the sweep
 *   began, tells how far is free in each of the four directions square to
 *   the walls.
 *
 * If a wall straight across one of the square axes (a hit near the axis,
 * or hits as far along it on both sides of it), within a hallway's width of
 * the body's side (2 x wall_target_mm + body_half_width_mm from its centre,
 * as far as a ranger may read long), is not at wall_target_mm (the nearer
 * of two), it
 * first moves square to the walls to stand there (SHIFT_TOL_MM of slack), as
 * the wall following will want: the home circle is wider than the room a
 * hallway leaves beside the body. The route's first direction is then the
 * one with open floor ahead for the body (no wall within a hallway's width
 * in a band of its width) and a wall close on the configured side
 * (home_wall_side; "any": walls close on the most sides, i.e. along a
 * hallway); ties go to the smaller turn. The robot turns to it, and
 * odometry's frame is turned so that this direction is heading 0, square to
 * the walls (wall_direction.c relies on that), as if placed facing it.
 * Nothing of one map's distances: only "open ahead", "a wall close beside".
 *
 * Before all that, room to turn (phases CLEAR, ESCAPE): the home circle is
 * wider than the room a hallway leaves, so the robot may stand closer to a
 * wall than its turning radius (its farthest front corner). The nearest
 * wall is judged from the five rangers now (each hit, and the line through
 * two rangers' hits on one wall); within the radius + CLEAR_MARGIN_MM it
 * moves away first: straight, for a wall ahead or behind; an S and back
 * along it, for a wall beside. During the sweep, a wall's line seen within
 * the radius (it may reach on into a blind sector between the rangers)
 * stops the sweep for the same move, and the sweep starts again. A
 * reading within a ranger's fold-back span may be a wall nearly touching:
 * short straight "fold moves" away from such readings come first, and a
 * fold move forward turns back if a front ranger's reading grows as it
 * nears its wall (folded back: lead_grew).
 *
 * Built with FFR_HOME_FOLD_MM > 0 (default 0: off), a reading up to that
 * many mm may be a ranger folded back (a wall 3-5.5 cm off reads 10-18.5
 * cm): if only such readings put a wall within the radius, a 15 mm probe
 * (phase PROBE) tells folded from far before any turn (docs/firmware.md,
 * "A ranger folded back at the start").
 */
#include "ffr_internal.h"

#define ORIENT_SWEEP_DEG 95.0f
#define SEG_MIN_MM 40.0f  /* a stretch of one ranger's hits: at least this long (noise)  */
#define SEG_MAX_MM 120.0f /* at most this: longer is a jump to another wall              */
#define SEG_RANGE_MM 350.0f /* hits farther than this are too noisy for a direction      */
#define SEG_MIN_TOTAL_MM 150.0f /* less wall than this seen: keep the heading as placed  */
#define BIN_NONE 0xFFFFu
/* chosen: the aim's band narrows by this (tan 5 degrees) per mm ahead: a
 * sweep's hits are placed with its heading error (a few % of turn odometry
 * over the 95 degree sweep, rangers read late while turning), so a side
 * wall's end 50 cm ahead lands up to ~10 cm off its line, into the band (a
 * realistic robot, turn odometry +4 %, read the east hallway blocked 48 cm
 * ahead by the end of room 1's east wall and started west). A wall straight
 * across still has hits on the axis. */
#define AIM_BAND_SLOPE 0.0875f
#define BAND_MARGIN_MM 30.0f /* the body's path: its half width plus this each side      */
#define SHIFT_TOL_MM 40.0f   /* a shift shorter than this is not made                    */
#define QUICK_TOL_DEG 2.0f
/* the shift's turn: and turning slower than this (chosen: 80 % of the
 * sweep's 200 degrees/s, a body not yet braked from the sweep's spin; 60
 * and 120 lost realistic robot 37 whole, whose shift's turn braked for 80
 * ms and was done at 163: docs/robustness.md) */
#define QUICK_SPIN_DEG_S 160.0f
/* where to stand goes by walls straight across each axis (a band this wide
 * each side), not by a wall's end off to the side at a junction */
#define CENTRE_BAND_MM 40.0f
/* ... or a wall across it farther out, whose nearest hits either side of
 * the axis fall outside that band: the sweep's hits are bins 10 degrees
 * wide, 80 mm apart on a wall 46 cm off (chosen: within 15 degrees of the
 * axis, both sides as far along it within ACROSS_TOL_MM + ACROSS_TOL_FRAC
 * of the nearer: the two sides' hits may come from two rangers, one part
 * reading short and one long, 471 and 572 mm on one wall in fresh
 * +-2.5 cm start seed 372) */
#define ACROSS_CONE 0.26794919f /* tan 15 degrees */
#define ACROSS_TOL_MM 30.0f
#ifndef ACROSS_TOL_FRAC
#define ACROSS_TOL_FRAC 0.25f
#endif
#ifndef RANGE_LONG_FRAC
#define RANGE_LONG_FRAC 0.15f
#endif
/* the aim's bands: a hit counts in one only if it is there also as far out
 * along its ray as an uncalibrated GP2D12 may read short (its datasheet
 * spread: 0.25..0.55 V at 80 cm, swing +-12.5 %: 20-30 % short at 15-40 cm) */
#ifndef RANGE_SHORT_FRAC
#define RANGE_SHORT_FRAC 0.25f
#endif

/* room to turn in place: the body's farthest corner plus this (chosen: the
 * rangers' noise at 10-20 cm is a few mm; 20 mm leaves room for it) */
#define CLEAR_MARGIN_MM 20.0f
#define CLEAR_LINE_MAX_MM 400.0f  /* two hits farther apart: not one wall          */
#define CLEAR_LINE_MIN_MM 20.0f   /* two hits closer: no direction between them     */
#define CLEAR_RANGE_MM 350.0f     /* a hit farther than this is no threat          */
#define ESCAPE_RADIUS_MM 150.0f   /* a sideways escape: an arc of this radius      */
#define ESCAPE_WIDE_MM 300.0f     /* and from a wall beside that near, if it fits (chosen) */
#define ESCAPE_MAX_MM 200.0f      /* one escape move at most this long             */
/* a straight move back stops with the rear pair's chord this near behind
 * them, if it came nearer by REAR_NEARING_MM since the move began (walls
 * beside do not come nearer). Chosen: their 135-degree beams reach the
 * span's bottom (100 mm) on a wall 71 mm behind them, where they stop
 * measuring it (fresh seed 476: the chord stayed at 81-83 mm from there
 * on); 100 mm stops while both still measure it. 120 mm cut short moves
 * that needed their length (fresh +-2.5 cm seeds 688, 746 lost whole) */
#define REAR_CHORD_MM 100.0f
#define REAR_NEARING_MM 15.0f
/* corner_chord's front reading above the span's bottom (chosen, as
 * BESIDE_REAR_MM: a part reading long; at 0, start circle seeds 574 and
 * 936, 22 and 36 mm off a wall along the side, front 106 and 109 mm, rear
 * at the bottom, were taken for corners and their sweeps met the wall) */
#define CHORD_FRONT_MM 30.0f
#define ESCAPE_FREE_MM 60.0f      /* the end it drives toward keeps this clear     */
#define LINE_MARGIN_MM 10.0f      /* the sweep stops for a wall line this near     */
#define LINE_REACH_MM 200.0f      /* a wall seen may reach this far on unseen     */
#define ARC_BAND_MM 30.0f         /* an arc's path: the half width plus this       */
#define ESCAPE_START_MM 0.0f      /* the front shut: less room than this beyond ESCAPE_FREE_MM (chosen) */
#define ESCAPE_TRIES FFR_ORIENT_ESCAPE_TRIES /* moves before the sweep goes ahead regardless */
#define BESIDE_REAR_MM 30.0f      /* a rear ranger this far above its span's bottom: the wall beside */
/* the wide S: the front ranger this far above its span's bottom too (a wall
 * 8 mm off the side folds back to read ~4 mm above it; chosen: 20, 30 and 40
 * all won start seeds 7636 and 1001 on the rows of docs/robustness.md, "The
 * wide S from a front ranger just above its bottom"; 40 won the most) */
#define WIDE_FRONT_MM 40.0f
#define LEG_PROBE_RETURN 4u       /* the probe's way back to where it stood (nothing folded back) */
#define LEG_ALONG_RETURN 10u      /* the same for unfold_front's probe, retracing its way */
#define LEG_ALONG 11u             /* unfold_front's moves back (its probe, the move after): the wall beside along them */
#define LEG_BACK 5u               /* the escape's leg: straight back, the front shut */
#define LEG_FOLD 6u               /* the escape's leg: a fold move, straight (rear: forward; front: back) */
#define LEG_TURNED 7u             /* the escape's leg: a fold move forward turned back (lead_grew) */
#define LEG_BACK_S 8u             /* the escape's leg: straight back for the S's floor (back_for_s) */
#define BACK_S_WALL_MM 500.0f     /* the other side's rear ranger reads a wall within this: a way's far wall (chosen) */
#define LEG_SOFT 9u               /* the escape's leg: the wide S's first arc, begun gently (soft_len) */
/* That gentle start's radius. An arc of radius R away from a wall beside
 * swings the rear corner toward it by up to sqrt(b^2 + (R + w/2)^2) -
 * (R + w/2) before the body's angle carries it off (b, w/2: the corner
 * behind and beside the axle; the default body 100 and 100 mm): 12 mm on
 * ESCAPE_WIDE_MM's arc, 7 mm on this one. Chosen: 500 kept fewer starts,
 * 600-800 about as many (docs/robustness.md, "The body along a wall") */
#define ESCAPE_SOFT_MM 600.0f
/* The rear fold move's length: the default body's rear corner swings out
 * sqrt(100^2 + 100^2) - 100 = 41 mm turning in place; this, with a few mm
 * to spare (chosen: 60 put seed 51 of the held-out +-2.5 cm jitter row in
 * the middle hallway's mouth, and the aim took it; docs/robustness.md) */
#define REAR_FOLD_MOVE_MM 45.0f
/* The front fold move's length: a wall the centre ranger reads folded back
 * is 40-80 mm off it, 140-180 mm ahead of the axle; 30 mm more puts it
 * beyond the front corners' 156 mm turning circle (chosen: 20, 45 and 60 mm
 * measured, docs/robustness.md "The front fold move") */
#define FRONT_FOLD_MOVE_MM 30.0f
/* a rear reading this much shorter after the move was folded back (chosen:
 * above the rangers' noise at 10-16 cm, a few mm) */
#define FOLD_SHRINK_MM 4.0f
#define ESCAPE_SPEED_MM_S 120.0f  /* chosen: slow, so a wall unseen costs no bump  */
#define PROBE_GROW_MM 8.0f        /* a reading grown this much on a move away: no fold-back */
#define PROBE_MM 15.0f            /* the probe for fold-back: this far, straight (chosen) */
#define PROBE_SPEED_MM_S 40.0f    /* and this slowly (chosen: a reading or two per mm)   */
#define PROBE_TELL_MM 8.0f        /* a reading changed this much on the probe tells its way */
/* a front ranger's reading grown this much on a fold move forward: folded
 * back (lead_grew; chosen: 4, 6, 8 and 12 mm measured, docs/robustness.md
 * "A fold move watches its leading end") */
#define LEAD_GROW_MM 8.0f
/* a straight escape forward stops this far (along the move) from a wall
 * across it at a slant, in front of a front corner (chosen: a realistic
 * robot's corner ranger, near its span's bottom, read the wall some 30 mm
 * far: with 40 mm the corner met it, with 100 that mission went home with
 * no contact) */
#define CORNER_FREE_MM 100.0f
/* after a shift backward stopped by a rear ranger at its span's bottom
 * (rear_at_bottom_behind): straight forward this far before the aim (chosen:
 * with 70 mm, start seeds 7141 and 8260 ended where the aim chose the west
 * hallway) */
#define SHIFT_BOTTOM_MOVE_MM 30.0f
#define SIDE_MARGIN_MM 20.0f      /* a wall beside within the turning radius + this: the sweep turns away from it (chosen) */
/* a line across a corner with too little floor ahead for the S: first this
 * far straight forward, if the floor ahead has room. As REAR_FOLD_MOVE_MM:
 * past the rear corner's 41 mm swing (30, 45 and 70 mm measured: 30 and 45
 * alike, docs/robustness.md "A fold move watches its leading end") */
#define CHORD_STEP_MM 45.0f
/* The arbitrary start (a hallway, any heading): a straight step forward
 * before the first sweep, when a rear ranger reads nothing within
 * HALL_OPEN_MM (first_step). Chosen: 100 mm and 750 mm (60, 100 and 150
 * mm, 600 and 750 mm and no condition measured: docs/robustness.md, "A step
 * before the sweep from a hallway start") */
#define HALL_STEP_MM 100.0f
#define HALL_OPEN_MM 750.0f

/* a shift to stand at wall_target_mm at most this far across the route's
 * first direction (and at most SHIFT_TOL_MM along it) is not made; 0 (the
 * default): every shift over SHIFT_TOL_MM is. Off: with 100 the nominal
 * start is faster but the realistic sweep loses missions (docs/firmware.md,
 * "Cheaper orientation"). Build with -DFFR_HOME_SKIP_MM=100.0f to try it. */
#ifndef FFR_HOME_SKIP_MM
#define FFR_HOME_SKIP_MM 0.0f
#endif

enum { PH_SWEEP = 0, PH_CENTRE = 1, PH_SHIFT_TURN = 2, PH_SHIFT_DRIVE = 3, PH_AIM = 4, PH_TURN = 5, PH_DONE = 6,
       PH_CLEAR = 7, PH_ESCAPE = 8, PH_PROBE = 9 };

static const float k_bin_rad = 2.0f * FFR_PI / (float)FFR_ORIENT_BINS;

void ffr_orient_reset(ffr_home_orient_t *o, const ffr_odometry_t *odo)
{
    int i;
    o->phase = PH_SWEEP;
    o->reverse = 0u;
    o->escapes = 0u;
    o->leg = 0u;
    o->trusted = 0u;
    o->probed = 0u;
    o->probe_done = 0u;
    o->folded = 0u;
    o->sweep_side = 0;
    o->after_shift = 0u;
    o->slant_watch = 0u;
    o->back_chord_mm = 0.0f; /* no leg begun: nothing to watch */
    o->leg_mm = 0.0f;
    o->near_mm = 65535.0f;
    o->near_x_mm = 0.0f;
    o->near_y_mm = 0.0f;
    o->x0_mm = odo->x_mm;
    o->y0_mm = odo->y_mm;
    o->h0_rad = odo->heading_rad;
    o->dir0_rad = 0.0f;
    o->target_rad = odo->heading_rad;
    o->goal_mm = 0.0f;
    o->anchors = 0u;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        o->anchor_x_mm[i] = 0.0f;
        o->anchor_y_mm[i] = 0.0f;
        o->probe_mm[i] = 0.0f;
    }
    o->c4 = 0.0f;
    o->s4 = 0.0f;
    o->w = 0.0f;
    for (i = 0; i < FFR_ORIENT_BINS; ++i) {
        o->bin_mm[i] = (uint16_t)BIN_NONE;
        o->bin_x_mm[i] = 0.0f;
        o->bin_y_mm[i] = 0.0f;
    }
}

/* bin of a direction (rad, any value) */
static int bin_of(float dir)
{
    float a = dir;
    int b;
    while (a < 0.0f) {
        a += 2.0f * FFR_PI;
    }
    while (a >= 2.0f * FFR_PI) {
        a -= 2.0f * FFR_PI;
    }
    b = (int)(a / k_bin_rad);
    return b >= FFR_ORIENT_BINS ? FFR_ORIENT_BINS - 1 : b;
}

void ffr_orient_record(ffr_home_orient_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo,
                       const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT])
{
    float c = ffr_cosf(odo->heading_rad);
    float s = ffr_sinf(odo->heading_rad);
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float px, py, dx, dy, r, len;
        int b;
        if (!ffr_ir_valid(cfg, ir_mm[i])) {
            o->anchors = (uint8_t)(o->anchors & ~(1 << i));
            o->probe_mm[i] = 0.0f;
            continue;
        }
        /* the hit in odometry's frame, relative to the sweep's centre */
        px = odo->x_mm + c * g->hit_x_mm[i] - s * g->hit_y_mm[i] - o->x0_mm;
        py = odo->y_mm + s * g->hit_x_mm[i] + c * g->hit_y_mm[i] - o->y0_mm;
        b = bin_of(ffr_atan2f(py, px));
        r = px * px + py * py; /* squared: the root only for a new nearest */
        if (r < (float)o->bin_mm[b] * (float)o->bin_mm[b]) {
            r = ffr_sqrtf(r);
            o->bin_mm[b] = (uint16_t)(r < 65534.0f ? r : 65534.0f);
            o->bin_x_mm[b] = px;
            o->bin_y_mm[b] = py;
        }
        if (ir_mm[i] > SEG_RANGE_MM) {
            o->anchors = (uint8_t)(o->anchors & ~(1 << i));
            o->probe_mm[i] = 0.0f;
            continue;
        }
        if (!((o->anchors >> i) & 1)) {
            o->anchors = (uint8_t)(o->anchors | (1 << i));
            o->anchor_x_mm[i] = px;
            o->anchor_y_mm[i] = py;
            continue;
        }
        dx = px - o->anchor_x_mm[i];
        dy = py - o->anchor_y_mm[i];
        len = ffr_sqrtf(dx * dx + dy * dy);
        if (len < SEG_MIN_MM) {
            continue;
        }
        if (len <= SEG_MAX_MM) {
            float u = dx / len, v = dy / len; /* the stretch's unit direction */
            ffr_add_dir4(dx, dy, len, &o->c4, &o->s4);
            o->w += len;
            {
                /* the wall's line near the robot: its nearest point, if
                 * within LINE_REACH_MM of the stretch seen (the wall may go
                 * on unseen into a blind sector between the rangers) */
                float qx = odo->x_mm - o->x0_mm - o->anchor_x_mm[i];
                float qy = odo->y_mm - o->y0_mm - o->anchor_y_mm[i];
                float t = qx * u + qy * v; /* along the stretch from its start */
                /* how far its line passes from the axle, kept for this
                 * ranger until its next stretch (sweep_side_at_bottom) */
                o->probe_mm[i] = ffr_absf(qx * v - qy * u);
                if (t > -LINE_REACH_MM && t < len + LINE_REACH_MM) {
                    float fx = o->anchor_x_mm[i] + t * u - (odo->x_mm - o->x0_mm);
                    float fy = o->anchor_y_mm[i] + t * v - (odo->y_mm - o->y0_mm);
                    float fd = ffr_sqrtf(fx * fx + fy * fy);
                    if (fd < o->near_mm) {
                        o->near_mm = fd;
                        o->near_x_mm = fx;
                        o->near_y_mm = fy;
                    }
                }
            }
        }
        if (len > SEG_MAX_MM) {
            o->probe_mm[i] = 0.0f; /* a jump to another wall: not the last stretch's */
        }
        o->anchor_x_mm[i] = px;
        o->anchor_y_mm[i] = py;
    }
}

float ffr_orient_square(const ffr_home_orient_t *o)
{
    return 0.25f * ffr_atan2f(o->s4, o->c4);
}

float ffr_orient_free_mm(const ffr_home_orient_t *o, float band, float dir, float cx, float cy)
{
    float ux = ffr_cosf(dir), uy = ffr_sinf(dir);
    float best = 65535.0f;
    int b;
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        float qx, qy, along, lat;
        if (o->bin_mm[b] == BIN_NONE) {
            continue;
        }
        qx = o->bin_x_mm[b] - cx;
        qy = o->bin_y_mm[b] - cy;
        along = qx * ux + qy * uy;
        lat = ffr_absf(qy * ux - qx * uy);
        if (along > 0.0f && lat < band && along < best) {
            best = along;
        }
    }
    return best;
}

void ffr_orient_free4(const ffr_home_orient_t *o, float band, float dir0, float cx, float cy, float free_mm[4])
{
    /* one pass, the points turned into the walls' frame once (a tick's
     * budget: four passes with their own trigonometry cost twice it) */
    float c = ffr_cosf(dir0), s = ffr_sinf(dir0);
    int b, k;
    for (k = 0; k < 4; ++k) {
        free_mm[k] = 65535.0f;
    }
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        float qx, qy, u, v;
        if (o->bin_mm[b] == BIN_NONE) {
            continue;
        }
        qx = o->bin_x_mm[b] - cx;
        qy = o->bin_y_mm[b] - cy;
        u = qx * c + qy * s;  /* along dir0      */
        v = qy * c - qx * s;  /* along dir0 + 90 */
        if (ffr_absf(v) < band) {
            if (u > 0.0f && u < free_mm[0]) {
                free_mm[0] = u;
            } else if (u < 0.0f && -u < free_mm[2]) {
                free_mm[2] = -u;
            }
        }
        if (ffr_absf(u) < band) {
            if (v > 0.0f && v < free_mm[1]) {
                free_mm[1] = v;
            } else if (v < 0.0f && -v < free_mm[3]) {
                free_mm[3] = -v;
            }
        }
    }
}

/* The aim's view of the four ways k (dir0 + k * 90 degrees), from (cx, cy),
 * in the walls' frame (u along dir0, v along dir0 + 90). Each hit is taken
 * as read and as far out along its ray from the sweep's centre as if read
 * RANGE_SHORT_FRAC short (lu, lv: the farther of the two from each axis):
 * - wall[j] (j: +u, +v, -u, -v): a hit ahead along that axis within
 *   open_mm, in the body's path band (narrowing with distance) either way:
 *   a wall beside the ways square to it;
 * - side[q]: of the hits within a hallway's width ahead along u (`reach`)
 *   even as far out as they may be (lu), the nearest to the u axis, as far
 *   out as it may be (lv), per quadrant q (u > 0, v > 0); side[4 + q] the
 *   same along v;
 * - beside[i]: of the hits within open_mm of the u axis, the nearest to
 *   the axle along u, on the axis' +v side (i = 1) or not (0); beside[2 + i]
 *   the same along v, on its +u side (i = 1) or not.
 * One pass over the bins, each bin's sums and tests once (the tick's
 * budget: a way's view each would cost four times it). */
typedef struct {
    uint32_t side[8];   /* as fbits (below) */
    uint32_t beside[4];
    uint8_t wall[4];
} aim_view_t;

/* A float's bits, and back. Non-negative floats order as their bits do
 * (IEEE 754): the aim's scan compares distances as integers (one
 * instruction, not a compare, a flags move and a branch's worth: the tick's
 * budget) and takes |x| and x's sign from its bits. */
typedef union {
    float f;
    uint32_t u;
} fbits_t;

static inline uint32_t fbits(float x)
{
    fbits_t t;
    t.f = x;
    return t.u;
}

static inline float bitsf(uint32_t u)
{
    fbits_t t;
    t.u = u;
    return t.f;
}

#define ABS_BITS 0x7FFFFFFFu
#define AIM_PER_AXIS (FFR_ORIENT_BINS / 4) /* the bins nearest each of the four axes */
typedef char aim_bins_in_quarters[(FFR_ORIENT_BINS % 4 == 0) ? 1 : -1];
#define AIM_SHUT_LOOK 2 /* after the 3 bins (+-15 degrees) nearest each axis: all shut? (chosen) */

static inline void keep_min_bits(uint32_t *m, uint32_t x) { *m = x < *m ? x : *m; }

/* the limits a hit is tested against (bits of non-negative floats, as
 * fbits), and (cu, cv): where the robot is, in the walls' frame from the
 * sweep's centre */
typedef struct {
    uint32_t two_band, reach, near, axis, ahead;
    float band, cu, cv;
} aim_lim_t;

static void aim_start(aim_view_t *w, aim_lim_t *l, const ffr_config_t *cfg, float cu, float cv)
{
    float near = cfg->open_mm, two_band, reach;
    int i;
    l->band = cfg->body_half_width_mm + BAND_MARGIN_MM;
    two_band = 2.0f * l->band;
    l->two_band = fbits(two_band);
    reach = 2.0f * cfg->wall_target_mm + cfg->body_half_width_mm;
    l->reach = fbits(reach);
    l->ahead = fbits(near > reach ? near : reach); /* farther ahead: neither side nor wall */
    l->near = fbits(near);
    l->axis = fbits(near > two_band ? near : two_band); /* farther off an axis: none of its tests */
    l->cu = cu;
    l->cv = cv;
    for (i = 0; i < 8; ++i) {
        w->side[i] = fbits(65535.0f);
    }
    for (i = 0; i < 4; ++i) {
        w->beside[i] = fbits(65535.0f);
        w->wall[i] = 0u;
    }
}

/* one hit (u0, v0: in the walls' frame from the sweep's centre) into the
 * view. nu, nv: the hit on the -u, -v side of the robot's axes (-0: -).
 * A side's nearest hit counts only below twice the band (farther, neither
 * the body's half width nor the band's room between the sides depends on
 * it): a hit off an axis by that much and by open_mm skips that axis' tests.
 * A side's hit counts within the reach ahead only if it would be there even
 * as far along as a short reading may have put it: the sweep's bins keep
 * each bin's nearest hit, a far wall read short among them (orientation
 * bench start seed 9649: the home hallway's north wall ~740 mm off read as
 * ~530 mm, 96 mm off the way north's axis after the shift to the hallway's
 * middle; the way was judged shut and the route set off west, into the
 * middle hallway) */
static inline void aim_hit(aim_view_t *w, const aim_lim_t *l, float u0, float v0)
{
    uint32_t bu = fbits(u0 - l->cu), bv = fbits(v0 - l->cv);
    uint32_t au = bu & ABS_BITS, av = bv & ABS_BITS, lu, lv;
    uint32_t nu = bu >> 31, nv = bv >> 31;
    if (av >= l->axis && au >= l->axis) {
        return; /* far off both axes (or no hit): none of their tests */
    }
    /* as far along each axis as it may be (a reading short by
     * RANGE_SHORT_FRAC): off a way's axis, how far a side's hit is; along
     * it, whether it is within the reach even so */
    lu = fbits(u0 - l->cu + RANGE_SHORT_FRAC * u0) & ABS_BITS;
    lv = fbits(v0 - l->cv + RANGE_SHORT_FRAC * v0) & ABS_BITS;
    lu = lu > au ? lu : au;
    lv = lv > av ? lv : av;
    if (av < l->axis) {
        /* near the u axis: the ways along u */
        if (av < l->near) {
            keep_min_bits(&w->beside[1u - nv], au);
        }
        if (au < l->ahead && lv < l->two_band) {
            if (lu < l->reach) {
                keep_min_bits(&w->side[2u * (1u - nu) + 1u - nv], lv);
            }
            if (au < l->near && bitsf(lv) < l->band - AIM_BAND_SLOPE * bitsf(au)) {
                w->wall[2u * nu] = 1u;
            }
        }
    }
    if (au < l->axis) {
        /* near the v axis: the ways along v */
        if (au < l->near) {
            keep_min_bits(&w->beside[3u - nu], av);
        }
        if (av < l->ahead && lu < l->two_band) {
            if (lv < l->reach) {
                keep_min_bits(&w->side[4u + 2u * (1u - nu) + 1u - nv], lu);
            }
            if (av < l->near && bitsf(lu) < l->band - AIM_BAND_SLOPE * bitsf(av)) {
                w->wall[1u + 2u * nv] = 1u;
            }
        }
    }
}

/* the bins into the walls' frame (u along dir0, v along dir0 + 90 degrees,
 * from the sweep's centre), once (the centre's tick): the aim's scan then
 * turns none (its tick's budget). And in the aim's order: out from the four
 * axes, nearest first (slot 4 i + q: axis q's bin at offset 0, -1, +1, -2,
 * ... for i = 0, 1, 2, ...), so that the aim sees first the bins that shut
 * ways. A bin without a hit: far off both axes */
void ffr_orient_to_walls(ffr_home_orient_t *o, float dir0)
{
    const float c = ffr_cosf(dir0), s = ffr_sinf(dir0);
    const int base = bin_of(dir0);
    float u[FFR_ORIENT_BINS], v[FFR_ORIENT_BINS];
    int i, q;
    for (i = 0; i < FFR_ORIENT_BINS; ++i) {
        float x = o->bin_x_mm[i], y = o->bin_y_mm[i];
        int none = o->bin_mm[i] == BIN_NONE;
        u[i] = none ? 65535.0f : x * c + y * s;
        v[i] = none ? 65535.0f : y * c - x * s;
    }
    for (i = 0; i < AIM_PER_AXIS; ++i) {
        int b = base + ((i & 1) ? -(i + 1) / 2 : i / 2);
        for (q = 0; q < 4; ++q, b += AIM_PER_AXIS) {
            int from = b < 0 ? b + FFR_ORIENT_BINS : b >= FFR_ORIENT_BINS ? b - FFR_ORIENT_BINS : b;
            o->bin_x_mm[4 * i + q] = u[from];
            o->bin_y_mm[4 * i + q] = v[from];
        }
    }
}

/* way k's sides in the view: left, right (along u: left is +v ahead +u,
 * -v ahead -u; along v: left is -u ahead +v, +u ahead -v) */
static const uint8_t AIM_LEFT[4] = {3u, 5u, 0u, 6u};
static const uint8_t AIM_RIGHT[4] = {2u, 7u, 1u, 4u};

/* way k shut: within a hallway's width ahead, no room for the body's path
 * band between the walls either side of its axis (a wall across it, or a
 * wall's end in front of the body). A narrow hallway with the body off its
 * middle is a way: the wall following takes the body to its line */
static int aim_shut(const aim_view_t *w, const ffr_config_t *cfg, int k)
{
    float left = bitsf(w->side[AIM_LEFT[k]]), right = bitsf(w->side[AIM_RIGHT[k]]);
    return left < cfg->body_half_width_mm || right < cfg->body_half_width_mm ||
           left + right < 2.0f * (cfg->body_half_width_mm + BAND_MARGIN_MM);
}

/* the way by the rule, from the view */
static int aim_decide(const ffr_config_t *cfg, const aim_view_t *w, float dir0, float heading)
{
    static const uint8_t left_pos[4] = {1u, 0u, 0u, 1u}; /* way k's left on the + side of its cross axis */
    int k, best = -1;
    int best_score = -1;
    float best_turn = 0.0f, best_beside = 65535.0f;
    int side = cfg->home_wall_side == FFR_HOME_WALL_LEFT ? 0 : 1;
    for (k = 0; k < 4; ++k) {
        int left_wall = w->wall[(k + 1) & 3];
        int right_wall = w->wall[(k + 3) & 3];
        int score;
        float beside = 0.0f;
        float turn = ffr_absf(ffr_wrap_pi(dir0 + (float)k * 0.5f * FFR_PI - heading));
        /* with a wall side: how far ahead (or behind) of the axle its wall
         * is nearest; a hallway's wall is beside the axle, a wall's end at
         * a junction starts ahead of it */
        if (cfg->home_wall_side == FFR_HOME_WALL_LEFT || cfg->home_wall_side == FFR_HOME_WALL_RIGHT) {
            int wp = side == 0 ? left_pos[k] : 1 - left_pos[k]; /* the wall side: + of the cross axis? */
            beside = bitsf(w->beside[((k & 1) ? 2 : 0) + wp]);
        }
        if (aim_shut(w, cfg, k)) {
            continue;
        }
        if (cfg->home_wall_side == FFR_HOME_WALL_LEFT) {
            score = left_wall;
        } else if (cfg->home_wall_side == FFR_HOME_WALL_RIGHT) {
            score = right_wall;
        } else {
            score = left_wall + right_wall;
        }
        if (score > best_score ||
            (score == best_score && (beside < best_beside - SHIFT_TOL_MM ||
                                     (beside <= best_beside + SHIFT_TOL_MM && turn < best_turn)))) {
            best = k;
            best_score = score;
            best_turn = turn;
            best_beside = beside;
        }
    }
    return best;
}

int ffr_orient_choose(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                      float cy)
{
    /* a copy turned into the walls' frame: the firmware turns its own once,
     * on the centre's tick (ffr_orient_to_walls), and aims from it */
    ffr_home_orient_t w = *o;
    ffr_orient_to_walls(&w, dir0);
    return ffr_orient_aim(&w, cfg, dir0, heading, cx, cy);
}

int ffr_orient_aim(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                   float cy)
{
    const float c = ffr_cosf(dir0), s = ffr_sinf(dir0);
    aim_view_t w;
    aim_lim_t l;
    int b, k;
    aim_start(&w, &l, cfg, cx * c + cy * s, cy * c - cx * s);
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        aim_hit(&w, &l, o->bin_x_mm[b], o->bin_y_mm[b]);
        if (b == 4 * AIM_SHUT_LOOK + 3) {
            /* every way shut by then stays shut (the nearest hits only get
             * nearer): none open, the rest unseen (walls close all round
             * cost every bin every test: the tick's budget) */
            for (k = 0; k < 4 && aim_shut(&w, cfg, k); ++k) {
            }
            if (k == 4) {
                return -1;
            }
        }
    }
    return aim_decide(cfg, &w, dir0, heading);
}

void ffr_orient_across4(const ffr_home_orient_t *o, float cu, float cv, float free_mm[4])
{
    /* per axis k and side of it (+, -), the nearest hit along k within the
     * cone: slot 2 k (+) and 2 k + 1 (-) */
    float cone[8];
    int b, k;
    for (k = 0; k < 4; ++k) {
        free_mm[k] = 65535.0f;
    }
    for (k = 0; k < 8; ++k) {
        cone[k] = 65535.0f;
    }
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        /* a bin without a hit is far off both axes (ffr_orient_to_walls): in
         * no band or cone. The u axis' test and the v axis' are written out,
         * not one helper called twice: -Os does not inline it, and the calls
         * took the centre's tick from 4,400 to 5,360 instructions on the M4
         * (make selftest), over the 5,000 the PIL tests assert */
        float u = o->bin_x_mm[b] - cu, v = o->bin_y_mm[b] - cv;
        float au = ffr_absf(u), av = ffr_absf(v);
        if (av < CENTRE_BAND_MM || av < ACROSS_CONE * au) {
            int k0 = u > 0.0f ? 0 : 2, slot = 2 * k0 + (v >= 0.0f ? 0 : 1);
            if (av < CENTRE_BAND_MM && au < free_mm[k0]) {
                free_mm[k0] = au;
            }
            cone[slot] = au < cone[slot] ? au : cone[slot];
        }
        if (au < CENTRE_BAND_MM || au < ACROSS_CONE * av) {
            int k1 = v > 0.0f ? 1 : 3, slot = 2 * k1 + (u >= 0.0f ? 0 : 1);
            if (au < CENTRE_BAND_MM && av < free_mm[k1]) {
                free_mm[k1] = av;
            }
            cone[slot] = av < cone[slot] ? av : cone[slot];
        }
    }
    for (k = 0; k < 4; ++k) {
        /* no hit in the band: a wall across the axis, as far along it on
         * both sides of it? (a hit in the band is nearer the axis: the
         * better measure where the wall crosses it) */
        float p = cone[2 * k], m = cone[2 * k + 1];
        if (free_mm[k] > 65534.0f && ffr_absf(p - m) < ACROSS_TOL_MM + ACROSS_TOL_FRAC * (p < m ? p : m)) {
            free_mm[k] = p < m ? p : m;
        }
    }
}

void ffr_orient_centre_walls(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float cx, float cy,
                             float *dx, float *dy, float *toward_mm)
{
    /* a hallway's width from the body's side, as far as a ranger may read long */
    float near = (2.0f * cfg->wall_target_mm + cfg->body_half_width_mm) * (1.0f + RANGE_LONG_FRAC);
    float c0 = ffr_cosf(dir0), s0 = ffr_sinf(dir0);
    float free_mm[4], sk[2], to[2];
    int k;
    ffr_orient_across4(o, cx * c0 + cy * s0, cy * c0 - cx * s0, free_mm);
    for (k = 0; k < 2; ++k) {
        float a = free_mm[k];
        float b = free_mm[k + 2];
        float s = 0.0f; /* along dir: the nearer wall at wall_target_mm (in a contest
                         * hallway that is its middle; a far wall may be a wall's end) */
        float t = 0.0f; /* and that wall's distance, if the shift goes toward it */
        if (a < near && a <= b) {
            s = a - cfg->wall_target_mm;
            t = s > 0.0f ? a : 0.0f;
        } else if (b < near) {
            s = cfg->wall_target_mm - b;
            t = s < 0.0f ? b : 0.0f;
        }
        sk[k] = s;
        to[k] = t;
    }
    *dx = sk[0] * c0 - sk[1] * s0;
    *dy = sk[0] * s0 + sk[1] * c0;
    /* the shift runs along one axis (within ACROSS_CONE) toward its wall */
    *toward_mm = ffr_absf(sk[1]) <= ACROSS_CONE * ffr_absf(sk[0]) ? to[0]
                 : ffr_absf(sk[0]) <= ACROSS_CONE * ffr_absf(sk[1]) ? to[1]
                                                                    : 0.0f;
}

void ffr_orient_centre(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float cx, float cy,
                       float *dx, float *dy)
{
    ffr_home_orient_t w = *o;
    float toward;
    ffr_orient_to_walls(&w, dir0);
    ffr_orient_centre_walls(&w, cfg, dir0, cx, cy, dx, dy, &toward);
}

int ffr_orient_skip(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                    float cy, float dx, float dy, float skip_mm)
{
    /* the route's first direction as seen from where the shift would end
     * (from where it stands, a wall's end the shift is for may lie in the
     * body's path): a shift small across it is not worth a turn, a drive
     * and a turn back (the wall following takes it up) */
    int k = ffr_orient_aim(o, cfg, dir0, heading, cx + dx, cy + dy);
    float target, across, along;
    if (k < 0) {
        return -1;
    }
    target = dir0 + (float)k * 0.5f * FFR_PI;
    across = dy * ffr_cosf(target) - dx * ffr_sinf(target);
    along = dx * ffr_cosf(target) + dy * ffr_sinf(target);
    return ffr_absf(across) <= skip_mm && ffr_absf(along) <= SHIFT_TOL_MM ? k : -1;
}

float ffr_orient_turn_radius_mm(const ffr_config_t *cfg)
{
    return ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm);
}

uint8_t ffr_orient_fold_suspects(const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float max_mm)
{
    uint8_t m = 0u;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (ir_mm[i] > cfg->ir_min_mm + 0.5f && ir_mm[i] <= max_mm) {
            m = (uint8_t)(m | (1 << i));
        }
    }
    return m;
}

/* the rangers whose beam points within a cone about the unit vector (ux,
 * uy) in the body frame: beam . u > min_dot (bit i: ranger i) */
static uint8_t beams_toward(const ffr_ir_geom_t *g, float ux, float uy, float min_dot)
{
    uint8_t m = 0u;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (g->beam_cos[i] * ux + g->beam_sin[i] * uy > min_dot) {
            m = (uint8_t)(m | (1 << i));
        }
    }
    return m;
}

/* the rangers looking ahead, and those looking back: beams within 60 degrees
 * of straight ahead or straight back */
static uint8_t front_beams(const ffr_state_t *st) { return beams_toward(&st->ir_geom, 1.0f, 0.0f, 0.5f); }
static uint8_t rear_beams(const ffr_state_t *st) { return beams_toward(&st->ir_geom, -1.0f, 0.0f, 0.5f); }

/* pairs of rangers that see one wall: a side's two, the front's three, the rear's two */
static const uint8_t WALL_PAIRS[6][2] = {{FFR_IR_LF, FFR_IR_LR}, {FFR_IR_RF, FFR_IR_RR}, {FFR_IR_CF, FFR_IR_LF},
                                         {FFR_IR_CF, FFR_IR_RF}, {FFR_IR_LF, FFR_IR_RF}, {FFR_IR_LR, FFR_IR_RR}};

/* The foot of the perpendicular from the axle midpoint to the line through
 * two hits (body frame): near them, the wall's nearest point. 0 when the
 * hits are too close or too far apart for one wall, or the foot lies well
 * outside them. */
static int wall_foot(float ax, float ay, float bx, float by, float *fx, float *fy, float *d)
{
    float ex = bx - ax, ey = by - ay, len, t;
    len = ffr_sqrtf(ex * ex + ey * ey);
    if (len < CLEAR_LINE_MIN_MM || len > CLEAR_LINE_MAX_MM) {
        return 0;
    }
    t = -(ax * ex + ay * ey) / (len * len);
    if (t < -0.25f || t > 1.25f) {
        return 0;
    }
    *fx = ax + t * ex;
    *fy = ay + t * ey;
    *d = ffr_sqrtf(*fx * *fx + *fy * *fy);
    return 1;
}

int ffr_orient_clearance(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                         float *dist_mm, float *nx, float *ny)
{
    return ffr_orient_clearance_fold(cfg, g, ir_mm, 0u, 0u, 0u, dist_mm, nx, ny);
}

int ffr_orient_clearance_fold(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT],
                              uint8_t folded, uint8_t not_both, uint8_t not_any, float *dist_mm, float *nx,
                              float *ny)
{
    int ok[FFR_IR_COUNT];
    int i, k, found = 0;
    float best = 65535.0f;
    *nx = 0.0f;
    *ny = 0.0f;
    float hx[FFR_IR_COUNT], hy[FFR_IR_COUNT];
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float x = g->hit_x_mm[i], y = g->hit_y_mm[i], r;
        ok[i] = ffr_ir_valid(cfg, ir_mm[i]) && ir_mm[i] <= CLEAR_RANGE_MM;
        if (!ok[i]) {
            continue;
        }
        if (ir_mm[i] <= cfg->ir_min_mm + 0.5f || ((folded >> i) & 1 && ir_mm[i] <= FFR_FOLD_MAX_MM)) {
            /* at the bottom of the ranger's span (or maybe folded back from
             * below it): the wall is anywhere up to ir_min_mm off the
             * ranger; half of it */
            x = cfg->ir_x_mm[i] + 0.5f * cfg->ir_min_mm * g->beam_cos[i];
            y = cfg->ir_y_mm[i] + 0.5f * cfg->ir_min_mm * g->beam_sin[i];
        }
        hx[i] = x;
        hy[i] = y;
        r = ffr_sqrtf(x * x + y * y);
        if (r > 1.0f && r < best) {
            best = r;
            *nx = x / r;
            *ny = y / r;
            found = 1;
        }
    }
    for (k = 0; k < 6; ++k) {
        int a = WALL_PAIRS[k][0], b = WALL_PAIRS[k][1];
        float fx, fy, d;
        if (!ok[a] || !ok[b] || ((not_both >> a) & 1 && (not_both >> b) & 1) ||
            ((not_any >> a) & 1 && ir_mm[b] > cfg->ir_min_mm + 0.5f) ||
            ((not_any >> b) & 1 && ir_mm[a] > cfg->ir_min_mm + 0.5f)) {
            continue; /* points that may be folded back are no line (but with one surely near, at its span's bottom) */
        }
        if (wall_foot(hx[a], hy[a], hx[b], hy[b], &fx, &fy, &d) && d > 1.0f && d < best) {
            best = d;
            *nx = fx / d;
            *ny = fy / d;
            found = 1;
        }
    }
    *dist_mm = best;
    return found;
}

int ffr_orient_sweep_side(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT])
{
    /* a wall beside the body, nearer than the turning radius + SIDE_MARGIN_MM:
     * the sweep turns away from it (+1 left, -1 right; 0: no such wall).
     * Turning away, the front corner on its side (156 mm from the axle)
     * swings off it and only the rear corner (141 mm) swings toward it;
     * turning toward it, the front corner meets it first */
    /* the front corners' beams: within 15 degrees of 45 degrees either side */
    static const float corner = 0.70710678f, within = 0.96592583f;
    float d, nx, ny;
    uint8_t s;
    int l, r, away;
    if (ffr_orient_clearance(cfg, g, ir_mm, &d, &nx, &ny) && d < ffr_orient_turn_radius_mm(cfg) + SIDE_MARGIN_MM) {
        return ffr_absf(ny) < 0.5f ? 0 : ny < 0.0f ? 1 : -1;
    }
    /* none near as read, but a front corner ranger reading within its
     * fold-back span (FFR_FOLD_CORNER_MAX_MM): its wall may be 42-80 mm off it,
     * the front corner on it. Away from that side, if the other front
     * corner does not read so too (start circle seeds 629, 635: turning
     * toward it, the corner met the wall at once) */
    s = ffr_orient_fold_suspects(cfg, ir_mm, FFR_FOLD_CORNER_MAX_MM);
    l = (s & beams_toward(g, corner, corner, within)) != 0u;
    r = (s & beams_toward(g, corner, -corner, within)) != 0u;
    away = l == r ? 0 : l ? -1 : 1;
    /* unless the centre ranger reads so too: the wall is across the front,
     * the suspect corner nearest it. Turning away from that side swings the
     * corner forward, into it; turning toward its side swings it back (the
     * other front corner, farther off, comes forward). Start seeds 7683,
     * 9417, 10458: docs/robustness.md, "The sweep's direction". The
     * centre's beam looked up only then: looked up on every call, the
     * Cortex-M0's worst tick went from 105,812 to 107,312 instructions
     * (make selftest) */
    return away != 0 && (s & beams_toward(g, 1.0f, 0.0f, within)) != 0u ? -away : away;
}

void ffr_orient_begin(ffr_state_t *st)
{
    ffr_orient_reset(&st->orient, &st->odo);
    st->orient.phase = PH_CLEAR;
    st->state = FFR_ST_ORIENT;
}

/* Room to turn in place? If a wall is within the body's turning radius (+
 * a margin), one move away from it: straight forward or back when the wall
 * is mostly ahead or behind, else an arc turning away from it (forward if
 * the front is free, else backward). 1 when there is room (or the moves are
 * spent): the sweep begins here. */
static float end_room(const ffr_state_t *st, int backward, float band, uint8_t skip);
static float straight_room(const ffr_state_t *st, int backward, uint8_t skip);
static uint8_t beside_skip(const ffr_state_t *st, float side);
static uint8_t beside_skip_within(const ffr_state_t *st, float side, float front_mm);
static int line_reading(const ffr_config_t *cfg, float d);
/* both sides' walls beside at the span's bottom (beside_skip): along a
 * straight move; `front_mm`: how far above its bottom the front one may
 * read (0.5: at it) */
static uint8_t along_skip(const ffr_state_t *st, float front_mm)
{
    return (uint8_t)(beside_skip_within(st, 1.0f, front_mm) | beside_skip_within(st, -1.0f, front_mm));
}
static int escape_free(const ffr_state_t *st);
static uint8_t front_beams(const ffr_state_t *st);
static int unfold_front(ffr_state_t *st, uint8_t was_along);

/* An S of arcs of radius r that ends lat mm farther from the wall: each
 * arc's angle (2 r (1 - cos a) = lat) */
static float s_angle(float lat, float r)
{
    float c = 1.0f - lat / (2.0f * r);
    return ffr_atan2f(ffr_sqrtf(1.0f - c * c), c);
}

/* The free floor ahead (from the axle) that such an S forward needs: the
 * body's front, ESCAPE_FREE_MM, and the S's length along the wall, 2 r sin a */
static float s_room(const ffr_config_t *cfg, float r, float a)
{
    return cfg->body_front_mm + ESCAPE_FREE_MM + 2.0f * r * ffr_sinf(a);
}

/* A line across a corner, not a wall along the side (side: > 0 left, < 0
 * right): the side's front corner ranger measures its wall, more than
 * CHORD_FRONT_MM above its span's bottom, and the rear one reads at the
 * bottom. A wall along the side reads alike at both ends (both at the
 * bottom when near); here the front one's wall is ahead of that side, the
 * rear one's behind it (fresh +-2.5 cm start seed 703: 142 mm on the wall
 * ahead at 31 degrees, the rear one on the wall behind). */
static int corner_chord(const ffr_state_t *st, float side)
{
    int i, front = 0, rear = 0;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (st->ir_geom.beam_sin[i] * side > 0.5f) {
            if (st->ir_geom.beam_cos[i] > 0.0f) {
                front = line_reading(&st->cfg, st->ir_mm[i]) && st->ir_mm[i] > st->cfg.ir_min_mm + CHORD_FRONT_MM;
            } else {
                rear = ffr_ir_valid(&st->cfg, st->ir_mm[i]) && st->ir_mm[i] <= st->cfg.ir_min_mm + 0.5f;
            }
        }
    }
    return front && rear;
}

/* An escape leg straight ahead (backward: astern) for len mm, watched as
 * every leg is (ffr_orient_watch_leg) */
static void straight_leg(ffr_state_t *st, float len, uint8_t backward, uint8_t leg)
{
    ffr_home_orient_t *o = &st->orient;
    o->reverse = backward;
    o->leg = leg;
    o->target_rad = 0.0f; /* curvature (1/mm): straight */
    o->goal_mm = st->odo.dist_mm + len;
    ffr_orient_watch_leg(st);
    o->phase = PH_ESCAPE;
}

/* ranger i reads no wall within far_mm (nothing read counts) */
static int reads_open(const ffr_state_t *st, int i, float far_mm)
{
    return !ffr_ir_valid(&st->cfg, st->ir_mm[i]) || st->ir_mm[i] >= far_mm;
}

/* The S forward away from a wall beside nearer than the rangers measure
 * (skip: that side's pair at their span's bottom, beside_skip) cannot
 * start: the floor ahead, front_beside mm, is shorter than the S of radius
 * r and arc angle a needs. The leg would stop on the tick it began and the
 * try be spent standing still; with four so spent the sweep's turn swung
 * the rear corner into the wall beside (orientation bench start seeds
 * 6830, 8692: a wall 200-280 mm ahead, about 308 mm of the 383 the S
 * needs). First straight back by what the floor ahead lacks, for the wider
 * S (ESCAPE_WIDE_MM, whose first arc swings the rear corner out less) as
 * far as the floor behind allows, then the look again. Only when the other
 * side's rear ranger reads a wall within BACK_S_WALL_MM, a way's far wall
 * behind, the body along the near one: without it the "wall beside" may
 * converge on the body, nearest at the rear corner, which backing drives
 * into it (start seed 4392: 33 degrees off the axis, that ranger reading
 * nothing; docs/robustness.md, "A move back for an S short of floor").
 * 1 when the move began. */
static int back_for_s(ffr_state_t *st, float ny, uint8_t skip, float front_beside, float lat, float r, float a)
{
    const ffr_config_t *cfg = &st->cfg;
    float want = s_room(cfg, r, a) - front_beside + 10.0f;
    float wide = s_room(cfg, ESCAPE_WIDE_MM, s_angle(lat, ESCAPE_WIDE_MM)) - front_beside + 10.0f;
    float behind = straight_room(st, 1, skip);
    int i, wall_behind = 0;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        /* the other side's rear ranger */
        if (st->ir_geom.beam_sin[i] * ny < -0.5f && st->ir_geom.beam_cos[i] < 0.0f) {
            wall_behind |= !reads_open(st, i, BACK_S_WALL_MM);
        }
    }
    if (wall_behind && behind > want) {
        float len = wide < behind ? wide : behind;
        straight_leg(st, len < ESCAPE_MAX_MM ? len : ESCAPE_MAX_MM, 1u, LEG_BACK_S);
        return 1;
    }
    return 0;
}

/* The S's first arc from a wall beside, begun at ESCAPE_SOFT_MM and
 * tightened to r once the body has turned through soft_turn: there the
 * rear corner no longer swings toward the wall on r's arc (its swing stops
 * at an angle b / (r + w/2); b taken as body_front_mm, the longer end, the
 * rear being unknown to the firmware). The arc's length to turn through a. */
static float soft_turn(const ffr_config_t *cfg, float a, float r)
{
    float t = cfg->body_front_mm / (r + cfg->body_half_width_mm);
    return t < a ? t : a;
}

static float soft_len(const ffr_config_t *cfg, float a, float r)
{
    float t = soft_turn(cfg, a, r);
    return ESCAPE_SOFT_MM * t + r * (a - t);
}

/* the S's first arc, begun gently or not */
static int s_first_arc(const ffr_home_orient_t *o) { return o->leg == 1u || o->leg == LEG_SOFT; }

/* The yaw rate of an escape leg driven at v with left mm to go: its
 * curvature (target_rad), the gentle part of LEG_SOFT's at ESCAPE_SOFT_MM
 * (leg_mm: the wide arc's length, r a) */
static float leg_yaw(const ffr_state_t *st, float v, float left)
{
    const ffr_home_orient_t *o = &st->orient;
    if (o->leg == LEG_SOFT) {
        float a = o->leg_mm * ffr_absf(o->target_rad);
        if (soft_len(&st->cfg, a, ESCAPE_WIDE_MM) - left < ESCAPE_SOFT_MM * soft_turn(&st->cfg, a, ESCAPE_WIDE_MM)) {
            return v * (o->target_rad > 0.0f ? 1.0f : -1.0f) / ESCAPE_SOFT_MM;
        }
    }
    return v * o->target_rad;
}

/* One move away from a wall d mm off in direction (nx, ny) (body frame). */
static void start_escape(ffr_state_t *st, float need, float d, float nx, float ny)
{
    ffr_home_orient_t *o = &st->orient;
    float len;
    o->escapes++;
    if (ffr_absf(nx) >= 0.5f) {
        /* ahead or behind: straight away from it */
        o->reverse = nx > 0.0f;
        o->leg = 0u;
        o->target_rad = 0.0f; /* curvature (1/mm): straight */
        len = (need - d) / ffr_absf(nx) + 10.0f;
        o->goal_mm = st->odo.dist_mm + (len < ESCAPE_MAX_MM ? len : ESCAPE_MAX_MM);
    } else {
        /* beside: an S away from it (an arc turning away, one turning back:
         * the heading as before, 2 R (1 - cos a) farther from the wall),
         * forward if the front is free, else backward; then straight back
         * along the wall to where it began (after a first arc begun gently,
         * LEG_SOFT, (ESCAPE_SOFT_MM - r) sin(soft_turn), ~9 cm, short of it) */
        float lat = need - d + 10.0f;
        float a = s_angle(lat, ESCAPE_RADIUS_MM), r = ESCAPE_RADIUS_MM;
        /* turning away from the wall's side, either way driven */
        /* the wall beside, read at the span's bottom, is no end of the path
         * when the floor ahead (as the other rangers see it) has room for the
         * whole S beyond ESCAPE_FREE_MM (else: as before) */
        uint8_t skip = beside_skip(st, ny);
        float front = end_room(st, 0, ARC_BAND_MM, 0u);
        float front_beside = end_room(st, 0, ARC_BAND_MM, skip);
        uint8_t was_back = o->leg == LEG_BACK || o->leg == LEG_BACK_S || o->leg == LEG_ALONG;
        uint8_t was_along = o->leg == LEG_ALONG; /* after unfold_front's probe or move */
        int shut;
        if (front_beside > s_room(&st->cfg, ESCAPE_RADIUS_MM, a)) {
            front = front_beside;
        }
        shut = front < st->cfg.body_front_mm + ESCAPE_FREE_MM + ESCAPE_START_MM;
        /* after the straight back below: forward, if that gave the front room */
        o->reverse = end_room(st, 1, ARC_BAND_MM, 0u) > front && (shut || !was_back);
        if (!o->reverse && beside_skip_within(st, ny, WIDE_FRONT_MM) != 0u) {
            /* forward from a wall beside nearer than the rangers measure
             * (both at their span's bottom, or just above it: a wall 8 mm
             * off the side, parallel, folds both back to ~104 mm; the front
             * one within WIDE_FRONT_MM of the bottom, the rear one within
             * BESIDE_REAR_MM): the first arc swings the rear corner out
             * toward it, ~19 mm on the 150 mm arc, ~12 mm on
             * ESCAPE_WIDE_MM's. The wider S where the floor ahead has room
             * for it (fresh +-2.5 cm start seed 605: 14 mm off the wall;
             * nominal start seed 7636: 8 mm off, the front ranger at 104 mm,
             * the 150 mm arc met it) */
            float aw = s_angle(lat, ESCAPE_WIDE_MM);
            if (front > s_room(&st->cfg, ESCAPE_WIDE_MM, aw)) {
                a = aw;
                r = ESCAPE_WIDE_MM;
            }
        }
        if (!o->reverse && skip != 0u && !was_back && front_beside < s_room(&st->cfg, r, a) &&
            back_for_s(st, ny, skip, front_beside, lat, r, a)) {
            return;
        }
        if (!o->reverse && front < s_room(&st->cfg, r, a) && corner_chord(st, ny)) {
            /* the line cuts across a corner, and the floor ahead is shorter
             * than the whole S: no S forward, whose front corner would meet
             * the wall ahead (seed 703: 269 mm of the 356 it needs, the
             * front left corner on the south wall at 1.22 s). The escapes
             * are given up and the sweep turns in place, as once they are
             * spent: the rangers read the two walls past the body's ends,
             * not beside it (seed 703: 216 and 233 mm off the axle).
             * First, on the orientation's first move, a short step straight
             * forward if the floor ahead has room for it: the rear ranger at
             * its bottom may be a wall along the side at a slant, nearest at
             * the rear corner, that the sweep's turn would swing that corner
             * into (start seeds 4632, 8130, 9434: 41-49 mm off it along the
             * rear beam); a straight move takes the rear corner away from a
             * wall behind or diagonally behind, and keeps the body in its
             * own band. Then the look again decides */
            if (o->escapes == 1u &&
                straight_room(st, 0, 0u) > CHORD_STEP_MM) {
                straight_leg(st, CHORD_STEP_MM, 0u, 0u);
                return;
            }
            o->escapes = ESCAPE_TRIES;
            o->phase = PH_CLEAR;
            return;
        }
        o->leg = 1u;
        o->leg_mm = r * a;
        o->target_rad = (ny > 0.0f ? -1.0f : 1.0f) / r;
        o->goal_mm = st->odo.dist_mm + o->leg_mm;
        if (!o->reverse && r == ESCAPE_WIDE_MM && front > s_room(&st->cfg, r, a) + soft_len(&st->cfg, a, r) - r * a) {
            /* the wide S forward from a wall beside nearer than the rangers
             * measure, begun gently where the floor ahead has room for its
             * longer first arc: its rear corner swings out ~7 mm, not
             * ~12 (orientation bench start seed 11437: 6 mm off the wall
             * and parallel to it, met at once; held-out +-5 cm start seed
             * 76). The second arc and the way back are the wide S's */
            o->leg = LEG_SOFT;
            o->goal_mm = st->odo.dist_mm + soft_len(&st->cfg, a, r);
        }
        if (!o->reverse) {
            /* the S forward as it would begin (an arc: no slant or chord
             * watch, so as escape_free asks on its first tick) stops at
             * once: that try would be spent standing */
            if (!escape_free(st) && unfold_front(st, was_along)) {
                return;
            }
        }
        if (o->reverse && shut && !was_back) {
            /* the front shut (a wall at a front corner): not an S backward
             * at once. The rear pair look out at 135 degrees: they see none
             * of the floor behind the rear face nor beside it, and the S's
             * arcs swing a rear corner out over that floor (a wall's end
             * there is met unseen). First straight back, the body within its
             * own band, until the front would have room for the S; then look
             * again (a wall's end behind comes into the rear pair's beams as
             * the rear nears it) and drive the S forward. Once: a wall that
             * keeps the front shut gets the S backward as before */
            float want = st->cfg.body_front_mm + ESCAPE_FREE_MM + ESCAPE_START_MM + 10.0f - front;
            o->leg = LEG_BACK;
            o->target_rad = 0.0f;
            o->goal_mm = st->odo.dist_mm + (want < ESCAPE_MAX_MM ? want : ESCAPE_MAX_MM);
        }
    }
    ffr_orient_watch_leg(st);
    o->phase = PH_ESCAPE;
}

/* Fold-back: a GP2D12 closer to a wall than its span's bottom reads far
 * again (3-5.5 cm reads as 10-18.5 cm), so a reading in that span may be a
 * wall nearly touching the body. Such a reading counts as a near wall (the
 * bottom of the span, as a reading of ir_min_mm) until a move away from it
 * has made it grow, as a wall that far would (folded back, it shrinks or
 * drops to the bottom instead). */
uint8_t ffr_orient_probe_trust(const ffr_config_t *cfg, uint8_t probed, const float before_mm[FFR_IR_COUNT],
                               const float ir_mm[FFR_IR_COUNT])
{
    uint8_t t = 0u;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if ((probed >> i) & 1 && ffr_ir_valid(cfg, ir_mm[i]) && ir_mm[i] > before_mm[i] + PROBE_GROW_MM) {
            t = (uint8_t)(t | (1 << i));
        }
    }
    return t;
}

void ffr_orient_probe_tell(const ffr_config_t *cfg, const ffr_ir_geom_t *g, int backward, uint8_t suspects,
                           const float before_mm[FFR_IR_COUNT], const float ir_mm[FFR_IR_COUNT], uint8_t *genuine,
                           uint8_t *folded)
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        /* +1: the move goes toward this ranger's wall, -1: away from it */
        float toward = (backward ? -1.0f : 1.0f) * g->beam_cos[i];
        float delta;
        if (!((suspects >> i) & 1) || ffr_absf(toward) < 0.3f || !ffr_ir_valid(cfg, ir_mm[i])) {
            continue;
        }
        delta = (ir_mm[i] - before_mm[i]) * (toward > 0.0f ? -1.0f : 1.0f); /* > 0: as a wall that far */
        if (ir_mm[i] <= cfg->ir_min_mm + 0.5f && toward < 0.0f) {
            /* moving away, it dropped to its span's bottom: folded back */
            *folded = (uint8_t)(*folded | (1 << i));
        } else if (delta > PROBE_TELL_MM) {
            *genuine = (uint8_t)(*genuine | (1 << i));
        } else if (delta < -PROBE_TELL_MM) {
            *folded = (uint8_t)(*folded | (1 << i));
        }
    }
}

int ffr_orient_probe_back(const ffr_ir_geom_t *g, uint8_t suspects)
{
    /* A ranger folded back sees a wall 3-5.5 cm off: beyond the body's face
     * its beam leaves through. The rear rangers' beams (135 degrees off
     * the axis) leave through the rear face, the centre one's through the
     * front face: such a wall is behind, or ahead. The front corners' beams
     * (45 degrees) leave through the side, 4 cm from the ranger: a wall
     * folded back there is beside the body, along the move. So: forward,
     * unless only the front may be blocked. */
    int i, front = 0, rear = 0;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (!((suspects >> i) & 1)) {
            continue;
        }
        if (g->beam_cos[i] < -0.5f) {
            rear = 1;
        } else if (g->beam_cos[i] > 0.5f) {
            front = 1;
        }
    }
    return front && !rear;
}

/* The probe: a short slow straight move, watching the suspect rangers (a
 * reading in the fold-back span): a wall that far comes nearer as the robot
 * moves toward it, one folded back reads farther (and the other way round
 * moving away): over 15 mm a wall as read changes by about 10 mm, one
 * folded back by 3-4 times more the other way. It stops early only when a
 * ranger it moves toward reads folded back. */
static void probe_step(ffr_state_t *st)
{
    ffr_home_orient_t *o = &st->orient;
    uint8_t genuine = 0u, folded = 0u, ahead;
    float left = o->goal_mm - st->odo.dist_mm;
    uint8_t along = (uint8_t)(o->leg == LEG_ALONG || o->leg == LEG_ALONG_RETURN);
    if (along) {
        /* unfold_front's probe counts the body's net travel along its axis
         * since it began (leg_mm, signed), not path length: it may begin
         * with the body still rolling on from the move before (an S cut
         * short), and that roll would count toward its 15 mm. goal_mm
         * bounds each leg's path length as well */
        o->leg_mm += 0.5f * (st->odo.dpos_mm[0] + st->odo.dpos_mm[1]);
        left = left > 0.0f ? (o->leg == LEG_ALONG ? PROBE_MM + o->leg_mm : -o->leg_mm) : 0.0f;
    }
    if (o->leg == LEG_PROBE_RETURN || o->leg == LEG_ALONG_RETURN) {
        /* nothing folded back: back to where it stood (the sweep from there
         * sees what it would have seen without the probe). unfold_front's
         * goes back over the floor it has just left, to where it began: no
         * look at the room (the floor ahead as read is short there, or it
         * would not have probed) */
        if (left > 0.0f && (o->leg == LEG_ALONG_RETURN || escape_free(st))) {
            float v = ffr_stopping_speed(left, PROBE_SPEED_MM_S);
            st->cmd_v_mm_s = o->reverse ? -v : v;
            return;
        }
        ffr_stop(st);
        o->leg = 0u;
        o->phase = PH_CLEAR;
        return;
    }
    ffr_orient_probe_tell(&st->cfg, &st->ir_geom, o->reverse & 1u, o->probed, o->probe_mm, st->ir_mm, &genuine,
                          &folded);
    ahead = beams_toward(&st->ir_geom, o->reverse ? -1.0f : 1.0f, 0.0f, 0.3f);
    if (left > 0.0f && !(folded & ahead) && escape_free(st)) {
        float v = ffr_stopping_speed(left, PROBE_SPEED_MM_S);
        st->cmd_v_mm_s = o->reverse ? -v : v;
        return;
    }
    ffr_stop(st);
    /* what the probe did not see folded back is taken as read (a wall
     * along the move, or noise: no more moves for it) */
    o->trusted = (uint8_t)(o->trusted | (o->probed & ~folded) | genuine);
    o->folded = folded;
    o->probed = 0u;
    o->phase = PH_CLEAR;
    if (folded == 0u) {
        o->leg = along ? LEG_ALONG_RETURN : LEG_PROBE_RETURN;
        o->reverse ^= 1u;
        o->goal_mm = st->odo.dist_mm + (along ? 2.0f * PROBE_MM : PROBE_MM - left);
        o->phase = PH_PROBE;
    }
}

/* A straight move of len mm away from the rangers `away` (backward: from
 * rangers looking ahead, else from rangers looking back). How their
 * readings change over it tells fold-back (clear_step, LEG_FOLD and
 * LEG_TURNED). leg: LEG_FOLD (fold_move) or LEG_TURNED (a fold move forward
 * turned back, lead_grew). */
static void fold_leg(ffr_state_t *st, uint8_t away, float len, uint8_t backward, uint8_t leg)
{
    ffr_home_orient_t *o = &st->orient;
    int i;
    o->leg_mm = len; /* a turn back (LEG_TURNED): how far it came */
    o->probed = away;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        o->probe_mm[i] = st->ir_mm[i];
    }
    straight_leg(st, len, backward, leg);
}

/* A fold move: one of the moves before the sweep. The rear and front fold
 * moves and the move after a passed peak (pass_move) make it. */
static void fold_move(ffr_state_t *st, uint8_t away, float len, uint8_t backward)
{
    st->orient.escapes++;
    fold_leg(st, away, len, backward, LEG_FOLD);
}

/* The fold move away from `away` if there are such rangers and the end it
 * drives toward has room for it (1 when it starts) */
static int fold_move_if_room(ffr_state_t *st, uint8_t away, float len, uint8_t backward)
{
    if (away == 0u || straight_room(st, backward, 0u) < len) {
        return 0;
    }
    fold_move(st, away, len, backward);
    return 1;
}

/* A rear suspect's own side's front corner ranger a suspect too, reading
 * within NEARER_FRONT_MM above its span's bottom and NEARER_BY_MM or more
 * below the rear one: the wall beside is nearer at the front corner as
 * read, and may be nearer still (folded back: ~5 cm off the ranger, the
 * corner a few mm off the wall). The rear fold move forward would drive
 * that corner into it (nominal start seeds 6383, 6709, 6803, 6823: 3-8 mm
 * off the home hallway's south wall, 11-37 degrees toward it). Not when the
 * other rear ranger reads a wall within BEHIND_MM: a wall behind, which the
 * move back would meet (arbitrary start seed 2051: a hallway's end wall).
 * A front ranger at its very bottom is left to the rules as before (the
 * wall beside: the S forward). Those front rangers, else 0
 * (docs/robustness.md, "Back first from a wall beside nearer at the front") */
#define NEARER_FRONT_MM 15.0f /* chosen: the won starts read 1-11 mm above the bottom */
#define NEARER_BY_MM 20.0f    /* chosen: they read 28-56 mm below the rear one */
#define BEHIND_MM 250.0f      /* chosen: the hallway start lost read 229; the won 296 and more */
static uint8_t front_nearer(const ffr_state_t *st, uint8_t suspects)
{
    uint8_t m = 0u;
    int k;
    for (k = 0; k < 2; ++k) {
        /* WALL_PAIRS' first two: a side's front and rear rangers */
        int fi = WALL_PAIRS[k][0], ri = WALL_PAIRS[k][1], other_rear = WALL_PAIRS[1 - k][1];
        float f = st->ir_mm[fi], r = st->ir_mm[ri];
        if ((suspects >> ri) & 1 && (suspects >> fi) & 1 && f <= st->cfg.ir_min_mm + NEARER_FRONT_MM &&
            f < r - NEARER_BY_MM && st->ir_mm[other_rear] > BEHIND_MM) {
            m = (uint8_t)(m | (1 << fi));
        }
    }
    return m;
}

/* The front fold move itself: straight back FRONT_FOLD_MOVE_MM away from
 * the front suspects, if the floor behind has room (1 when it starts) */
static int front_move_back(ffr_state_t *st, uint8_t suspects)
{
    return fold_move_if_room(st, (uint8_t)(suspects & front_beams(st)), FRONT_FOLD_MOVE_MM, 1u);
}

/* A rear ranger reading within the fold-back span (above its bottom, up to
 * FFR_FOLD_MAX_MM) may be a wall 3-5.5 cm off it, read as 10-18.5 cm: a
 * rear corner on a wall, which no rule from the hits sees (the hit is
 * placed far off), and the sweep's turn swings it in. Before anything else
 * (the first move of the orientation), once: straight forward
 * REAR_FOLD_MOVE_MM, if the front has room. A straight move keeps the body
 * in its own band (a wall beside along it is not met) and takes every point
 * away from a wall behind or diagonally behind. `suspects`: the readings
 * within the fold-back span on the first look (ffr_orient_step gives 0
 * after any move, and with the fold-back probe built in, which does this
 * job there). But the front fold move, back, where the wall beside is
 * nearer at the front corner (front_nearer). 1 when the move starts. */
static int rear_fold_move(ffr_state_t *st, uint8_t suspects)
{
    uint8_t front;
    if (suspects == 0u) {
        return 0; /* the common case: the beams not looked up (the first look's tick, make selftest) */
    }
    front = front_nearer(st, suspects);
    if (front != 0u) {
        /* the wall beside may slant in toward the front corner: the front
         * fold move instead (straight back), as front_fold_move's */
        return front_move_back(st, suspects);
    }
    return fold_move_if_room(st, (uint8_t)(suspects & rear_beams(st)), REAR_FOLD_MOVE_MM, 0u);
}

/* The same for the front: the centre ranger or a front corner ranger
 * reading within the fold-back span may be a wall 4-8 cm off it, read as
 * 10-16 cm: a wall ahead within the turning circle (the centre's, 2-6 cm
 * off the front face) or a front corner on a wall, which the sweep's turn
 * meets at once (start seeds 4694, 8071, 9803: docs/robustness.md, "The
 * front fold move"). First, once, and only with no rear ranger within the
 * span (that is the rear fold move's, and a wall behind): straight back
 * FRONT_FOLD_MOVE_MM, if the floor behind as the rear pair see it has room.
 * The readings over the move tell which rangers were folded back, as for
 * the rear move. `suspects` as there. 1 when the move starts. */
static int front_fold_move(ffr_state_t *st, uint8_t suspects)
{
    return suspects != 0u && (suspects & rear_beams(st)) == 0u && front_move_back(st, suspects);
}

/* The probe (probe_step) away from the suspects' walls, backward or not */
static void start_probe(ffr_state_t *st, uint8_t suspects, uint8_t backward)
{
    ffr_home_orient_t *o = &st->orient;
    int i;
    o->probe_done = 1u;
    o->reverse = backward;
    o->target_rad = 0.0f;
    o->goal_mm = st->odo.dist_mm + PROBE_MM;
    o->probed = suspects;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        o->probe_mm[i] = st->ir_mm[i];
    }
    o->phase = PH_PROBE;
}

/* The S forward from a wall beside nearer than the rangers measure would
 * stop on the tick it begins: the floor ahead, as read, too short for it.
 * The tries would be spent standing, and the sweep turn where it stands.
 * A front ranger reading within the fold-back span may be a wall ahead
 * nearer than read, within the front corners' turning circle (fresh
 * +-2.5 cm start seed 1390: the centre ranger 54 mm off a wall across
 * ahead, read 106 mm; the sweep's turn put the front corner on it). So
 * first the probe, backward (slowly, PROBE_MM), watched with the wall
 * beside skipped while its side's rangers read within BESIDE_REAR_MM of
 * their bottom (LEG_ALONG: backing along it, the front one's reading
 * grows a little). A front ranger its probe found folded back (was_along:
 * the leg before was LEG_ALONG): straight back FRONT_FOLD_MOVE_MM more,
 * watched alike. A wall read as it is: back
 * where it stood (LEG_ALONG_RETURN), and the tries go on as before. The
 * probe takes a try; not on the last one, which would leave none for the
 * move back. 1 when a move began */
static int unfold_front(ffr_state_t *st, uint8_t was_along)
{
    ffr_home_orient_t *o = &st->orient;
    uint8_t front = front_beams(st), sus;
    if (was_along && (o->folded & front) != 0u) {
        if (straight_room(st, 1, along_skip(st, BESIDE_REAR_MM)) < FRONT_FOLD_MOVE_MM) {
            return 0;
        }
        o->folded &= (uint8_t)~front;
        straight_leg(st, FRONT_FOLD_MOVE_MM, 1u, LEG_ALONG);
        return 1;
    }
    sus = (uint8_t)(ffr_orient_fold_suspects(&st->cfg, st->ir_mm, FFR_FOLD_MAX_MM) & front & ~o->trusted);
    if (sus == 0u || o->probe_done || o->escapes >= ESCAPE_TRIES ||
        straight_room(st, 1, along_skip(st, BESIDE_REAR_MM)) < PROBE_MM) {
        return 0; /* on the last try: no try would be left for the move back */
    }
    start_probe(st, sus, 1u);
    o->leg = LEG_ALONG;
    o->leg_mm = 0.0f; /* its net travel (probe_step) */
    o->goal_mm = st->odo.dist_mm + 3.0f * PROBE_MM; /* and a bound on its path */
    return 1;
}

static int clear_step(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_home_orient_t *o = &st->orient;
    float need = ffr_orient_turn_radius_mm(cfg) + CLEAR_MARGIN_MM;
    float d, nx, ny, mx, my, d2, nx2, ny2, ir[FFR_IR_COUNT];
    uint8_t suspects, grown;
    int i, found;
    grown = ffr_orient_probe_trust(cfg, o->probed, o->probe_mm, st->ir_mm);
    if (o->leg == LEG_FOLD || o->leg == LEG_TURNED) {
        /* after a fold move: a ranger whose reading dropped to its span's
         * bottom or shrank as the robot moved away was folded back (a wall
         * as far as read recedes; one along the move, read by the ranger's
         * slanted beam, reads the same: neither is folded) */
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            if ((o->probed >> i) & 1 && ffr_ir_valid(cfg, st->ir_mm[i]) &&
                (st->ir_mm[i] <= cfg->ir_min_mm + 0.5f || st->ir_mm[i] < o->probe_mm[i] - FOLD_SHRINK_MM)) {
                o->folded = (uint8_t)(o->folded | (1 << i));
            }
        }
        o->leg = 0u;
    }
    o->trusted = (uint8_t)(o->trusted | grown);
    o->probed = 0u;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        /* such a ranger, still reading within the fold-back span, reads the
         * wall the move went away from: the rear corner is now the move's
         * length farther off it than it was, room for the turn. Taken as
         * read, at its span's bottom the wall would count as near, and
         * the escapes walked the robot on (seed 51 of the held-out +-2.5 cm
         * jitter row: into the middle hallway's mouth) */
        ir[i] = (FFR_HOME_FOLD_MM <= 0.0f && (o->folded >> i) & 1 && st->ir_mm[i] <= FFR_FOLD_MAX_MM)
                    ? FFR_IR_NONE(cfg)
                    : st->ir_mm[i];
    }
    suspects = (uint8_t)(ffr_orient_fold_suspects(cfg, ir, FFR_HOME_FOLD_MM) & ~o->trusted);
    if (o->probe_done) {
        suspects &= o->folded; /* after the probe: only what it saw folded back */
    }
    if (o->escapes >= ESCAPE_TRIES) {
        return 1;
    }
    /* the line through two rangers' hits: not through two that may both
     * be folded back (before the probe), nor through one seen to be (after
     * it); two the probe could not tell (a wall along the move) may be one
     * wall's */
    found = ffr_orient_clearance_fold(cfg, &st->ir_geom, ir, 0u, o->probe_done ? 0u : suspects,
                                      (uint8_t)(o->probe_done ? suspects & o->folded : suspects), &d2, &nx2, &ny2);
    if (found && d2 < need) {
        /* a wall near as read: away from it */
        d = d2;
        nx = nx2;
        ny = ny2;
    } else if (suspects == 0u ||
               !ffr_orient_clearance_fold(cfg, &st->ir_geom, ir, suspects, 0u, suspects, &d, &nx, &ny) ||
               d >= need) {
        /* not near even if folded back (with no suspects that is the same
         * wall as above: not worked out twice, a tick's budget) */
        return 1;
    } else if (!o->probe_done) {
        /* near only if a reading is folded back: a probe tells which first
         * (once per look: away from the nearest such wall) */
        start_probe(st, suspects, (uint8_t)ffr_orient_probe_back(&st->ir_geom, suspects));
        return 0;
    }
    start_escape(st, need, d, nx, ny);
    if (o->phase == PH_PROBE) {
        return 0; /* unfold_front's probe */
    }
    if (FFR_HOME_FOLD_MM <= 0.0f) {
        /* toward the wall a fold move left (backing: the rear move's; forward:
         * the front move's): its rangers read again */
        o->folded &= (uint8_t)~(o->reverse ? rear_beams(st) : front_beams(st));
    }
    /* the rangers this move goes away from: their readings tell fold-back */
    if (o->leg == 0u || o->leg == LEG_BACK || o->leg == LEG_BACK_S || o->leg == LEG_ALONG) {
        mx = o->reverse ? -1.0f : 1.0f;
        my = 0.0f;
    } else {
        mx = 0.0f;
        my = ny > 0.0f ? -1.0f : 1.0f;
    }
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (st->ir_geom.beam_cos[i] * mx + st->ir_geom.beam_sin[i] * my < -0.3f) {
            o->probed = (uint8_t)(o->probed | (1 << i));
            o->probe_mm[i] = st->ir_mm[i];
        }
    }
    return 0;
}

/* Free floor from the axle midpoint to the nearest hit in the body's path
 * (its half width + band each side), ahead (backward = 0) or behind. */
static float end_room(const ffr_state_t *st, int backward, float band, uint8_t skip)
{
    const ffr_config_t *cfg = &st->cfg;
    float room = 65535.0f;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float x = st->ir_geom.hit_x_mm[i], y = st->ir_geom.hit_y_mm[i];
        if (!ffr_ir_valid(cfg, st->ir_mm[i]) || (skip >> i) & 1) {
            continue;
        }
        if (st->ir_mm[i] <= cfg->ir_min_mm + 0.5f) {
            x = cfg->ir_x_mm[i] + 0.5f * cfg->ir_min_mm * st->ir_geom.beam_cos[i];
            y = cfg->ir_y_mm[i] + 0.5f * cfg->ir_min_mm * st->ir_geom.beam_sin[i];
        }
        if (backward) {
            x = -x;
        }
        if (x > 0.0f && ffr_absf(y) < cfg->body_half_width_mm + band && x < room) {
            room = x;
        }
    }
    return room;
}

/* How long a straight move ahead (backward = 0) or behind may be: the free
 * floor in the body's path (end_room, BAND_MARGIN_MM, the rangers `skip`
 * left out) beyond the body's front and ESCAPE_FREE_MM */
static float straight_room(const ffr_state_t *st, int backward, uint8_t skip)
{
    return end_room(st, backward, BAND_MARGIN_MM, skip) - st->cfg.body_front_mm - ESCAPE_FREE_MM;
}

/* The wall beside that a sideways escape moves away from (side: > 0 left,
 * < 0 right), nearer than the rangers measure: the corner and rear rangers
 * on that side reading at their span's bottom see that wall (very near, not
 * unknown), which lies along the move, not across either end of it; both
 * of them, as a wall along the side (one alone may be a wall's end). The
 * rear one may read up to BESIDE_REAR_MM above the bottom: a part reading
 * long, or the body a few degrees to the wall (fresh +-2.5 cm start seed
 * 414: 27 mm off the wall, its rear ranger read 109-115 mm; taken for a
 * wall's end, the front stayed shut, the escapes were spent without
 * moving and the sweep swung the rear corner into the wall). Their
 * hits, placed at half the span's bottom, would otherwise land inside the
 * body's path band at both ends and shut both (the escape could not move;
 * the sweep then swung a corner into the wall). The centre ranger still
 * looks ahead, the other side's rangers at their corners. */
static uint8_t beside_skip(const ffr_state_t *st, float side) { return beside_skip_within(st, side, 0.5f); }

/* the same, the front one reading up to front_mm above its span's bottom */
static uint8_t beside_skip_within(const ffr_state_t *st, float side, float front_mm)
{
    uint8_t m = 0u;
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (st->ir_geom.beam_sin[i] * side > 0.5f) {
            if (st->ir_mm[i] > st->cfg.ir_min_mm + (st->ir_geom.beam_cos[i] > 0.0f ? front_mm : BESIDE_REAR_MM)) {
                return 0u; /* not both: the other may be a wall's end at a corner */
            }
            m = (uint8_t)(m | (1 << i));
        }
    }
    return m;
}

/* a reading measured within the span (not at its bottom, a bound) and near
 * enough to draw a wall's line through */
static int line_reading(const ffr_config_t *cfg, float d)
{
    return ffr_ir_valid(cfg, d) && d > cfg->ir_min_mm + 0.5f && d <= CLEAR_RANGE_MM;
}

/* the unit direction (ux, uy) from hit a to hit b; 0 when they are too close
 * for a direction or too far apart for one wall */
static int line_dir(const ffr_ir_geom_t *g, int a, int b, float *ux, float *uy)
{
    float ex = g->hit_x_mm[b] - g->hit_x_mm[a], ey = g->hit_y_mm[b] - g->hit_y_mm[a];
    float len = ffr_sqrtf(ex * ex + ey * ey);
    if (len < CLEAR_LINE_MIN_MM || len > CLEAR_LINE_MAX_MM) {
        return 0;
    }
    *ux = ex / len;
    *uy = ey / len;
    return 1;
}

/* Driving straight ahead, how far until a front corner meets the line
 * through the centre ranger's hit and a corner ranger's (both measured, not
 * at the span's bottom), for a line the move runs into at 20 degrees or
 * more (a wall beside, along the move, is no end of it). A wall across at a
 * slant is met first by the corner on its side, while the centre ranger
 * still reads it far ahead: end_room (the hits in the body's path) saw room,
 * and a realistic robot's straight escape drove at 47 degrees to a wall
 * until the corner ranger read it folded back and the sweep's turn put the
 * corner on it (`--noise realistic --start hallway`, start seed 23).
 * 65535 if none. */
#define CORNER_INTO_COS 0.34f /* 20 degrees into it (chosen) */
static float corner_room(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_ir_geom_t *g = &st->ir_geom;
    static const uint8_t corner_ranger[2] = {FFR_IR_LF, FFR_IR_RF};
    float room = 65535.0f;
    int k;
    if (!line_reading(cfg, st->ir_mm[FFR_IR_CF])) {
        return room;
    }
    for (k = 0; k < 2; ++k) {
        int c = corner_ranger[k];
        float ux, uy, nx, ny, cx, cy, d;
        if (!line_reading(cfg, st->ir_mm[c]) || !line_dir(g, FFR_IR_CF, c, &ux, &uy)) {
            continue;
        }
        /* the line's unit normal, pointing away from the axle */
        nx = -uy;
        ny = ux;
        if (nx * g->hit_x_mm[FFR_IR_CF] + ny * g->hit_y_mm[FFR_IR_CF] < 0.0f) {
            nx = -nx;
            ny = -ny;
        }
        if (nx < CORNER_INTO_COS) {
            continue;
        }
        /* the front corner the line comes nearest (on the side its normal
         * leans to): its gap to the line, along the move */
        cx = cfg->body_front_mm;
        cy = ny >= 0.0f ? cfg->body_half_width_mm : -cfg->body_half_width_mm;
        d = ((g->hit_x_mm[FFR_IR_CF] - cx) * nx + (g->hit_y_mm[FFR_IR_CF] - cy) * ny) / nx;
        if (d < room) {
            room = d;
        }
    }
    return room;
}

/* the rear pair (looking back, *a to the left, *b to the right), both
 * reading a wall their hits can put a line through: 0 if not */
static int rear_pair(const ffr_state_t *st, int *a, int *b)
{
    const ffr_ir_geom_t *g = &st->ir_geom;
    int i;
    *a = -1;
    *b = -1;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (g->beam_cos[i] < -0.5f && line_reading(&st->cfg, st->ir_mm[i])) {
            if (g->beam_sin[i] > 0.3f) {
                *a = i;
            } else if (g->beam_sin[i] < -0.3f) {
                *b = i;
            }
        }
    }
    return *a >= 0 && *b >= 0 && g->hit_y_mm[*a] - g->hit_y_mm[*b] >= 1.0f;
}

/* The rear pair's chord: the line through the two rear rangers' hits, how
 * far behind them it crosses the body's band (65535: not both measured).
 * Two walls meeting at a corner behind lie beyond it, a wall across behind
 * on it; two walls beside (a hallway) give the same readings, a chord that
 * does not come nearer as the robot backs along them. */
static float pair_chord_room(const ffr_state_t *st, int a, int b)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_ir_geom_t *g = &st->ir_geom;
    float k, xl, xr, rear;
    k = (g->hit_x_mm[b] - g->hit_x_mm[a]) / (g->hit_y_mm[b] - g->hit_y_mm[a]);
    xl = g->hit_x_mm[a] + (cfg->body_half_width_mm - g->hit_y_mm[a]) * k;
    xr = g->hit_x_mm[a] + (-cfg->body_half_width_mm - g->hit_y_mm[a]) * k;
    rear = 0.5f * (cfg->ir_x_mm[a] + cfg->ir_x_mm[b]);
    return rear - (xl > xr ? xl : xr);
}

static float rear_chord_room(const ffr_state_t *st)
{
    int a, b;
    return rear_pair(st, &a, &b) ? pair_chord_room(st, a, b) : 65535.0f;
}

/* What a leg watches, set as it begins: a wall across at a slant ahead of
 * a front corner (forward, straight), the rear pair's chord (straight back).
 * A straight escape forward watches for a wall across it at a slant only
 * if it begins clear of one (corner_room at least CORNER_FREE_MM): a line
 * that near from the start may be two walls' hits across a room's corner
 * (the centre ranger on a wall ahead, the corner one on a wall beside), and
 * refusing the move at once would spend the escapes without moving */
void ffr_orient_watch_leg(ffr_state_t *st)
{
    ffr_home_orient_t *o = &st->orient;
    o->slant_watch = (uint8_t)(!o->reverse && o->target_rad == 0.0f && corner_room(st) >= CORNER_FREE_MM);
    o->back_chord_mm = rear_chord_room(st);
}

/* the end the escape drives toward is free */
static int escape_free(const ffr_state_t *st)
{
    /* an arc swings the body's corners out: a wider band. On the S's first
     * arc (turning away from the wall beside: that wall on the other side
     * of the turn) the wall beside is no end of the path */
    float band = st->orient.target_rad != 0.0f ? ARC_BAND_MM : BAND_MARGIN_MM;
    const ffr_home_orient_t *o = &st->orient;
    float need = st->cfg.body_front_mm + ESCAPE_FREE_MM;
    if (o->slant_watch && o->phase == PH_ESCAPE && corner_room(st) < CORNER_FREE_MM) {
        return 0; /* a wall across at a slant, ahead of a front corner */
    }
    if (o->reverse && o->target_rad == 0.0f && o->phase == PH_ESCAPE) {
        /* straight back: a wall behind the rear pair's chord, coming nearer
         * (fresh +-2.5 cm start seed 476: the east wall behind at a slant,
         * 45 degrees off the move, in no hit within the body's band) */
        float r = rear_chord_room(st);
        if (r < REAR_CHORD_MM && r < o->back_chord_mm - REAR_NEARING_MM) {
            return 0;
        }
    }
    /* back_for_s's move and unfold_front's: the wall beside, at its span's
     * bottom (unfold_front's: near it), is along the move, no end of it */
    if (end_room(st, o->reverse & 1u, band,
                 o->leg == LEG_BACK_S ? along_skip(st, 0.5f)
                                      : (o->leg == LEG_ALONG ? along_skip(st, BESIDE_REAR_MM) : 0u)) > need) {
        return 1;
    }
    /* forward on the S's first arc: the wall beside read at the span's
     * bottom is no end, if the rest of the S fits ahead */
    return s_first_arc(o) && !o->reverse &&
           end_room(st, 0, band, beside_skip(st, o->target_rad > 0.0f ? -1.0f : 1.0f)) >
               need + 0.9f * ((o->goal_mm - st->odo.dist_mm) + o->leg_mm);
}

/* The nearest wall square to the walls' direction, from the line through
 * two rangers' measured hits (readings within their span, not at its
 * bottom): ffr_orient_clearance's pairs and feet, each line taken only if it
 * runs within SQUARE_LINE_TOL_DEG of square to `walls` (the walls'
 * direction in the body frame, mod 90 degrees). Contest walls meet at right
 * angles: a line at a slant through two hits is two walls' hits across a
 * corner, nearer than either wall. 1 and its distance and unit direction
 * (body frame) if one is found. */
#define SQUARE_LINE_TOL_DEG 10.0f /* chosen: a sweep's walls' direction is within a few degrees */
int ffr_orient_square_wall(const ffr_config_t *cfg, const ffr_ir_geom_t *g, const float ir_mm[FFR_IR_COUNT], float walls,
                           float *dist_mm, float *nx, float *ny)
{
    const float c4 = ffr_cosf(4.0f * walls), s4 = ffr_sinf(4.0f * walls);
    const float tol = ffr_cosf(4.0f * SQUARE_LINE_TOL_DEG * FFR_DEG);
    int k, found = 0;
    *dist_mm = 65535.0f;
    *nx = 0.0f;
    *ny = 0.0f;
    for (k = 0; k < 6; ++k) {
        int a = WALL_PAIRS[k][0], b = WALL_PAIRS[k][1];
        float fx, fy, d, ca, sa, c2, s2;
        if (!line_reading(cfg, ir_mm[a]) || !line_reading(cfg, ir_mm[b]) || !line_dir(g, a, b, &ca, &sa)) {
            continue;
        }
        /* the line's direction times 4 against the walls' times 4: square
         * (mod 90 degrees) when cos(4 (line - walls)) is near 1 */
        c2 = ca * ca - sa * sa;
        s2 = 2.0f * ca * sa;
        if ((c2 * c2 - s2 * s2) * c4 + 2.0f * c2 * s2 * s4 < tol) {
            continue;
        }
        if (wall_foot(g->hit_x_mm[a], g->hit_y_mm[a], g->hit_x_mm[b], g->hit_y_mm[b], &fx, &fy, &d) && d > 1.0f &&
            d < *dist_mm) {
            *dist_mm = d;
            *nx = fx / d;
            *ny = fy / d;
            found = 1;
        }
    }
    return found;
}

/* A rear ranger at its span's bottom reads a wall within ~8 cm of it:
 * behind the rear face by less than a rear corner swings out turning in
 * place (the default body: 57 mm behind the ranger, 37 mm behind the face,
 * against 41 mm). A wall across behind, unless the front corner ranger on
 * the same side reads within the fold-back span too (a wall along that
 * side, which a move back does not near). The rear pair's chord
 * (shift_back_blocked) needs both rear readings measured, above the
 * bottom: a wall behind at a slant, or a part reading short, brings one to
 * its bottom first (orientation bench start seed 7878: the shift backed
 * 100 mm past where it should have, the right rear ranger at its bottom,
 * and the aim's turn met the wall). */
static int rear_at_bottom_behind(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_ir_geom_t *g = &st->ir_geom;
    uint8_t rear = beams_toward(g, -1.0f, 0.0f, 0.5f);
    int i, j;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (!((rear >> i) & 1) || !ffr_ir_valid(cfg, st->ir_mm[i]) || st->ir_mm[i] > cfg->ir_min_mm + 0.5f) {
            continue;
        }
        for (j = 0; j < FFR_IR_COUNT; ++j) {
            if (g->beam_cos[j] > 0.3f && g->beam_sin[j] * g->beam_sin[i] > 0.0f &&
                (!ffr_ir_valid(cfg, st->ir_mm[j]) || st->ir_mm[j] > FFR_FOLD_MAX_MM)) {
                return 1;
            }
        }
    }
    return 0;
}

/* Room to turn again after the shift, before the aim's turn in place. The
 * shift drives to where a wall across its axis would be at wall_target_mm
 * as the sweep read it; a ranger reading long (a GP2D12 within its
 * datasheet spread reads a wall at 35-45 cm some 20 % long) sends it past
 * that, to within the turning radius of the wall it drove toward (jittered
 * start seed 60: the east wall read 447 mm off, truly 366; the shift ended
 * 141 mm from it and the aim's turn swung a rear corner into it). Now, near
 * that wall, two rangers measure it (ffr_orient_square_wall: a line square
 * to the walls the sweep found): if it is within the turning radius +
 * CLEAR_MARGIN_MM ahead or behind, one straight move away from it (the
 * escape's), then the aim. Once per sweep. Not step 0's rule (every hit, a
 * reading at the span's bottom taken as half of it): a realistic robot's
 * ranger reading short, or two hits across a corner, would move it after
 * most shifts (robots 4, 30 of the realistic sweep). With no such line
 * after a shift backward that a rear ranger at its bottom stopped
 * (rear_at_bottom_behind): SHIFT_BOTTOM_MOVE_MM straight forward. */
void ffr_orient_after_shift(ffr_state_t *st)
{
    ffr_home_orient_t *o = &st->orient;
    float need = ffr_orient_turn_radius_mm(&st->cfg) + CLEAR_MARGIN_MM;
    float d, nx, ny, len;
    uint8_t back;
    if (o->after_shift) {
        return;
    }
    if (ffr_orient_square_wall(&st->cfg, &st->ir_geom, st->ir_mm, o->dir0_rad - st->odo.heading_rad, &d, &nx, &ny)) {
        if (d >= need || ffr_absf(nx) < 0.5f) {
            return;
        }
        /* straight away from the measured wall by the missing room */
        back = nx > 0.0f;
        len = (need - d) / ffr_absf(nx) + 10.0f;
        len = len < ESCAPE_MAX_MM ? len : ESCAPE_MAX_MM;
    } else if (o->reverse && rear_at_bottom_behind(st)) {
        /* a shift backward stopped by a rear ranger at its bottom: no
         * measured line to move off, so a short straight move forward */
        back = 0u;
        len = ffr_clampf(straight_room(st, 0, 0u), 0.0f, SHIFT_BOTTOM_MOVE_MM);
    } else {
        return;
    }
    o->after_shift = 1u;
    straight_leg(st, len, back, 0u);
}

/* A shift driven backward is the sweep's reading of the wall behind from
 * afar: a part reading it long backed the robot to within its turning
 * radius of that wall (+-2.5 cm start seeds 2297, 2377, 3624: 290-310 mm
 * back, both rear rangers at their span's bottom) and the aim's turn met it.
 * It stops where the rear pair's chord, square to the shift (a wall across
 * behind), is within the turning radius of the axle and has come
 * REAR_NEARING_MM nearer than the farthest it read since the heading
 * settled (walls beside, a hallway's, do not come nearer); the look after
 * the shift (ffr_orient_after_shift) then measures that wall and moves
 * off it. Not at the radius + CLEAR_MARGIN_MM: that cut short shifts that
 * had room for the aim (the 2001 plan's jittered start seed 54, 23 mm
 * short; its route then missed a door). It also stops where a rear ranger
 * reaches its span's bottom on a wall across behind (rear_at_bottom_behind):
 * there the chord is not measured. */
static int shift_back_blocked(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_ir_geom_t *g = &st->ir_geom;
    ffr_home_orient_t *o = &st->orient;
    float r, rear, dx, dy;
    int a, b;
    if (rear_at_bottom_behind(st)) {
        return 1;
    }
    if (!rear_pair(st, &a, &b) || ffr_absf(st->odo.heading_rad - o->target_rad) > 5.0f * FFR_DEG) {
        return 0;
    }
    r = pair_chord_room(st, a, b);
    rear = -0.5f * (cfg->ir_x_mm[a] + cfg->ir_x_mm[b]); /* the pair behind the axle */
    dx = g->hit_x_mm[a] - g->hit_x_mm[b];
    dy = g->hit_y_mm[a] - g->hit_y_mm[b];
    if (ffr_absf(dx) > 0.176f * dy) {
        return 0;
    }
    if (o->back_chord_mm >= 65535.0f || r > o->back_chord_mm) {
        o->back_chord_mm = r;
    }
    return r + rear < ffr_orient_turn_radius_mm(cfg) && r < o->back_chord_mm - REAR_NEARING_MM;
}

/* A shift toward a wall across its axis goes by the sweep's reading of that
 * wall from afar: a GP2D12 reads 20-30 % short at 40-80 cm (its datasheet
 * spread, RANGE_SHORT_FRAC), and a wall 78 cm off read as 59 cm left the
 * robot 15 cm short of a corridor's middle, off its line at the mouth,
 * where the wall following's first leg met the jamb (hallway +-2.5 cm
 * start seed 1029; eight starts of that row, docs/robustness.md "A shift
 * toward a wall ends on the front ranger"). Driven forward along the axis
 * (within 15 degrees), the front ranger looks at that wall and reads it
 * nearer, so better, as the robot goes. If it puts the wall more than
 * SHIFT_TOL_MM beyond where the length would stand the body, the shift goes
 * on to where the wall ahead is wall_target_mm off (the stand it is for),
 * as far as a wall read short may be (SHIFT_FAR_FRAC), and only on floor free ahead
 * of the body. Otherwise as before: the length, or front_stop_mm (ending
 * every such shift on the front ranger moved stands that were right by a
 * few cm, and lost a +-5 cm start whole). No reading (the wall beyond the
 * ranger's span): the length. The shift's distance left. */
#define SHIFT_FAR_FRAC (RANGE_SHORT_FRAC / (1.0f - RANGE_SHORT_FRAC))
static float shift_toward(const ffr_state_t *st, float left)
{
    const ffr_home_orient_t *o = &st->orient;
    float f, cap;
    if (o->near_mm >= 65535.0f) {
        return left; /* not toward a wall across, or driven backward (PH_CENTRE) */
    }
    f = ffr_front_now(&st->cfg, &st->odo, st->ir_mm);
    if (f >= 1.0e6f) {
        return left;
    }
    cap = o->goal_mm + SHIFT_FAR_FRAC * o->near_mm - st->odo.dist_mm; /* as far as the wall may be, read short */
    f -= st->cfg.wall_target_mm;
    if (f <= left + SHIFT_TOL_MM || end_room(st, 0, BAND_MARGIN_MM, 0u) <= st->cfg.body_front_mm + ESCAPE_FREE_MM) {
        /* the wall where measured (or nearer: front_stop_mm stops the
         * shift), or on past the length only on floor free ahead of the
         * body, as an escape's */
        return left;
    }
    return f < cap ? f : cap;
}

/* odometry's frame turned by -rot about its origin: `rot` becomes heading 0 */
static void reframe(ffr_odometry_t *odo, float rot)
{
    float c = ffr_cosf(rot);
    float s = ffr_sinf(rot);
    float x = odo->x_mm, y = odo->y_mm;
    odo->x_mm = c * x + s * y;
    odo->y_mm = -s * x + c * y;
    odo->heading_rad -= rot;
    /* the sweep's heading error is the walls' direction measured, not the
     * turn scale's doing: turn_calibration.c counts rotation from here */
    odo->rot_raw_rad = 0.0f;
}

/* the unwrapped heading nearest `heading` that points along `dir` */
static float nearest(float heading, float dir) { return heading + ffr_wrap_pi(dir - heading); }

/* A turn in place at home: quicker than the route's turns (twice the gain,
 * done within 2 degrees without waiting for the spin to settle: the next
 * motion holds the heading anyway). 1 when there. With `settle` (the
 * shift's turn) not while the body still spins faster than
 * QUICK_SPIN_DEG_S: the sweep ends at its full rate, and a shift whose
 * direction lay within 2 degrees of that heading was "there" at once; the
 * body spun on ~30 degrees as the shift began backing, drove off its line
 * toward a wall beside, was cut short there, and the aim from the
 * junction's mouth chose the wrong way (jittered start seeds 5884, 6825).
 * Not for the aim's turn: the route's first leg goes forward, its heading
 * held, and settling there too lost realistic robot 5610 whole
 * (docs/robustness.md, "The shift's turn done while still spinning"). */
static int quick_turn(ffr_state_t *st, float target, int settle)
{
    const ffr_config_t *cfg = &st->cfg;
    float err = target - st->odo.heading_rad;
    float lim = cfg->turn_rate_deg_s * FFR_DEG;
    float w = ffr_clampf(2.0f * cfg->heading_kp * err, -lim, lim);
    if (ffr_absf(err) < QUICK_TOL_DEG * FFR_DEG && (!settle || ffr_turn_spin(cfg, &st->odo) < QUICK_SPIN_DEG_S * FFR_DEG)) {
        return 1;
    }
    if (ffr_absf(w) < 30.0f * FFR_DEG) {
        w = err > 0.0f ? 30.0f * FFR_DEG : -30.0f * FFR_DEG;
    }
    st->cmd_w_rad_s = w;
    return 0;
}

/* the route's first direction from where the robot stands now */
static void aim(ffr_state_t *st)
{
    ffr_home_orient_t *o = &st->orient;
    float cx = st->odo.x_mm - o->x0_mm, cy = st->odo.y_mm - o->y0_mm;
    int k = ffr_orient_aim(o, &st->cfg, o->dir0_rad, st->odo.heading_rad, cx, cy);
    float dir = o->dir0_rad + (float)(k < 0 ? 0 : k) * 0.5f * FFR_PI;
    if (k < 0) {
        /* nothing open: the square direction nearest the one placed in */
        dir = nearest(o->h0_rad, o->dir0_rad);
        while (dir - o->h0_rad > 0.25f * FFR_PI) {
            dir -= 0.5f * FFR_PI;
        }
        while (dir - o->h0_rad < -0.25f * FFR_PI) {
            dir += 0.5f * FFR_PI;
        }
    }
    o->target_rad = nearest(st->odo.heading_rad, dir);
    o->phase = PH_TURN;
}

/* A wall behind passed into fold-back (issue 13, 29 Nov). Backing toward a
 * wall, a ranger looking back reads shorter and shorter until the wall is at
 * its output's peak (8 cm on the GP2D12), and then LONGER as the wall comes
 * nearer still: a move back that watches the reading for a wall near (the
 * rear pair's chord, the end's free floor) sees it recede and drives on into
 * it (orientation bench start seeds 4412 and 8343: a rear ranger peaked and
 * fell back 0.4-0.7 s before the rear corner met the wall). A reading that
 * came down to PASS_MIN_MM or less on this move and has since grown by
 * PASS_RISE_MM is that peak passed; a wall straight behind does not recede
 * as the robot backs toward it. Chosen: a part's peak reads 100-120 mm
 * through the firmware's curve (the datasheet spread's lowest, 2,178 mV:
 * docs/firmware.md), and 6 mm is above the readings' noise there (4 mm
 * stopped moves that needed their length). The probe_mm slots of the
 * rangers looking back that no probe watches hold the shortest reading
 * since the move back began (no room in the state for more: it is at
 * FFR_STATE_MAX). Bits of the rangers that passed their peak. */
#define PASS_MIN_MM 130.0f
#define PASS_RISE_MM 6.0f
/* anchors' bit 7 (its bits 0-4 are the sweep's, one per ranger): this move
 * back is being watched, its shortest readings kept since it began */
#define BACK_WATCH 0x80u
typedef char back_watch_bit_free[(FFR_IR_COUNT < 8) ? 1 : -1];
static uint8_t rear_passed(ffr_state_t *st)
{
    ffr_home_orient_t *o = &st->orient;
    const ffr_config_t *cfg = &st->cfg;
    uint8_t back, passed = 0u;
    int i;
    if (!o->reverse || (o->phase != PH_ESCAPE && o->phase != PH_SHIFT_DRIVE)) {
        /* nothing else on other ticks: the sweep's and the aim's ticks are
         * the firmware's heaviest (docs/pil.md) */
        o->anchors = (uint8_t)(o->anchors & ~BACK_WATCH);
        return 0u;
    }
    back = (uint8_t)(rear_beams(st) & ~o->probed);
    if (!(o->anchors & BACK_WATCH)) {
        o->anchors = (uint8_t)(o->anchors | BACK_WATCH);
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            if ((back >> i) & 1) {
                o->probe_mm[i] = 65535.0f;
            }
        }
    }
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float r = st->ir_mm[i];
        if (!((back >> i) & 1) || !ffr_ir_valid(cfg, r)) {
            continue;
        }
        if (r < o->probe_mm[i]) {
            o->probe_mm[i] = r;
        } else if (o->probe_mm[i] <= PASS_MIN_MM && r >= o->probe_mm[i] + PASS_RISE_MM) {
            passed = (uint8_t)(passed | (1 << i));
        }
    }
    return passed;
}

static void pass_move(ffr_state_t *st, uint8_t passed)
{
    ffr_home_orient_t *o = &st->orient;
    float len = straight_room(st, 0, 0u);
    ffr_stop(st);
    if (o->phase == PH_SHIFT_DRIVE) {
        o->after_shift = 1u;
    }
    fold_move(st, passed, ffr_clampf(len, 0.0f, REAR_FOLD_MOVE_MM), 0u);
}

/* A fold move forward watches its leading end. A front ranger that read
 * within the fold-back span when it began may be folded back itself: a wall
 * converging ahead, a few mm off the front corner, read as 10-13 cm (the
 * rear one on that side, reading alike, then reads its wall as it is).
 * Driven nearer, a folded reading grows (below the GP2D12's 8 cm peak its
 * output falls toward contact), a wall read as it is comes nearer or stays.
 * Grown by LEAD_GROW_MM: the rangers (bit i) so grown, 0 if none. Every
 * fold move forward is watched: the rear fold move's and the one after a
 * rear peak passed on a move back (pass_move). */
static uint8_t lead_grew(const ffr_state_t *st)
{
    const ffr_home_orient_t *o = &st->orient;
    uint8_t lead, m = 0u;
    int i;
    if (o->leg != LEG_FOLD || o->reverse || o->escapes >= ESCAPE_TRIES) {
        /* not a fold move forward, or the last of the moves: a move back may
         * pass a rear peak (pass_move, forward again), and the two would
         * take turns */
        return 0u;
    }
    /* the front rangers it does not move away from, within the span as it began */
    lead = (uint8_t)(front_beams(st) & ~o->probed & ffr_orient_fold_suspects(&st->cfg, o->probe_mm, FFR_FOLD_MAX_MM));
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if ((lead >> i) & 1 && ffr_ir_valid(&st->cfg, st->ir_mm[i]) && st->ir_mm[i] >= o->probe_mm[i] + LEAD_GROW_MM) {
            m = (uint8_t)(m | (1 << i));
        }
    }
    return m;
}

/* Placed in a hallway, the body may stand beside a wall's end: a door's
 * jamb or a hallway's mouth a centimetre or two off its side or behind it,
 * the wall running away between the rangers' beams. No ranger sees it
 * (within the turning circle they read folded back, if at all), and the
 * sweep's turn swings a corner into it within 15-35 degrees. A straight move
 * keeps the body in its own band, and 100 mm forward takes a point beside
 * the axle or behind it out of the turning circle. The step has its own
 * blind spot, a wall's end pointing at the front face off the centre
 * ranger's line; taken always it lost about as many starts as it saved
 * (docs/robustness.md). So only where such an end is likely: a rear ranger
 * reading no wall within HALL_OPEN_MM (open floor behind that side, the
 * body at a mouth or a door), and on the first look only (nothing moved
 * yet), the floor ahead as the rangers see it free.
 *
 * From the home circle, only where the sweep would swing such an end into
 * a front corner: nothing near as read (`side`, ffr_orient_sweep_side, is
 * 0: the sweep turns toward home_wall_side), both rangers of the side it
 * turns toward reading no wall within OPEN_SIDE_MM, and both of the other
 * side reading one (a hallway's far wall along it). That is the body in a
 * hallway by a junction, the outer corner of the block between two open
 * ways 25-50 mm off its side between the beams (the 2004 arena's home
 * beside the middle room's corner): turning toward it brings it to the
 * front corner (156 mm from the axle). Not toward the other side: turning
 * away passes such an end by the rear corner (141 mm), and the step can
 * bring one standing ahead of the axle to beside it (the hallway's rule
 * from home: orientation benches +6 and -4 of 8,000). Nor with no wall
 * along the other side: one wall behind the body may be the only one to go
 * by, and the step takes the body away from it (test
 * a_small_shift_across_the_way_is_not_made). Chosen: 400 mm (300, 400 and
 * 750 measured: docs/robustness.md, "A step before the sweep toward an open
 * side, from home"). 1 when the step starts. */
#define OPEN_SIDE_MM 400.0f
/* the sweep's turn when nothing near decides it: toward home_wall_side
 * (+1 left, -1 right) */
static float default_turn(const ffr_config_t *cfg)
{
    return cfg->home_wall_side == FFR_HOME_WALL_RIGHT ? -1.0f : 1.0f;
}

static int first_step(ffr_state_t *st, int side)
{
    const ffr_config_t *cfg = &st->cfg;
    int i, open = 0;
    if (st->odo.dist_mm > 0.0f || st->orient.escapes != 0u || (cfg->start_area != FFR_START_HALLWAY && side != 0)) {
        return 0; /* before anything else: the first look's tick is among the heaviest (docs/pil.md) */
    }
    if (cfg->start_area == FFR_START_HALLWAY) {
        uint8_t rear = rear_beams(st);
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            open |= (rear >> i) & 1 && reads_open(st, i, HALL_OPEN_MM);
        }
    } else {
        /* one pass, out at the first reading against it (the first look's
         * tick is the firmware's heaviest, docs/pil.md): both rangers of the
         * turning side open, both of the other side on a wall */
        float turn = default_turn(cfg);
        int n = 0, m = 0;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            float across = st->ir_geom.beam_sin[i] * turn;
            if (across > 0.5f) {
                if (!reads_open(st, i, OPEN_SIDE_MM)) {
                    return 0;
                }
                ++n;
            } else if (across < -0.5f) {
                if (reads_open(st, i, OPEN_SIDE_MM)) {
                    return 0;
                }
                ++m;
            }
        }
        open = n > 0 && m > 0;
    }
    if (!open || straight_room(st, 0, 0u) <= HALL_STEP_MM || corner_room(st) < CORNER_FREE_MM + HALL_STEP_MM) {
        return 0;
    }
    straight_leg(st, HALL_STEP_MM, 0u, 0u);
    return 1;
}

/* The sweep's stop for something within the turning circle: away from it
 * (start_escape: `d` mm off in the body's direction (nx, ny)), then the
 * sweep again. A hard stop, not the speed ramp's: at the sweep's full rate
 * the ramp (accel_mm_s2) lets the body turn on ~20 degrees, and a wall's
 * end seen this late is within that (a corner beside the body, in no
 * ranger's beam until the turn brings its wall round). The wheels'
 * references and position integrals cleared, the speed loop brakes on the
 * measured speed at once */
static void sweep_escape(ffr_state_t *st, float d, float nx, float ny)
{
    ffr_stop(st);
    ffr_speed_reset(&st->speed);
    start_escape(st, ffr_orient_turn_radius_mm(&st->cfg) + CLEAR_MARGIN_MM, d, nx, ny);
}

/* A ranger on the side the sweep turns toward come down to its span's
 * bottom as the body turns (issue 13, 2 Dec): a face crossing its beam
 * within ~10 cm, just off that side's corner. Its hit lies outside the
 * turning circle (the corner rangers' shortest hit is ~200 mm off the axle),
 * so the sweep's wall-line test does not stop for it, but the face it
 * belongs to runs on toward the body: a corner of the home hallway's block
 * beside the front corner, a wall behind the rear corner (nominal start
 * seeds 6500, 6779, 7431: the corner met 2-20 degrees of turn later). Only
 * at the bottom (within 0.5 mm of ir_min_mm, as elsewhere here): a part
 * reading 105-110 there took moves the turn did not need and lost more
 * starts than it saved (docs/robustness.md, "A ranger at its bottom in the
 * sweep"). Not on the first SWEEP_BOTTOM_AFTER_DEG: what the rangers read
 * before the turn is the clearance's to judge (clear_step). The ranger (its
 * index), or -1. */
#define SWEEP_BOTTOM_AFTER_DEG 1.0f
/* where the near face is taken to be, off the axle toward that ranger: just
 * inside the front corners' circle (156 mm), so the move away is ~47 mm */
#define SWEEP_BOTTOM_AT_MM 150.0f
/* ... but not for a ranger whose hits run along a wall that passes clear
 * of the turn: the line of its last stretch of hits (ffr_orient_record
 * keeps how far it passes from the axle, in probe_mm, until the ranger's
 * next stretch, a jump or a reading out of the stretches' range) beyond the
 * room a turn needs (turning radius + CLEAR_MARGIN_MM, as the clearance)
 * plus the wall-line test's LINE_MARGIN_MM. A wall across the beam comes
 * down to the bottom as the turn brings the beam square to it, and a part
 * reading short puts a wall 124 mm off at the bottom (realistic robot 5741
 * from the nominal start: the home hallway's south wall, 230 mm off the
 * axle, its line read at 200-206 mm; the stop's escapes cost it 40
 * missions, docs/robustness.md "A ranger at its bottom along a far wall").
 * A face that runs on toward the body has its line within the circle, as
 * has any corner the body could meet on it; no stretch yet: the stop, as
 * before. Lines read at 167-179 mm, just outside the circle, were the
 * corner of a nearer face the last stretch had not reached (nominal start
 * 6151, hallway starts 1056 and 2053): with LINE_MARGIN_MM alone, lost. */
static int sweep_side_at_bottom(const ffr_state_t *st, float sweep)
{
    /* the turning side's rangers: beams within 60 degrees of that side */
    uint8_t side = beams_toward(&st->ir_geom, 0.0f, sweep > 0.0f ? 1.0f : -1.0f, 0.5f);
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if ((side >> i) & 1 && st->ir_mm[i] <= st->cfg.ir_min_mm + 0.5f &&
            !(st->orient.probe_mm[i] > ffr_orient_turn_radius_mm(&st->cfg) + CLEAR_MARGIN_MM + LINE_MARGIN_MM)) {
            return i;
        }
    }
    return -1;
}

int ffr_orient_step(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_home_orient_t *o = &st->orient;
    uint8_t passed = rear_passed(st); /* every tick: it also ends the watch of a move back */
    ffr_stop(st);
    if (o->phase == PH_ESCAPE) {
        float left = o->goal_mm - st->odo.dist_mm;
        uint8_t grew;
        if (passed) {
            pass_move(st, passed);
            return 0;
        }
        grew = lead_grew(st);
        if (grew != 0u) {
            /* its wall is the near one: the move turns back, as far as it
             * came and on as far as the front fold move goes, away from that
             * wall; after it those rangers' readings tell fold-back as after
             * the front fold move (clear_step). Odometry's distance counts
             * both ways, so the few mm the body rolls on forward as it
             * brakes shorten the way back by as much (a hard stop here, as
             * the sweep's, measured no better: docs/robustness.md) */
            fold_leg(st, grew, o->leg_mm - left + FRONT_FOLD_MOVE_MM, 1u, LEG_TURNED);
            return 0;
        }
        if (left > 0.0f && escape_free(st)) {
            float v = ffr_stopping_speed(left, ESCAPE_SPEED_MM_S);
            st->cmd_v_mm_s = o->reverse ? -v : v;
            st->cmd_w_rad_s = leg_yaw(st, st->cmd_v_mm_s, left);
            return 0;
        }
        if (left <= 0.0f && s_first_arc(o)) {
            /* the S's second arc: turning back */
            o->leg = 2u;
            o->target_rad = -o->target_rad;
            o->goal_mm = st->odo.dist_mm + o->leg_mm;
            return 0;
        }
        if (left <= 0.0f && o->leg == 2u) {
            /* straight back along the wall, as far as the wide or plain S
             * goes along it (a first arc begun gently went ~9 cm farther:
             * the robot ends that much along, on floor found free) */
            o->leg = 3u;
            o->reverse ^= 1u;
            o->goal_mm = st->odo.dist_mm + 2.0f * ffr_sinf(o->leg_mm * ffr_absf(o->target_rad)) / ffr_absf(o->target_rad);
            o->target_rad = 0.0f;
            ffr_orient_watch_leg(st);
            return 0;
        }
        /* look again (next tick: the rangers from here); after the shift's
         * move for room, the aim */
        o->phase = o->after_shift ? PH_AIM : PH_CLEAR;
        return 0;
    }
    if (o->phase == PH_PROBE) {
        probe_step(st);
        return 0;
    }
    if (o->phase == PH_CLEAR) {
        uint8_t tries = o->escapes;
        int side;
        /* the fold moves: on the orientation's first look only, and not
         * with the probe built in (it does their job there) */
        uint8_t suspects = FFR_HOME_FOLD_MM > 0.0f || o->escapes > 0u
                               ? 0u
                               : ffr_orient_fold_suspects(cfg, st->ir_mm, FFR_FOLD_MAX_MM);
        if (rear_fold_move(st, suspects) || front_fold_move(st, suspects) || !clear_step(st)) {
            return 0;
        }
        side = ffr_orient_sweep_side(cfg, &st->ir_geom, st->ir_mm);
        if (first_step(st, side)) {
            return 0;
        }
        /* room to turn: the sweep starts from here */
        ffr_orient_reset(o, &st->odo);
        o->escapes = tries;
        o->sweep_side = (int8_t)side;
    }
    if (o->phase == PH_SWEEP) {
        /* toward the side the route wants its wall on: it is usually the way back */
        float sweep = (o->sweep_side != 0 ? (float)o->sweep_side : default_turn(cfg)) * ORIENT_SWEEP_DEG * FFR_DEG;
        float done = ffr_absf(st->odo.heading_rad - o->h0_rad);
        ffr_orient_record(o, cfg, &st->odo, &st->ir_geom, st->ir_mm);
        if (o->near_mm < ffr_orient_turn_radius_mm(cfg) + LINE_MARGIN_MM && o->escapes < ESCAPE_TRIES) {
            /* a wall's line passes within the turning circle: away from it
             * first, then the sweep again */
            float c = ffr_cosf(st->odo.heading_rad), sn = ffr_sinf(st->odo.heading_rad);
            float bx = (c * o->near_x_mm + sn * o->near_y_mm) / o->near_mm;
            float by = (c * o->near_y_mm - sn * o->near_x_mm) / o->near_mm;
            sweep_escape(st, o->near_mm, bx, by);
            return 0;
        }
        if (o->escapes < ESCAPE_TRIES && done > SWEEP_BOTTOM_AFTER_DEG * FFR_DEG) {
            int at_bottom = sweep_side_at_bottom(st, sweep);
            if (at_bottom >= 0) {
                sweep_escape(st, SWEEP_BOTTOM_AT_MM, st->ir_geom.beam_cos[at_bottom], st->ir_geom.beam_sin[at_bottom]);
                return 0;
            }
        }
        if (done < ffr_absf(sweep) - 2.0f * FFR_DEG) {
            /* on at full turn rate past the end: no slowing down to stop there */
            st->cmd_w_rad_s = ffr_turn_yaw(cfg, st->odo.heading_rad, o->h0_rad + 1.5f * sweep);
            return 0;
        }
        if (o->w < SEG_MIN_TOTAL_MM) {
            /* no walls to go by: as placed */
            o->dir0_rad = o->h0_rad;
            o->target_rad = o->h0_rad;
            o->phase = PH_TURN;
        } else {
            o->dir0_rad = ffr_orient_square(o);
            o->phase = PH_CENTRE; /* next tick: one tick's budget for each decision */
        }
        return 0;
    }
    if (o->phase == PH_CENTRE) {
        float dx, dy, toward, cx = st->odo.x_mm - o->x0_mm, cy = st->odo.y_mm - o->y0_mm;
        /* the bins into the walls' frame, once: the centre reads them so,
         * and the aim (next tick or after the shift) */
        ffr_orient_to_walls(o, o->dir0_rad);
        ffr_orient_centre_walls(o, cfg, o->dir0_rad, cx, cy, &dx, &dy, &toward);
        if (FFR_HOME_SKIP_MM > 0.0f && dx * dx + dy * dy > SHIFT_TOL_MM * SHIFT_TOL_MM) {
            int k = ffr_orient_skip(o, cfg, o->dir0_rad, st->odo.heading_rad, cx, cy, dx, dy, FFR_HOME_SKIP_MM);
            if (k >= 0) {
                o->target_rad = nearest(st->odo.heading_rad, o->dir0_rad + (float)k * 0.5f * FFR_PI);
                o->phase = PH_TURN;
                return 0;
            }
        }
        if (dx * dx + dy * dy > SHIFT_TOL_MM * SHIFT_TOL_MM) {
            float dir = ffr_atan2f(dy, dx);
            float fwd = nearest(st->odo.heading_rad, dir);
            float back = nearest(st->odo.heading_rad, dir + FFR_PI);
            o->reverse = ffr_absf(back - st->odo.heading_rad) < ffr_absf(fwd - st->odo.heading_rad);
            o->target_rad = o->reverse ? back : fwd;
            o->goal_mm = ffr_sqrtf(dx * dx + dy * dy);
            /* driven forward toward the wall it goes by: the front ranger
             * ends it (shift_toward; the sweep's bins are free now) */
            o->near_mm = !o->reverse && toward > 0.0f ? toward : 65535.0f;
            o->phase = PH_SHIFT_TURN;
        } else {
            o->phase = PH_AIM;
        }
        return 0;
    }
    if (o->phase == PH_SHIFT_TURN) {
        if (!quick_turn(st, o->target_rad, 1)) {
            return 0;
        }
        ffr_stop(st);
        o->goal_mm += st->odo.dist_mm; /* the shift's length, from here */
        o->back_chord_mm = 65535.0f;
        o->phase = PH_SHIFT_DRIVE;
    }
    if (o->phase == PH_SHIFT_DRIVE) {
        float left = o->goal_mm - st->odo.dist_mm;
        int blocked;
        if (passed) {
            pass_move(st, passed);
            return 0;
        }
        blocked = o->reverse ? shift_back_blocked(st) : ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm;
        left = shift_toward(st, left);
        if (left > 0.0f && !blocked) {
            float v = ffr_stopping_speed(left, cfg->cruise_speed_mm_s);
            ffr_drive_heading(st, o->target_rad, o->reverse ? -v : v);
            return 0;
        }
        ffr_stop(st);
        o->phase = PH_AIM;
        ffr_orient_after_shift(st);
        return 0;
    }
    if (o->phase == PH_AIM) {
        aim(st);
    }
    if (o->phase == PH_TURN) {
        if (!quick_turn(st, o->target_rad, 0)) {
            return 0;
        }
        ffr_stop(st);
        reframe(&st->odo, o->target_rad);
        o->phase = PH_DONE;
    }
    return 1;
}
