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
 */
#include "ffr_internal.h"

/* a wall alongside keeps its distance to the side within this, mm */
#define REAR_LAT_DRIFT_MM 60.0f
/* the front ranger's hit jumping out this far to the side of the wall it was
 * following is past that wall's end (through a door, across a junction), even
 * when it still counts as beside; slow drift is followed at this share per tick */
#define FRONT_JUMP_MM 70.0f
#define FRONT_LAT_FOLLOW 0.2f

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
    }
}

void ffr_openings_update(ffr_openings_t *op, const ffr_config_t *cfg, const ffr_ir_geom_t *g,
                         const float ir_mm[FFR_IR_COUNT], float dist_mm, float step_mm)
{
    int side;
    for (side = 0; side < 2; ++side) {
        int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
        /* a wall beside the robot, not one across an opening (wall_follow.c);
         * fx, rx: how far ahead the hits are, fy, ry: to the side */
        float fx = 0.0f, fy = 0.0f, rx = 0.0f, ry = 0.0f;
        int front = ffr_hit_beside(cfg, g, ir_mm, f, &fx, &fy);
        int rear = ffr_hit_beside(cfg, g, ir_mm, r, &rx, &ry);
        if (front) {
            float lat = ffr_absf(fy);
            if (op->front_lat_mm[side] < 0.0f) {
                op->front_lat_mm[side] = lat;
            } else if (lat - op->front_lat_mm[side] > FRONT_JUMP_MM) {
                front = 0; /* beyond the wall's end: keep its distance for a wall that resumes */
            } else {
                op->front_lat_mm[side] += FRONT_LAT_FOLLOW * (lat - op->front_lat_mm[side]);
            }
        }
        if (rear) {
            float lat = ffr_absf(ry);
            if (op->rear_lat0_mm[side] < 0.0f) {
                op->rear_lat0_mm[side] = lat;
            } else if (ffr_absf(lat - op->rear_lat0_mm[side]) > REAR_LAT_DRIFT_MM) {
                op->rear_ok[side] = 0; /* not a wall alongside: for good, this step */
            }
            op->rear_open_mm[side] = 0.0f;
            op->rear_at_mm[side] = dist_mm + rx;
        } else {
            op->rear_open_mm[side] += step_mm;
        }
        rear = rear && op->rear_ok[side];
        if (front || rear) {
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
                }
            }
        }
    }
}

int ffr_opening(const ffr_openings_t *op, int side) { return op->opened[side] != 0; }
