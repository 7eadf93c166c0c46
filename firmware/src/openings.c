/*
 * Side openings: a wall seen on one side for wall_seen_mm of travel, then
 * gone for open_confirm_mm; latched until the next route step. The front
 * corner ranger looks ahead, so where the wall ends is known: its last hit
 * point, ahead of the origin. At a junction the corner rangers end up seeing
 * the junction's own corners, so what they saw on the way in is what counts.
 *
 * A step that starts close to the wall's end (just after a turn) may give the
 * front ranger too little of the wall to see; the rear ranger, looking back
 * at the wall the robot is passing, counts as seeing it too, and then its
 * own last hit point (behind the origin) marks the wall's end once it opens.
 * Only a wall the robot passes along: one whose distance to the side stays
 * put; a wall across a junction behind the robot recedes and does not count.
 *
 * In a route step that ends at this side's opening (FOLLOW ... OPEN_L/R:
 * pend_side, from route.c) such a step's opening is pending once the front ranger has read open for
 * open_confirm_mm with the wall seen by the rear one alone (FRONT_PAST_END):
 * the front is past the wall's end, in the opening. The rear ranger looks
 * back ~20-25 cm, so it leaves the wall only when the robot is that far into
 * the opening; by then the front ranger may already see the opening's far
 * side (a 46 cm hallway), which is no wall beside this one. So while pending
 * a front hit neither cancels the opening nor moves its end, and the rear
 * ranger leaving the wall (open, or its hits no longer alongside) opens it
 * at the rear's last hit on the wall. But a front hit in line with the
 * rear ranger's wall (its distance to the side within REAR_LAT_DRIFT_MM of
 * the rear's) before that is the same wall going on (the rear ranger on a
 * door's jamb, the front one having looked through a gap): no end, the plain
 * rule again. Only there: the explorer's legs (a
 * hallway start) and a route step's other side keep the plain rule, the
 * front ranger's far-side hit cancelling the opening (with pending there the
 * arbitrary-start hallway guard lost 23 of 391 and 51 of 658 missions:
 * docs/robustness.md).
 */
#include "ffr_internal.h"

/* a wall alongside keeps its distance to the side within this, mm */
#define REAR_LAT_DRIFT_MM 60.0f
/* ... and only the rear ranger's hits within this of its first count toward
 * wall_seen_mm. A wall across behind the robot recedes from the rear
 * ranger's 135-degree beam by 1 mm to the side per mm of travel: with
 * REAR_LAT_DRIFT_MM alone it counted for the first 60 mm, and wall_seen_mm
 * is 60 (2001 plan, +-2.5 cm jitter, seeds 66, 72, 83: leaving room 2, the
 * west outer wall behind was "seen" on the right, and the step to the
 * corridor ended after 68 mm). Chosen: half of wall_seen_mm, above the
 * rangers' noise on a wall alongside (a few mm) */
#define REAR_SEEN_DRIFT_MM 30.0f
/* the front ranger's hit jumping out this far to the side of the wall it was
 * following is past that wall's end (through a door, across a junction), even
 * when it still counts as beside; slow drift is followed at this share per tick */
#define FRONT_JUMP_MM 70.0f
#define FRONT_LAT_FOLLOW 0.2f
/* From a hallway start (the explorer's legs), the front corner ranger's
 * first hit of a step this much farther to the side than the wall the rear
 * ranger passes along (its first hit's) is seen through an opening in that
 * wall, not the wall: a door's far side, a room's wall beyond it (+-2.5 cm
 * hallway start seed 2415: a probe begun past the wall's end for the front
 * ranger, its first hit 385 mm to the side against ~220, through the
 * bottom-right room's door; taken for the wall, it put the wall's end 30 cm
 * past the door's near jamb, and the probe met the far one). No wall for the
 * front ranger then, and the rear ranger's end marks the opening. Only the
 * first: after it the front ranger's own wall is the measure (FRONT_JUMP_MM).
 * Chosen: 120 mm, above the 60 mm two parts' spread puts between their
 * readings of one wall; any later hit so far out (a wall stepping out) lost
 * whole nominal hallway starts (docs/robustness.md, "A front hit through an
 * opening is no wall's end"). The route's legs keep the plain rule. */
#define THROUGH_MM 120.0f
/* ffr_openings_t.front_saw: the front ranger saw no wall this step but has
 * read open past the wall the rear ranger sees (a pending opening, above) */
#define FRONT_PAST_END 2u

void ffr_openings_reset(ffr_openings_t *op)
{
    int i;
    for (i = 0; i < 2; ++i) {
        op->seen[i] = 0;
        op->opened[i] = 0;
        op->front_saw[i] = 0;
        op->rear_ok[i] = 1;
        op->rear_lat0_mm[i] = -1.0f;
        op->front_lat_mm[i] = -1.0f;
        op->seen_mm[i] = 0.0f;
        op->open_mm[i] = 0.0f;
        op->rear_open_mm[i] = 0.0f;
        op->open_at_mm[i] = 0.0f;
        op->rear_at_mm[i] = 0.0f;
        op->since_open_mm[i] = 1.0e9f; /* never, in this step */
        op->gap_open[i] = 0;
        op->gaps[i] = 0;
        op->gap_track[i] = 0;
        op->gap_since_mm[i] = 0.0f;
        op->gap_run_mm[i] = 0.0f;
        op->gap_first_mm[i] = 0.0f;
        op->gap_end_mm[i] = 0.0f;
    }
}

/* Whole openings on one side, by the front corner ranger alone: a run of
 * open readings (open_confirm_mm, a missing reading counting half as above)
 * then a run of wall hits beside (wall_seen_mm) is one opening, ending where
 * the wall after it begins (the first hit of the run, then its nearer hits
 * on the same face: gap_refine). The ranger looks ahead at 45 degrees, so
 * the first hit beside after an opening is the far wall's face at the
 * opening's far edge, and its distance ahead puts that edge. A side open
 * from the step's start counts as an opening once a wall follows: a step
 * that begins in a door or a junction counts it. */
/* a later hit on the far wall is taken for its edge when it is within half
 * the travel since the last one taken of that one: the hits on a wall
 * across (the edge's face) stay put as the robot comes nearer, each from a
 * shorter range (a GP2D12 part's error shrinks with the range), while hits
 * on a wall alongside move on with the robot (by all of the travel) and are
 * not taken */

static void gap_refine(ffr_openings_t *op, int side, float *edge, float at_mm, float step_mm)
{
    op->gap_since_mm[side] += step_mm;
    if (ffr_absf(at_mm - *edge) <= 0.5f * op->gap_since_mm[side]) {
        *edge = at_mm;
        op->gap_since_mm[side] = 0.0f;
    }
}

static void gap_update(ffr_openings_t *op, const ffr_config_t *cfg, int side, int wall, int valid, float at_mm,
                       float step_mm)
{
    if (wall) {
        if (op->gap_open[side]) {
            if (op->gap_run_mm[side] <= 0.0f) {
                op->gap_first_mm[side] = at_mm;
                op->gap_since_mm[side] = 0.0f;
            } else {
                gap_refine(op, side, &op->gap_first_mm[side], at_mm, step_mm);
            }
            op->gap_run_mm[side] += step_mm;
            if (op->gap_run_mm[side] >= cfg->wall_seen_mm) {
                op->gap_end_mm[side] = op->gap_first_mm[side];
                if (op->gaps[side] < 255u) {
                    op->gaps[side] = (uint8_t)(op->gaps[side] + 1u);
                }
                op->gap_open[side] = 0;
                op->gap_run_mm[side] = 0.0f;
                op->gap_track[side] = 1;
            }
        } else {
            if (op->gap_track[side]) {
                /* the last opening's far edge, seen nearer */
                gap_refine(op, side, &op->gap_end_mm[side], at_mm, step_mm);
            }
            op->gap_run_mm[side] = 0.0f;
        }
    } else if (op->gap_open[side]) {
        op->gap_run_mm[side] = 0.0f; /* the wall's run broke: it was not one yet */
    } else {
        op->gap_run_mm[side] += valid ? step_mm : 0.5f * step_mm;
        if (op->gap_run_mm[side] >= cfg->open_confirm_mm) {
            op->gap_open[side] = 1;
            op->gap_track[side] = 0;
            op->gap_run_mm[side] = 0.0f;
        }
    }
}

void ffr_openings_update(ffr_openings_t *op, const ffr_config_t *cfg, const ffr_ir_geom_t *g,
                         const float ir_mm[FFR_IR_COUNT], float dist_mm, float step_mm, int pend_side)
{
    int side;
    for (side = 0; side < 2; ++side) {
        int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
        /* a wall beside the robot, not one across an opening (wall_follow.c);
         * fx, rx: how far ahead the hits are, fy, ry: to the side */
        float fx = 0.0f, fy = 0.0f, rx = 0.0f, ry = 0.0f;
        int rear_still = 0; /* the rear ranger's hit as far to the side as its first */
        int front = ffr_hit_beside(cfg, g, ir_mm, f, &fx, &fy);
        int rear = ffr_hit_beside(cfg, g, ir_mm, r, &rx, &ry);
        if (front) {
            float lat = ffr_absf(fy);
            if (op->front_lat_mm[side] < 0.0f) {
                if (cfg->start_area == FFR_START_HALLWAY && op->rear_ok[side] && op->rear_lat0_mm[side] >= 0.0f &&
                    lat - op->rear_lat0_mm[side] > THROUGH_MM) {
                    front = 0; /* its first hit, far beyond the rear ranger's wall: seen through an opening in it */
                } else {
                    op->front_lat_mm[side] = lat;
                }
            } else if (lat - op->front_lat_mm[side] > FRONT_JUMP_MM) {
                front = 0; /* beyond the wall's end: keep its distance for a wall that resumes */
            } else {
                op->front_lat_mm[side] += FRONT_LAT_FOLLOW * (lat - op->front_lat_mm[side]);
            }
        }
        if (rear) {
            float drift;
            if (op->rear_lat0_mm[side] < 0.0f) {
                op->rear_lat0_mm[side] = ffr_absf(ry);
            }
            drift = ffr_absf(ffr_absf(ry) - op->rear_lat0_mm[side]);
            if (drift > REAR_LAT_DRIFT_MM) {
                op->rear_ok[side] = 0; /* not a wall alongside: for good, this step */
            }
            rear_still = drift <= REAR_SEEN_DRIFT_MM;
            if (op->rear_ok[side] || op->front_saw[side] != FRONT_PAST_END) {
                /* pending, the last hit on the wall alongside is kept */
                op->rear_open_mm[side] = 0.0f;
                op->rear_at_mm[side] = dist_mm + rx;
            } else {
                op->rear_open_mm[side] += step_mm;
            }
        } else {
            op->rear_open_mm[side] += step_mm;
        }
        rear = rear && op->rear_ok[side];
        if (op->front_saw[side] == FRONT_PAST_END && !op->opened[side] && front
            && ffr_absf(fy) - op->rear_lat0_mm[side] < REAR_LAT_DRIFT_MM) {
            op->front_saw[side] = 1; /* the wall goes on ahead, in line with the rear's: no end */
        }
        if (op->front_saw[side] == FRONT_PAST_END) {
            /* pending: the rear ranger's leaving the wall decides */
            if (!op->opened[side] && (!op->rear_ok[side] || op->rear_open_mm[side] >= cfg->open_confirm_mm)) {
                op->opened[side] = 1;
                op->open_at_mm[side] = op->rear_at_mm[side];
            }
            continue;
        }
        if (front || (rear && rear_still)) {
            op->seen_mm[side] += step_mm;
            if (op->seen_mm[side] >= cfg->wall_seen_mm) {
                op->seen[side] = 1;
            }
        } else if (!op->seen[side]) {
            op->seen_mm[side] = 0.0f;
        }
        if (front) {
            op->front_saw[side] = 1;
            op->open_mm[side] = 0.0f;
            op->since_open_mm[side] += step_mm;
            if (!op->opened[side]) {
                /* where the wall ends if the next reading is open: the hit point ahead */
                op->open_at_mm[side] = dist_mm + fx;
            }
        } else {
            /* no reading at all counts half: a far wall seen through an
             * opening is an opening at once, a dropout of a sample or two
             * (a GP2D12 sample lasts ~12 mm of travel) is not */
            op->open_mm[side] += ffr_ir_valid(cfg, ir_mm[f]) ? step_mm : 0.5f * step_mm;
            op->since_open_mm[side] = 0.0f;
            if (op->seen[side] && !op->opened[side] && op->open_mm[side] >= cfg->open_confirm_mm) {
                if (op->front_saw[side]) {
                    op->opened[side] = 1;
                } else if (op->rear_ok[side] && op->rear_open_mm[side] >= cfg->open_confirm_mm) {
                    /* only the rear ranger saw the wall: it ended where that one last hit it */
                    op->opened[side] = 1;
                    op->open_at_mm[side] = op->rear_at_mm[side];
                } else if (op->rear_ok[side] && side == pend_side) {
                    op->front_saw[side] = FRONT_PAST_END; /* the rear ranger still on it */
                }
            }
        }
    }
}

int ffr_opening(const ffr_openings_t *op, int side) { return op->opened[side] != 0; }

void ffr_opening_forget(ffr_openings_t *op, int side)
{
    op->opened[side] = 0;
    op->seen[side] = 0;
    op->seen_mm[side] = 0.0f;
}

void ffr_gaps_update(ffr_openings_t *op, const ffr_config_t *cfg, const ffr_ir_geom_t *g,
                     const float ir_mm[FFR_IR_COUNT], float dist_mm, float step_mm, float yaw_rad)
{
    /* a hit's distance along the corridor: the robot yawed by yaw_rad off
     * it puts a hit to the side ahead or behind of where the robot frame's x
     * says (9 degrees: 5 cm at the 35 cm a far edge is first seen aside) */
    float c = ffr_cosf(yaw_rad);
    float sn = ffr_sinf(yaw_rad);
    int side;
    for (side = 0; side < 2; ++side) {
        int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        float fx = 0.0f, fy = 0.0f;
        int wall = ffr_hit_beside(cfg, g, ir_mm, f, &fx, &fy);
        gap_update(op, cfg, side, wall, ffr_ir_valid(cfg, ir_mm[f]), dist_mm + fx * c - fy * sn, step_mm);
    }
}

int ffr_gap(const ffr_openings_t *op, int side, uint8_t n) { return op->gaps[side] >= (n > 0u ? n : 1u); }

float ffr_gap_middle_mm(const ffr_openings_t *op, const ffr_config_t *cfg, int side)
{
    /* half a hallway before the far edge (not the middle of the two edges:
     * the wall before the opening is last hit late, the ranger's beam being
     * wide, so a middle taken from it fell late; docs/firmware.md) */
    return op->gap_end_mm[side] - cfg->hallway_half_mm;
}

float ffr_open_middle_mm(const ffr_openings_t *op, const ffr_config_t *cfg, int side)
{
    float goal = op->open_at_mm[side] + cfg->hallway_half_mm;
    /* a gap closed beyond the wall's end (gap_end past open_at) is this
     * opening's far edge: the near edge, the front corner ranger's last hit
     * on the wall before, is late by as much as the far edge, its first hit
     * on what follows, is early (the beam's width either way), so their
     * middle is the opening's */
    if (op->gap_end_mm[side] > op->open_at_mm[side]) {
        float mid = 0.5f * (op->open_at_mm[side] + op->gap_end_mm[side]);
        if (mid < goal) {
            goal = mid;
        }
    }
    return goal;
}
