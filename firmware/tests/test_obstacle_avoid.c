/*
 * Obstacles in a room (obstacle_avoid.c), called directly: the bit grid
 * (mark, look up, nearest), the rangers' hits put into it in odometry's frame,
 * the corridor the body sweeps toward the flame, and the detour's choice of
 * heading. Poses, headings and box places are drawn over the whole room from
 * a fixed-seed generator; the expected values are worked out here.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

#define CELL 64.0f /* obstacle_avoid.c OBST_CELL_MM */
#define HALF (0.5f * (float)FFR_OBST_CELLS * CELL) /* the grid's half side */
/* the detour looks along one corridor a tick (the straight one, then the
 * search's headings, 5 steps each way): asked this many times from one pose,
 * it has settled */
#define SETTLE 13

/* a fixed-seed generator: uniform in [lo, hi) */
static float draw(uint32_t *s, float lo, float hi)
{
    *s = *s * 1664525u + 1013904223u;
    return lo + (hi - lo) * (float)(*s >> 8) / 16777216.0f;
}

static void config(ffr_config_t *cfg) { ffr_config_default(cfg); }

/* odometry at (x, y) heading h, all else zero */
static ffr_odometry_t pose(float x, float y, float h)
{
    ffr_odometry_t o;
    unsigned char *p = (unsigned char *)&o;
    unsigned k;
    for (k = 0; k < sizeof o; ++k) {
        p[k] = 0u;
    }
    o.x_mm = x;
    o.y_mm = y;
    o.heading_rad = h;
    return o;
}

/* the detour asked from one pose until its search has settled */
static float detour(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, float flame_rad,
                    float reach_mm, float *free_mm)
{
    float off = 0.0f;
    int k;
    for (k = 0; k < SETTLE; ++k) {
        off = ffr_obst_detour(o, cfg, odo, flame_rad, reach_mm, free_mm);
    }
    return off;
}

/* a box (an axis-aligned rectangle, mm) marked densely, as the rangers
 * sweeping its faces would */
static void mark_box(ffr_obstacles_t *o, float x0, float y0, float x1, float y1)
{
    float x, y;
    for (x = x0; x <= x1; x += 8.0f) {
        ffr_obst_mark(o, x, y0);
        ffr_obst_mark(o, x, y1);
    }
    for (y = y0; y <= y1; y += 8.0f) {
        ffr_obst_mark(o, x0, y);
        ffr_obst_mark(o, x1, y);
    }
}

TEST(a_marked_point_is_found_and_nothing_else_is)
{
    uint32_t s = 7u;
    int k;
    for (k = 0; k < 200; ++k) {
        ffr_obstacles_t o;
        float cx = draw(&s, -2000.0f, 2000.0f), cy = draw(&s, -2000.0f, 2000.0f);
        float px = cx + draw(&s, -HALF + 10.0f, HALF - 10.0f), py = cy + draw(&s, -HALF + 10.0f, HALF - 10.0f);
        ffr_obst_reset(&o, cx, cy);
        CHECK(!ffr_obst_at(&o, px, py));
        ffr_obst_mark(&o, px, py);
        CHECK(ffr_obst_at(&o, px, py));
        /* a cell is 64 mm: two cells away is another cell, still empty */
        CHECK(!ffr_obst_at(&o, px + 2.0f * CELL, py));
        CHECK(!ffr_obst_at(&o, px, py - 2.0f * CELL));
        /* outside the grid's square: not kept, never found */
        ffr_obst_mark(&o, cx + HALF + 10.0f, cy);
        CHECK(!ffr_obst_at(&o, cx + HALF + 10.0f, cy));
        ffr_obst_mark(&o, cx, cy - HALF - 10.0f);
        CHECK(!ffr_obst_at(&o, cx, cy - HALF - 10.0f));
        /* the nearest mark: within a cell's half-diagonal of the true distance */
        {
            float qx = px + draw(&s, -150.0f, 150.0f), qy = py + draw(&s, -150.0f, 150.0f);
            float d = ffr_sqrtf((qx - px) * (qx - px) + (qy - py) * (qy - py));
            float got = ffr_obst_nearest_mm(&o, qx, qy, 400.0f);
            CHECK(ffr_absf(got - d) <= 0.71f * CELL + 1.0f);
            CHECK(ffr_obst_nearest_mm(&o, qx, qy, 10.0f) <= 10.0f);
        }
    }
}

TEST(the_rangers_hits_are_marked_where_they_are_in_odometrys_frame)
{
    uint32_t s = 11u;
    int k;
    for (k = 0; k < 100; ++k) {
        ffr_state_t st;
        ffr_config_t cfg;
        ffr_obstacles_t o;
        int i;
        float h = draw(&s, -FFR_PI, FFR_PI);
        config(&cfg);
        ffr_init(&st, &cfg);
        st.odo = pose(draw(&s, -500.0f, 500.0f), draw(&s, -500.0f, 500.0f), h);
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            st.ir_mm[i] = draw(&s, 100.0f, 590.0f);
        }
        ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm);
        ffr_obst_reset(&o, st.odo.x_mm, st.odo.y_mm);
        ffr_obst_record(&o, &st.cfg, &st.odo, &st.ir_geom, st.ir_mm);
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            /* the hit worked out here from the ranger's pose on the body */
            float a = st.cfg.ir_angle_deg[i] * FFR_DEG;
            float bx = st.cfg.ir_x_mm[i] + st.ir_mm[i] * ffr_cosf(a);
            float by = st.cfg.ir_y_mm[i] + st.ir_mm[i] * ffr_sinf(a);
            CHECK(ffr_obst_at(&o, st.odo.x_mm + ffr_cosf(h) * bx - ffr_sinf(h) * by,
                              st.odo.y_mm + ffr_sinf(h) * bx + ffr_cosf(h) * by));
        }
        /* readings beyond 60 cm (and none at all) leave the grid empty */
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            st.ir_mm[i] = i == 0 ? FFR_IR_NONE(&st.cfg) : draw(&s, 610.0f, 800.0f);
        }
        ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm);
        ffr_obst_reset(&o, st.odo.x_mm, st.odo.y_mm);
        ffr_obst_record(&o, &st.cfg, &st.odo, &st.ir_geom, st.ir_mm);
        CHECK(ffr_obst_nearest_mm(&o, st.odo.x_mm, st.odo.y_mm, 3000.0f) == 3000.0f);
    }
}

TEST(the_corridor_is_clear_up_to_a_box_in_the_bodys_way)
{
    uint32_t s = 23u;
    int k;
    ffr_config_t cfg;
    config(&cfg);
    for (k = 0; k < 200; ++k) {
        ffr_obstacles_t o;
        /* the robot at the origin heading +x, a box ahead of it; the flame
         * far ahead along +x (its line of sight is the x axis) */
        float ahead = draw(&s, 150.0f, 400.0f);                 /* box's near face, from the centre */
        float lat = draw(&s, 70.0f, 300.0f) * (k % 2 ? 1.0f : -1.0f); /* its centre across */
        float half = 50.0f;
        float reach = 300.0f;
        float l, fr;
        ffr_obst_reset(&o, 0.0f, 0.0f);
        mark_box(&o, ahead, lat - half, ahead + 100.0f, lat + half);
        fr = ffr_obst_free_mm(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f, reach, &l);
        if (ffr_absf(lat) - half > cfg.body_half_width_mm + 20.0f + CELL) {
            /* beside the corridor, a cell clear of it: no way blocked */
            CHECK(fr == reach);
        } else if (ffr_absf(lat) - half < cfg.body_half_width_mm && ahead - cfg.body_front_mm < reach - CELL) {
            /* in the body's way: blocked about where its near face is */
            CHECK(fr < reach);
            CHECK(ffr_absf(fr - (ahead - cfg.body_front_mm)) <= CELL + 20.0f);
            CHECK(lat > 0.0f ? l > 0.0f : l < 0.0f);
        }
    }
}

/* The corridor's first marked, non-candle cell looked for by dense samples
 * (2 mm ahead, about 2 mm across) over the body's width widened by grow_mm
 * a side: its distance past the front, or -1 if none up to reach_mm. */
static float sampled_free(const ffr_obstacles_t *o, const ffr_config_t *cfg, float x, float y, float dir,
                          float flame, float reach_mm, float grow_mm)
{
    float c = ffr_cosf(dir), s = ffr_sinf(dir), fc = ffr_cosf(flame), fs = ffr_sinf(flame);
    float w = cfg->body_half_width_mm + grow_mm;
    float a;
    int j;
    for (a = 0.0f; a <= reach_mm; a += 2.0f) {
        float ahead = cfg->body_front_mm + a;
        for (j = 0; j <= 100; ++j) {
            float l = -w + 2.0f * w * (float)j / 100.0f;
            float px = x + c * ahead - s * l, py = y + s * ahead + c * l;
            float gx = (px - (float)o->ox_mm) / CELL, gy = (py - (float)o->oy_mm) / CELL;
            float ccx, ccy;
            if (!ffr_obst_at(o, px, py) || gx < 0.0f || gy < 0.0f) {
                continue;
            }
            ccx = (float)o->ox_mm + ((float)(int)gx + 0.5f) * CELL - x;
            ccy = (float)o->oy_mm + ((float)(int)gy + 0.5f) * CELL - y;
            if (ffr_absf(-ccx * fs + ccy * fc) < 60.0f) {
                continue; /* the candle's (obstacle_avoid.c AVOID_CANDLE_LAT_MM) */
            }
            return a;
        }
    }
    return -1.0f;
}

TEST(the_corridor_walked_over_the_cells_is_what_dense_samples_see)
{
    uint32_t s = 61u;
    int k, hits = 0;
    ffr_config_t cfg;
    config(&cfg);
    for (k = 0; k < 150; ++k) {
        ffr_obstacles_t o;
        float x = draw(&s, -300.0f, 300.0f), y = draw(&s, -300.0f, 300.0f);
        float dir = draw(&s, -FFR_PI, FFR_PI), flame = dir + draw(&s, -0.7f, 0.7f);
        float reach = draw(&s, 0.0f, 320.0f);
        float got, inner, outer;
        int m, n = 1 + (int)draw(&s, 0.0f, 12.0f);
        ffr_obst_reset(&o, 0.0f, 0.0f);
        for (m = 0; m < n; ++m) {
            ffr_obst_mark(&o, x + draw(&s, -500.0f, 500.0f), y + draw(&s, -500.0f, 500.0f));
        }
        got = ffr_obst_free_mm(&o, &cfg, x, y, dir, flame, reach, NULL);
        /* samples over a corridor 3 mm narrower a side: what they see, the
         * walk sees no later (its distance rounded up to 20 mm) ... */
        inner = sampled_free(&o, &cfg, x, y, dir, flame, reach, -3.0f);
        /* ... and over one 3 mm wider: nothing they miss is seen */
        outer = sampled_free(&o, &cfg, x, y, dir, flame, reach, 3.0f);
        CHECK(got >= 0.0f && got <= reach);
        if (inner >= 0.0f) {
            CHECK(got <= inner + 20.0f);
        }
        if (outer < 0.0f) {
            CHECK(got == reach);
        } else {
            CHECK(got >= outer - 2.0f);
        }
        hits += inner >= 0.0f;
    }
    CHECK(hits > 30); /* the draws put marks in the corridor often */
}

TEST(a_mark_on_the_flames_line_of_sight_is_the_candle)
{
    ffr_config_t cfg;
    ffr_obstacles_t o;
    int k;
    config(&cfg);
    for (k = 0; k < 12; ++k) {
        float dir = -FFR_PI + (float)k * (FFR_PI / 6.0f);
        float d = 250.0f;
        ffr_obst_reset(&o, 0.0f, 0.0f);
        /* the base's face straight ahead, on the line of sight */
        ffr_obst_mark(&o, ffr_cosf(dir) * d, ffr_sinf(dir) * d);
        CHECK(ffr_obst_free_mm(&o, &cfg, 0.0f, 0.0f, dir, dir, 300.0f, NULL) == 300.0f);
        /* with the flame's line elsewhere, the same marks block the way */
        CHECK(ffr_obst_free_mm(&o, &cfg, 0.0f, 0.0f, dir, dir + 0.6f, 300.0f, NULL) < 300.0f);
    }
}

TEST(the_detour_turns_away_from_a_box_and_keeps_its_side)
{
    uint32_t s = 31u;
    int k;
    ffr_config_t cfg;
    config(&cfg);
    for (k = 0; k < 100; ++k) {
        ffr_obstacles_t o;
        float h = draw(&s, -FFR_PI, FFR_PI);
        ffr_odometry_t odo = pose(0.0f, 0.0f, h);
        float c = ffr_cosf(h), sn = ffr_sinf(h);
        float side = k % 2 ? 1.0f : -1.0f;              /* the box's side: + left */
        float ahead = draw(&s, 200.0f, 320.0f);
        float lat = side * draw(&s, 80.0f, 130.0f);
        float fr = 0.0f, off, x, y;
        ffr_obst_reset(&o, 0.0f, 0.0f);
        /* the box, 10 cm a side, placed in the robot's frame */
        for (x = ahead; x <= ahead + 100.0f; x += 8.0f) {
            for (y = lat - 50.0f; y <= lat + 50.0f; y += 8.0f) {
                ffr_obst_mark(&o, c * x - sn * y, sn * x + c * y);
            }
        }
        /* the first tick: only the straight way looked along, blocked: a
         * search begins, no detour yet */
        CHECK(ffr_obst_detour(&o, &cfg, &odo, h, 300.0f, &fr) == 0.0f);
        CHECK(o.first != 0 && o.next == 0u);
        off = detour(&o, &cfg, &odo, h, 300.0f, &fr);
        /* it turns away from the box, no more than 35 degrees, and that way
         * is clearer than straight on */
        CHECK(side > 0.0f ? off < 0.0f : off > 0.0f);
        CHECK(ffr_absf(off) <= 35.0f * FFR_DEG + 1e-5f);
        CHECK(fr > ffr_obst_free_mm(&o, &cfg, 0.0f, 0.0f, h, h, 300.0f, NULL));
        /* asked again, it keeps the side it took */
        {
            float again = detour(&o, &cfg, &odo, h, 300.0f, NULL);
            CHECK(again == 0.0f || (again > 0.0f) == (off > 0.0f));
        }
        /* past it (the box behind): straight on again */
        odo.x_mm = c * (ahead + 400.0f);
        odo.y_mm = sn * (ahead + 400.0f);
        CHECK(detour(&o, &cfg, &odo, h, 300.0f, NULL) == 0.0f);
        CHECK(o.first == 0); /* and no search under way */
        /* nothing to look at (reach 0): never a detour */
        CHECK(ffr_obst_detour(&o, &cfg, &odo, h, 0.0f, NULL) == 0.0f);
    }
}

TEST(the_trail_keeps_the_bends_of_an_approach)
{
    uint32_t s = 53u;
    int k;
    for (k = 0; k < 100; ++k) {
        ffr_obstacles_t o;
        float h0 = draw(&s, -FFR_PI, FFR_PI);
        float bend = draw(&s, 16.0f, 60.0f) * FFR_DEG * (k % 2 ? 1.0f : -1.0f);
        ffr_odometry_t odo = pose(draw(&s, -300.0f, 300.0f), draw(&s, -300.0f, 300.0f), h0);
        float x0 = odo.x_mm, y0 = odo.y_mm;
        int i;
        ffr_obst_reset(&o, 0.0f, 0.0f);
        ffr_obst_trail(&o, &odo, 1);
        CHECK(o.n_via == 0u); /* it starts at the scan point: nothing kept */
        /* straight on, wavering under 15 degrees: nothing kept */
        for (i = 0; i < 20; ++i) {
            odo.x_mm += 10.0f * ffr_cosf(h0);
            odo.y_mm += 10.0f * ffr_sinf(h0);
            odo.heading_rad = h0 + (i % 2 ? 1.0f : -1.0f) * 14.0f * FFR_DEG;
            ffr_obst_trail(&o, &odo, 0);
        }
        CHECK(o.n_via == 0u);
        /* a bend of more than 15 degrees: kept where it is */
        odo.heading_rad = h0 + bend;
        ffr_obst_trail(&o, &odo, 0);
        CHECK(o.n_via == 1u);
        CHECK(ffr_absf((float)o.via_x_mm[0] - odo.x_mm) <= 1.0f && ffr_absf((float)o.via_y_mm[0] - odo.y_mm) <= 1.0f);
        CHECK(ffr_absf((float)o.via_x_mm[0] - x0) > 100.0f || ffr_absf((float)o.via_y_mm[0] - y0) > 100.0f);
        /* more bends than room: the first kept, the last always the newest */
        for (i = 0; i < 5; ++i) {
            odo.x_mm += 50.0f;
            odo.heading_rad += 20.0f * FFR_DEG;
            ffr_obst_trail(&o, &odo, 0);
        }
        CHECK(o.n_via == FFR_OBST_VIA);
        CHECK(ffr_absf((float)o.via_x_mm[FFR_OBST_VIA - 1] - odo.x_mm) <= 1.0f);
        CHECK(ffr_absf((float)o.via_x_mm[0] - (x0 + 200.0f * ffr_cosf(h0))) <= 1.0f);
    }
}

TEST(a_clear_room_gives_no_detour_and_no_turning_points)
{
    uint32_t s = 41u;
    int k;
    ffr_config_t cfg;
    config(&cfg);
    for (k = 0; k < 100; ++k) {
        ffr_obstacles_t o;
        float x = draw(&s, -300.0f, 300.0f), y = draw(&s, -300.0f, 300.0f);
        ffr_odometry_t odo = pose(x, y, draw(&s, -FFR_PI, FFR_PI));
        ffr_obst_reset(&o, 0.0f, 0.0f);
        CHECK(ffr_obst_detour(&o, &cfg, &odo, odo.heading_rad + draw(&s, -0.5f, 0.5f), 300.0f, NULL) == 0.0f);
        CHECK(o.n_via == 0u);
    }
}

SUITE(obstacle_avoid,
      TEST_REF(a_marked_point_is_found_and_nothing_else_is),
      TEST_REF(the_rangers_hits_are_marked_where_they_are_in_odometrys_frame),
      TEST_REF(the_corridor_is_clear_up_to_a_box_in_the_bodys_way),
      TEST_REF(the_corridor_walked_over_the_cells_is_what_dense_samples_see),
      TEST_REF(a_mark_on_the_flames_line_of_sight_is_the_candle),
      TEST_REF(the_detour_turns_away_from_a_box_and_keeps_its_side),
      TEST_REF(the_trail_keeps_the_bends_of_an_approach),
      TEST_REF(a_clear_room_gives_no_detour_and_no_turning_points));
