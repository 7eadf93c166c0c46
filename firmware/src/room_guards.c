/*
 * The room task's geometry guards (room.c): where the robot stands relative
 * to the doorway it came in by, the wall the door is in, and the walls its
 * rangers see. Pure functions of the state; room.c's phase handlers decide
 * what to do with them. Tested directly in firmware/tests/test_room_guards.c.
 */
#include "ffr_internal.h"

/* contest lines are 2.5 cm wide, walls about 2 cm thick: the door wall's
 * room-side face lies about this far beyond the doorway line's near edge */
#define DOOR_WALL_FACE_MM 25.0f
/* the door's wall is known by odometry (short and reliable inside one room):
 * a corner stops at this share of the rangers' guard_stop_mm from it */
#define DOOR_STOP_SHARE 0.5f
/* the flame's balance (left - right over both) about 20 degrees off the heading */
#define FLAME_AIM_BAL 0.5f
/* the guards' steering: yaw rate (rad/s) per mm a wall is inside guard_side_mm
 * (chosen: 2.1 rad/s for a wall at the body's side with the default 70 mm) */
#define GUARD_YAW_PER_MM 0.03f
/* a ray leaving the scan point must head back toward the doorway line at
 * least this much (cosine to the reversed entry heading): one nearly along
 * the line meets it too far to the side to be the door */
#define DOOR_RAY_BACK_MIN 0.05f
/* the nose this near the doorway line (mm, along the entry heading), or
 * beyond it, is at the door: the line sensor meets the line within a tick
 * or two at approach speed */
#define DOORWAY_NOSE_MM 60.0f
/* clearance kept beyond the body's corner radius for the scan's turn in place */
#define SCAN_MARGIN_MM 35.0f
/* driving in, the heading offset (degrees) per mm a side wall is inside that
 * circle, and its limit (chosen: half a degree a mm edges the robot off the
 * wall within the room_entry_mm drive without steering it into the other side) */
#define SCAN_EDGE_DEG_PER_MM 0.5f
#define SCAN_EDGE_MAX_DEG 20.0f

int ffr_through_door(const ffr_state_t *st, float dir)
{
    const ffr_room_state_t *r = &st->room;
    float ce = ffr_cosf(r->entry_heading_rad);
    float se = ffr_sinf(r->entry_heading_rad);
    float dx = r->scan_x_mm - r->line_x_mm;
    float dy = r->scan_y_mm - r->line_y_mm;
    float depth = dx * ce + dy * se;  /* how far in the scan point is        */
    float lat = -dx * se + dy * ce;   /* and how far to the side of the path */
    float back = -ffr_cosf(dir - r->entry_heading_rad);
    float t;
    if (back <= DOOR_RAY_BACK_MIN || depth <= 0.0f) {
        return 0;
    }
    t = depth / back;
    lat += t * ffr_sinf(dir - r->entry_heading_rad);
    return ffr_absf(lat) < st->cfg.hallway_half_mm;
}

ffr_door_frame_t ffr_door_frame(const ffr_state_t *st)
{
    ffr_door_frame_t f;
    f.c = ffr_cosf(st->odo.heading_rad);
    f.s = ffr_sinf(st->odo.heading_rad);
    f.ce = ffr_cosf(st->room.entry_heading_rad);
    f.se = ffr_sinf(st->room.entry_heading_rad);
    return f;
}

float ffr_depth_in(const ffr_state_t *st, const ffr_door_frame_t *f, float bx, float by, float *lateral)
{
    const ffr_room_state_t *r = &st->room;
    float dx = st->odo.x_mm + f->c * bx - f->s * by - r->line_x_mm;
    float dy = st->odo.y_mm + f->s * bx + f->c * by - r->line_y_mm;
    if (lateral) {
        *lateral = -dx * f->se + dy * f->ce;
    }
    return dx * f->ce + dy * f->se;
}

int ffr_nose_in_doorway(const ffr_state_t *st, const ffr_door_frame_t *f)
{
    float lat;
    float depth = ffr_depth_in(st, f, st->cfg.line_sensor_x_mm, 0.0f, &lat);
    return depth < DOORWAY_NOSE_MM && ffr_absf(lat) < st->cfg.hallway_half_mm;
}

/*
 * The wall the door is in: the robot crossed its doorway line, so odometry
 * knows where that wall runs (through the crossing, square to the entry
 * heading). A candle by that wall is approached along it, and the door's jamb
 * is a thin wall end the rangers may not see: stop before a front corner
 * reaches the wall's line, as if it were seen. Odometry inside one room is
 * short and reliable, hence half the rangers' margin. A front corner nearing
 * the line turns the robot toward running along the wall (a yaw returned, as
 * the rangers' guard does): a candle hugging that wall is then approached
 * beside it instead of nose first, which stopped the robot with the fans out
 * of reach.
 */
float ffr_door_wall_guard(const ffr_state_t *st, const ffr_door_frame_t *f, float bal, int *stop)
{
    const ffr_config_t *cfg = &st->cfg;
    /* only by the door: farther along, the wall is a wall the rangers see, and
     * the odometry heading's error (a few degrees after a scan) grows with the
     * distance from the crossing point */
    const float reach = cfg->hallway_half_mm + cfg->guard_side_mm;
    float w = 0.0f;
    int k;
    for (k = 0; k < 2; ++k) {
        float lat;
        float d = ffr_depth_in(st, f, cfg->body_front_mm, k ? cfg->body_half_width_mm : -cfg->body_half_width_mm, &lat);
        if (ffr_absf(lat) >= reach) {
            continue;
        }
        /* the doorway line lies on the wall's centre line and is first seen at
         * its near edge: the wall's room-side face is about a line width deeper */
        if (d < DOOR_WALL_FACE_MM + DOOR_STOP_SHARE * cfg->guard_stop_mm) {
            *stop = 1;
        } else if (d < DOOR_WALL_FACE_MM + cfg->guard_side_mm) {
            /* left corner (k = 1) near: turn right, and the other way round;
             * less as the turn takes the flame off toward that side, none
             * with it FLAME_AIM_BAL off: the fans must still reach it */
            float push = (DOOR_WALL_FACE_MM + cfg->guard_side_mm - d) * GUARD_YAW_PER_MM;
            float keep = ffr_clampf(1.0f + (k ? -bal : bal) / FLAME_AIM_BAL, 0.0f, 1.0f);
            w += (k ? -push : push) * keep;
        }
    }
    return w;
}

/*
 * The rangers' part of the approach guard: their hit points near the body. Returns a yaw rate
 * that steers away from a wall beside the front half, and sets *stop when a
 * wall is about to touch a front corner. The GP2D12 folds back under 10 cm,
 * so this must act while the wall is still seen, not at contact.
 */
float ffr_ranger_guard(const ffr_state_t *st, int *stop, int *near)
{
    const ffr_config_t *cfg = &st->cfg;
    static const int rangers[3] = {FFR_IR_CF, FFR_IR_LF, FFR_IR_RF};
    float w = 0.0f;
    int k;
    *stop = 0;
    *near = 0;
    for (k = 0; k < 3; ++k) {
        int i = rangers[k];
        float d = st->ir_mm[i];
        float px = st->ir_geom.hit_x_mm[i];
        float py = st->ir_geom.hit_y_mm[i];
        float side_gap, front_gap;
        if (!ffr_ir_valid(cfg, d)) {
            continue;
        }
        side_gap = ffr_absf(py) - cfg->body_half_width_mm;
        front_gap = px - cfg->body_front_mm;
        if (px > 0.0f && side_gap < cfg->guard_side_mm && front_gap < cfg->guard_side_mm) {
            float push = (cfg->guard_side_mm - (side_gap > 0.0f ? side_gap : 0.0f)) * GUARD_YAW_PER_MM;
            if (i != FFR_IR_CF) {
                w += py > 0.0f ? -push : push;
                *near = 1;
            }
            if (side_gap < cfg->guard_stop_mm && front_gap < cfg->guard_stop_mm) {
                *stop = 1;
            }
        }
    }
    return w;
}

float ffr_approach_guard(const ffr_state_t *st, const ffr_door_frame_t *f, float bal, int *stop, int *near)
{
    float w = ffr_ranger_guard(st, stop, near);
    float wd = ffr_door_wall_guard(st, f, bal, stop);
    if (wd != 0.0f) {
        *near = 1;
    }
    return w + wd;
}

/*
 * Leaving: the heading back out of the door is odometry's, and a room's scan
 * (one turn or more in place on slipping tracks) can leave it 10-15 degrees
 * off. A front corner ranger's hit beside the front half, nearer the body's
 * side than guard_side_mm, steers away from it (the approach guard's law),
 * so the robot leaves along the jamb instead of into the wall beyond it.
 */
float ffr_leave_guard(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    static const int rangers[2] = {FFR_IR_LF, FFR_IR_RF};
    float w = 0.0f;
    int k;
    for (k = 0; k < 2; ++k) {
        int i = rangers[k];
        float px = st->ir_geom.hit_x_mm[i];
        float py = st->ir_geom.hit_y_mm[i];
        float side_gap = ffr_absf(py) - cfg->body_half_width_mm;
        if (!ffr_ir_valid(cfg, st->ir_mm[i]) || px <= 0.0f || px - cfg->body_front_mm >= cfg->guard_side_mm
            || side_gap >= cfg->guard_side_mm) {
            continue;
        }
        {
            float push = (cfg->guard_side_mm - (side_gap > 0.0f ? side_gap : 0.0f)) * GUARD_YAW_PER_MM;
            w += py > 0.0f ? -push : push;
        }
    }
    return w;
}

/*
 * The scan turns in place, sweeping a circle of the body's corner radius: a
 * robot that came through the door off-centre and has a side wall closer
 * than that edges away from it while it drives in (a heading offset, so the
 * heading hold still applies).
 */
float ffr_scan_room_offset(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    float need = ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm)
                 + SCAN_MARGIN_MM;
    float off = 0.0f;
    int side;
    for (side = 0; side < 2; ++side) {
        ffr_wall_t w = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, side);
        if (w.valid && w.dist_mm < need) {
            /* left wall: turn right (negative), and the other way round */
            off += (side == FFR_SIDE_LEFT ? -1.0f : 1.0f) * (need - w.dist_mm) * SCAN_EDGE_DEG_PER_MM * FFR_DEG;
        }
    }
    return ffr_clampf(off, -SCAN_EDGE_MAX_DEG * FFR_DEG, SCAN_EDGE_MAX_DEG * FFR_DEG);
}
