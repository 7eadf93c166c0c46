/*
 * The room task's geometry guards (room_guards.c), called directly on a
 * state set by hand: the doorway line crossed at (lx, ly) on the entry
 * heading, the robot's odometry pose, the rangers' readings. Each guard is
 * checked across the room (poses, headings, entry directions), against the
 * geometry worked out here independently.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* A fresh state: default configuration, no walls seen, the doorway line
 * crossed at (lx, ly) heading `entry`, the robot at (x, y) heading `h`. */
static void room_state(ffr_state_t *st, float entry, float lx, float ly, float x, float y, float h)
{
    ffr_config_t cfg;
    ffr_config_default(&cfg);
    ffr_init(st, &cfg);
    st->room.entry_heading_rad = entry;
    st->room.line_x_mm = lx;
    st->room.line_y_mm = ly;
    st->odo.x_mm = x;
    st->odo.y_mm = y;
    st->odo.heading_rad = h;
}

/* (depth, lateral) of the world point (px, py) in the door's frame */
static void door_coords(float entry, float lx, float ly, float px, float py, float *depth, float *lat)
{
    float ce = ffr_cosf(entry), se = ffr_sinf(entry);
    *depth = (px - lx) * ce + (py - ly) * se;
    *lat = -(px - lx) * se + (py - ly) * ce;
}

/* the rangers' readings in st->ir_mm, their hits worked out as ffr_step does */
static void see(ffr_state_t *st, const float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        st->ir_mm[i] = ir[i];
    }
    ffr_ir_geom_update(&st->ir_geom, &st->cfg, st->ir_mm);
}

TEST(depth_in_is_the_body_point_in_the_doors_frame)
{
    int e, k;
    for (e = 0; e < 8; ++e) {
        float entry = -FFR_PI + (float)e * 0.8f;
        for (k = 0; k < 25; ++k) {
            ffr_state_t st;
            ffr_door_frame_t f;
            float h = (float)k * 0.27f, x = 100.0f + 13.0f * (float)k, y = -70.0f + 9.0f * (float)k;
            float bx = 120.0f, by = (k % 2) ? 100.0f : -100.0f;
            float lat, want_d, want_lat;
            room_state(&st, entry, 40.0f, -25.0f, x, y, h);
            f = ffr_door_frame(&st);
            door_coords(entry, 40.0f, -25.0f, x + ffr_cosf(h) * bx - ffr_sinf(h) * by,
                        y + ffr_sinf(h) * bx + ffr_cosf(h) * by, &want_d, &want_lat);
            CHECK_NEAR(ffr_depth_in(&st, &f, bx, by, &lat), want_d, 1e-2);
            CHECK_NEAR(lat, want_lat, 1e-2);
            CHECK(ffr_depth_in(&st, &f, bx, by, NULL) == ffr_depth_in(&st, &f, bx, by, &lat));
        }
    }
}

TEST(through_door_is_a_ray_back_across_the_doorway)
{
    /* scan points 100..600 mm in, up to 150 mm off the path, every ray
     * direction, several entry headings: through the door exactly when the
     * ray heads back toward the line and meets it within half a hallway */
    int e, p, a, through = 0, not_through = 0;
    for (e = 0; e < 4; ++e) {
        float entry = (float)e * 1.3f - 2.0f;
        for (p = 0; p < 6; ++p) {
            float depth = 100.0f + 100.0f * (float)p;
            float off = -150.0f + 60.0f * (float)p;
            for (a = 0; a < 72; ++a) {
                ffr_state_t st;
                float dir = entry + (float)a * 5.0f * FFR_DEG + 0.01f;
                float rel = dir - entry;
                float back = -ffr_cosf(rel);
                int want = 0;
                room_state(&st, entry, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
                st.room.scan_x_mm = depth * ffr_cosf(entry) - off * ffr_sinf(entry);
                st.room.scan_y_mm = depth * ffr_sinf(entry) + off * ffr_cosf(entry);
                if (back > 0.05f) {
                    float cross = off + depth / back * ffr_sinf(rel); /* where it meets the line */
                    if (cross > -st.cfg.hallway_half_mm + 1.0f && cross < st.cfg.hallway_half_mm - 1.0f) {
                        want = 1;
                    } else if (cross > -st.cfg.hallway_half_mm - 1.0f && cross < st.cfg.hallway_half_mm + 1.0f) {
                        continue; /* on the jamb within rounding: either */
                    }
                }
                CHECK(ffr_through_door(&st, dir) == want);
                through += want;
                not_through += !want;
            }
        }
    }
    CHECK(through > 50 && not_through > 500); /* both sides were tried */
    {
        /* a scan point not in the room (not past the line): never */
        ffr_state_t st;
        room_state(&st, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
        st.room.scan_x_mm = -50.0f;
        CHECK(!ffr_through_door(&st, FFR_PI));
    }
}

TEST(nose_in_doorway_by_the_line_and_within_the_hallway)
{
    int e, k;
    for (e = 0; e < 4; ++e) {
        float entry = (float)e * FFR_PI / 2.0f + 0.2f;
        for (k = 0; k < 40; ++k) {
            /* facing back out, the nose (line sensor) at depth 0..390 mm,
             * lateral offsets within and beyond the hallway */
            float nose_depth = 10.0f * (float)k;
            float lat = (k % 3 == 0) ? 0.0f : (k % 3 == 1 ? 150.0f : 300.0f);
            float h = entry + FFR_PI;
            float xs = 0.0f, ys = 0.0f;
            ffr_state_t st;
            ffr_door_frame_t f;
            float ox, oy;
            room_state(&st, entry, xs, ys, 0.0f, 0.0f, h);
            /* the origin: the nose is line_sensor_x_mm ahead, toward the door */
            ox = (nose_depth + st.cfg.line_sensor_x_mm) * ffr_cosf(entry) - lat * ffr_sinf(entry);
            oy = (nose_depth + st.cfg.line_sensor_x_mm) * ffr_sinf(entry) + lat * ffr_cosf(entry);
            st.odo.x_mm = ox;
            st.odo.y_mm = oy;
            f = ffr_door_frame(&st);
            if (nose_depth != 60.0f) { /* 60 mm (DOORWAY_NOSE_MM): on the edge, either within rounding */
                CHECK(ffr_nose_in_doorway(&st, &f) == (nose_depth < 60.0f && lat < st.cfg.hallway_half_mm));
            }
        }
    }
}

TEST(door_wall_guard_pushes_off_then_stops_by_the_doors_wall)
{
    /* running along the door's wall, corner toward it: no push far from it,
     * a push away from it growing as the corner nears, a stop at last; and
     * nothing beyond the door's reach along the wall */
    float entry = 0.3f;
    int side, k;
    for (side = 0; side < 2; ++side) {
        /* heading: back toward the wall, 60 degrees off, so the left (side 1)
         * or right (side 0) front corner leads */
        float h = entry + FFR_PI + (side ? -60.0f : 60.0f) * FFR_DEG;
        float prev = 0.0f;
        int stopped_at = -1;
        for (k = 0; k < 60; ++k) {
            ffr_state_t st;
            ffr_door_frame_t f;
            int stop = 0;
            float w, corner_depth, lat, by;
            float depth = 300.0f - 5.0f * (float)k; /* the origin's depth */
            room_state(&st, entry, 0.0f, 0.0f, depth * ffr_cosf(entry), depth * ffr_sinf(entry), h);
            f = ffr_door_frame(&st);
            by = side ? st.cfg.body_half_width_mm : -st.cfg.body_half_width_mm;
            corner_depth = ffr_depth_in(&st, &f, st.cfg.body_front_mm, by, &lat);
            w = ffr_door_wall_guard(&st, &f, 0.0f, &stop);
            if (corner_depth >= 25.0f + st.cfg.guard_side_mm) {
                CHECK(w == 0.0f && !stop);
            } else if (corner_depth >= 25.0f + 0.5f * st.cfg.guard_stop_mm) {
                /* left corner near: turn right (negative), and the other way round */
                CHECK(side ? w < 0.0f : w > 0.0f);
                CHECK(ffr_absf(w) >= ffr_absf(prev));
                CHECK(!stop);
            } else {
                CHECK(stop);
                if (stopped_at < 0) {
                    stopped_at = k;
                }
            }
            prev = w;
        }
        CHECK(stopped_at > 0);
    }
    {
        /* the same pose far along the wall (beyond hallway + guard_side): nothing */
        ffr_state_t st;
        ffr_door_frame_t f;
        int stop = 0;
        float lat_far = 230.0f + 70.0f + 300.0f;
        room_state(&st, 0.0f, 0.0f, 0.0f, 40.0f, lat_far, FFR_PI);
        f = ffr_door_frame(&st);
        CHECK(ffr_door_wall_guard(&st, &f, 0.0f, &stop) == 0.0f && !stop);
    }
}

TEST(door_wall_guard_keeps_the_flame_in_view)
{
    /* the push toward a side the flame is off to shrinks with the balance
     * and is gone at FLAME_AIM_BAL (0.5) */
    ffr_state_t st;
    ffr_door_frame_t f;
    int stop = 0, k;
    float prev;
    float h = FFR_PI - 60.0f * FFR_DEG; /* left corner leads: the push is right (negative) */
    room_state(&st, 0.0f, 0.0f, 0.0f, 215.0f, 0.0f, h); /* the left corner ~68 mm in */
    f = ffr_door_frame(&st);
    prev = ffr_door_wall_guard(&st, &f, 0.0f, &stop);
    CHECK(prev < 0.0f && !stop);
    for (k = 1; k <= 10; ++k) {
        float bal = 0.05f * (float)k; /* flame more and more to the left */
        float w = ffr_door_wall_guard(&st, &f, bal, &stop);
        CHECK(w <= 0.0f && w >= prev);
        prev = w;
    }
    CHECK(prev == 0.0f);
    /* the flame to the right: the full push */
    CHECK(ffr_door_wall_guard(&st, &f, -0.3f, &stop) == ffr_door_wall_guard(&st, &f, 0.0f, &stop));
}

TEST(approach_guard_steers_off_a_side_wall_and_stops_at_contact)
{
    int side, k;
    for (side = 0; side < 2; ++side) {
        int i = side ? FFR_IR_LF : FFR_IR_RF;
        int was_stop = 0;
        for (k = 0; k < 40; ++k) {
            ffr_state_t st;
            ffr_door_frame_t f;
            float ir[FFR_IR_COUNT];
            int stop = 1, near = 1;
            float w, gap, front;
            room_state(&st, 0.0f, -2000.0f, 0.0f, 0.0f, 0.0f, 0.0f); /* the door far behind */
            rig_no_walls(&st.cfg, ir);
            ir[i] = 400.0f - 9.0f * (float)k;
            see(&st, ir);
            f = ffr_door_frame(&st);
            w = ffr_approach_guard(&st, &f, 0.0f, &stop, &near);
            gap = ffr_absf(st.ir_geom.hit_y_mm[i]) - st.cfg.body_half_width_mm;
            front = st.ir_geom.hit_x_mm[i] - st.cfg.body_front_mm;
            if (st.ir_geom.hit_x_mm[i] > 0.0f && gap < st.cfg.guard_side_mm && front < st.cfg.guard_side_mm) {
                CHECK(near);
                CHECK(side ? w < 0.0f : w > 0.0f); /* away from the wall */
                CHECK(stop == (gap < st.cfg.guard_stop_mm && front < st.cfg.guard_stop_mm));
                was_stop |= stop;
            } else {
                CHECK(!near && !stop && w == 0.0f);
            }
        }
        CHECK(was_stop);
    }
    {
        /* a wall straight ahead (centre ranger): no steering, not "beside", a stop when close */
        ffr_state_t st;
        ffr_door_frame_t f;
        float ir[FFR_IR_COUNT];
        int stop = 0, near = 1;
        room_state(&st, 0.0f, -2000.0f, 0.0f, 0.0f, 0.0f, 0.0f);
        rig_no_walls(&st.cfg, ir);
        ir[FFR_IR_CF] = st.cfg.body_front_mm - st.cfg.ir_x_mm[FFR_IR_CF] + 10.0f;
        see(&st, ir);
        f = ffr_door_frame(&st);
        CHECK(ffr_approach_guard(&st, &f, 0.0f, &stop, &near) == 0.0f);
        CHECK(stop && !near);
    }
}

TEST(leave_guard_steers_a_front_corner_off_a_wall)
{
    int side, k, pushed = 0;
    for (side = 0; side < 2; ++side) {
        int i = side ? FFR_IR_LF : FFR_IR_RF;
        for (k = 0; k < 40; ++k) {
            ffr_state_t st;
            float ir[FFR_IR_COUNT];
            float w, gap, front;
            room_state(&st, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
            rig_no_walls(&st.cfg, ir);
            ir[i] = 400.0f - 9.0f * (float)k;
            see(&st, ir);
            w = ffr_leave_guard(&st);
            gap = ffr_absf(st.ir_geom.hit_y_mm[i]) - st.cfg.body_half_width_mm;
            front = st.ir_geom.hit_x_mm[i] - st.cfg.body_front_mm;
            if (st.ir_geom.hit_x_mm[i] > 0.0f && gap < st.cfg.guard_side_mm && front < st.cfg.guard_side_mm) {
                CHECK(side ? w < 0.0f : w > 0.0f);
                pushed++;
            } else {
                CHECK(w == 0.0f);
            }
        }
    }
    CHECK(pushed > 4);
    {
        /* nothing seen: nothing */
        ffr_state_t st;
        float ir[FFR_IR_COUNT];
        room_state(&st, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
        rig_no_walls(&st.cfg, ir);
        see(&st, ir);
        CHECK(ffr_leave_guard(&st) == 0.0f);
    }
}

TEST(scan_room_offset_edges_away_from_a_near_side_wall)
{
    /* a side wall from 60 to 400 mm: away from it inside the corners'
     * circle + margin, more the nearer, never beyond 20 degrees; nothing
     * outside it */
    int side, k;
    for (side = 0; side < 2; ++side) {
        float prev = 0.0f;
        for (k = 0; k < 35; ++k) {
            ffr_state_t st;
            float ir[FFR_IR_COUNT];
            rig_walls_t walls = {0};
            float dist = 400.0f - 10.0f * (float)k;
            float need, off;
            int i;
            room_state(&st, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
            walls.left_y = side ? dist : 5000.0f;
            walls.right_y = side ? -5000.0f : -dist;
            for (i = 0; i < FFR_IR_COUNT; ++i) {
                ir[i] = rig_beam_mm(&st.cfg, &walls, i, 0.0f, 0.0f, 0.0f);
            }
            see(&st, ir);
            need = ffr_sqrtf(st.cfg.body_front_mm * st.cfg.body_front_mm
                             + st.cfg.body_half_width_mm * st.cfg.body_half_width_mm) + 35.0f;
            off = ffr_scan_room_offset(&st);
            CHECK(ffr_absf(off) <= 20.0f * FFR_DEG + 1e-6f);
            if (dist > need + 5.0f) {
                CHECK(off == 0.0f);
            } else if (dist < need - 5.0f) {
                CHECK(side ? off < 0.0f : off > 0.0f); /* left wall: turn right */
                CHECK(ffr_absf(off) >= ffr_absf(prev));
            }
            prev = off;
        }
        CHECK(ffr_absf(prev) > 5.0f * FFR_DEG);
    }
}

SUITE(room_guards,
      TEST_REF(depth_in_is_the_body_point_in_the_doors_frame),
      TEST_REF(through_door_is_a_ray_back_across_the_doorway),
      TEST_REF(nose_in_doorway_by_the_line_and_within_the_hallway),
      TEST_REF(door_wall_guard_pushes_off_then_stops_by_the_doors_wall),
      TEST_REF(door_wall_guard_keeps_the_flame_in_view),
      TEST_REF(approach_guard_steers_off_a_side_wall_and_stops_at_contact),
      TEST_REF(leave_guard_steers_a_front_corner_off_a_wall),
      TEST_REF(scan_room_offset_edges_away_from_a_near_side_wall));
