/*
 * Obstacles in a room (the contest's furniture mode): what the rangers have
 * seen, kept as a bit grid in odometry's frame, and the approach's detour
 * around what stands in the body's way to the flame.
 *
 * The front rangers look straight ahead (CF) and 45 degrees out (LF, RF):
 * an object ahead of a front corner but off the centre line is in none of
 * their beams until it is a few centimetres from the body. The scan (a turn
 * in place) sweeps every ranger round the room, so the grid is filled there,
 * and on during the approach; the approach then looks along the straight
 * corridor the body would sweep toward the flame and, when something is in
 * it, turns the heading off the flame's by the least offset whose corridor is
 * clear.
 *
 * The candle's base is a ranger target too. It stands on the flame's line of
 * sight, and no piece of furniture can (the flame is seen past it: pieces are
 * as tall as the walls), so hits within AVOID_CANDLE_LAT_MM of that line are
 * left out; and the corridor is looked along only for a share of the flame's
 * distance told by its strength, so the candle and the walls behind it are
 * never in it. Pure functions of what they are given; room.c decides when.
 * Tested directly in firmware/tests/test_obstacle_avoid.c.
 */
#include "ffr_internal.h"

/* a grid cell's side, mm (chosen: the thinnest piece is 10 cm; 24 cells
 * then cover 1.54 m, the 0.7 m the rangers' kept hits reach round the scan
 * point with the grid's centre GRID_AHEAD_MM beyond it: room.c) */
#define OBST_CELL_MM 64.0f
/* chosen: only hits this near are kept (a GP2D12 reads 2-3 cm off at 60 cm;
 * odometry's heading error over a scan moves far hits most) */
#define OBST_RANGE_MM 600.0f
/* the corridor's clearance is told in steps of this (mm) */
#define AVOID_STEP_MM 20.0f
/* chosen: the corridor is the body's width and this much each side (2 cm
 * made 5 furniture-free `realistic` missions with a candle by a wall detour
 * into the far wall: odometry's error moves the wall into the corridor) */
#define AVOID_SIDE_MM 0.0f
/* chosen: a marked cell whose centre is this near the flame's line of sight
 * is the candle's base (8 cm across) or beyond it; no piece can stand on that
 * line. A mark on the line has its cell's centre within 45 mm of it */
#define AVOID_CANDLE_LAT_MM 60.0f
/* the detour's headings: offsets from the flame's of this step, up to this
 * many steps each way (chosen: 35 degrees keeps the flame in the sensors'
 * +-60 degree view, half strength at 30) */
#define AVOID_OFFSET_DEG 7.0f
#define AVOID_OFFSET_STEPS 5
/* the detour's headings looked along in one tick while a search is under way
 * (chosen: the straight corridor is looked along on a tick of its own, so no
 * tick looks along more than one: the emulated boards' worst tick,
 * docs/pil.md) */
#define AVOID_PER_TICK 1
/* chosen: a detour whose best corridor is clear for less than this past the
 * front is no way round (one sample step) */
#define AVOID_MIN_FREE_MM 20.0f
/* the approach's trail: a turning point kept where the heading has turned
 * this much since the last (chosen: a bend the straight way back would cut
 * by some centimetres over the ~0.5 m of an approach) ... */
#define TRAIL_BEND_DEG 15.0f
/* ... and where a new approach begins this far from the last (mm, chosen) */
#define TRAIL_NEW_MM 50.0f

static int cell_of(const ffr_obstacles_t *o, float x_mm, float y_mm, int *ix, int *iy)
{
    float fx = (x_mm - (float)o->ox_mm) / OBST_CELL_MM;
    float fy = (y_mm - (float)o->oy_mm) / OBST_CELL_MM;
    if (fx < 0.0f || fy < 0.0f || fx >= (float)FFR_OBST_CELLS || fy >= (float)FFR_OBST_CELLS) {
        return 0;
    }
    *ix = (int)fx;
    *iy = (int)fy;
    return 1;
}

/* a row of the grid is three bytes, read as one mask */
FFR_STATIC_ASSERT(obst_row_is_three_bytes, FFR_OBST_CELLS == 24);

/* row iy's cells ix0..ix1 as a mask (bit ix: cell ix) */
static uint32_t row_bits(const ffr_obstacles_t *o, int iy, int ix0, int ix1)
{
    const uint8_t *row = &o->bits[iy * (FFR_OBST_CELLS / 8)];
    uint32_t bits = (uint32_t)row[0] | ((uint32_t)row[1] << 8) | ((uint32_t)row[2] << 16);
    return bits & (0xFFFFFFu >> (FFR_OBST_CELLS - 1 - ix1)) & ~(((uint32_t)1u << ix0) - 1u);
}

void ffr_obst_reset(ffr_obstacles_t *o, float cx_mm, float cy_mm)
{
    unsigned k;
    o->ox_mm = (int16_t)ffr_clampf(cx_mm - 0.5f * (float)FFR_OBST_CELLS * OBST_CELL_MM, -32000.0f, 32000.0f);
    o->oy_mm = (int16_t)ffr_clampf(cy_mm - 0.5f * (float)FFR_OBST_CELLS * OBST_CELL_MM, -32000.0f, 32000.0f);
    for (k = 0; k < sizeof o->bits; ++k) {
        o->bits[k] = 0u;
    }
    o->trail_rad = 0.0f;
    o->free_mm = 0;
    o->best_free_mm = 0;
    o->offset = 0;
    o->best = 0;
    o->first = 0;
    o->next = 0u;
    o->n_via = 0u;
    o->retrace = 0u;
    o->aside_next = 0u;
}

static void keep_point(ffr_obstacles_t *o, const ffr_odometry_t *odo)
{
    /* full: the last one is moved on (the first bends, by the scan point and
     * the piece passed, are the ones the straight way back would cut) */
    uint8_t k = o->n_via < FFR_OBST_VIA ? o->n_via : (uint8_t)(FFR_OBST_VIA - 1u);
    o->via_x_mm[k] = (int16_t)ffr_clampf(odo->x_mm, -32000.0f, 32000.0f);
    o->via_y_mm[k] = (int16_t)ffr_clampf(odo->y_mm, -32000.0f, 32000.0f);
    o->n_via = (uint8_t)(k + 1u);
    o->trail_rad = odo->heading_rad;
}

void ffr_obst_trail_from(ffr_obstacles_t *o, const ffr_odometry_t *odo)
{
    o->n_via = 0u;
    keep_point(o, odo);
}

void ffr_obst_trail(ffr_obstacles_t *o, const ffr_odometry_t *odo, int begin)
{
    if (begin) {
        /* a new approach (after a scan's turn): it starts here */
        if (o->n_via > 0u) {
            float dx = (float)o->via_x_mm[o->n_via - 1u] - odo->x_mm;
            float dy = (float)o->via_y_mm[o->n_via - 1u] - odo->y_mm;
            if (dx * dx + dy * dy > TRAIL_NEW_MM * TRAIL_NEW_MM) {
                keep_point(o, odo);
            }
        }
        o->trail_rad = odo->heading_rad;
        return;
    }
    if (ffr_absf(odo->heading_rad - o->trail_rad) > TRAIL_BEND_DEG * FFR_DEG) {
        keep_point(o, odo);
    }
}

void ffr_obst_mark(ffr_obstacles_t *o, float x_mm, float y_mm)
{
    int ix, iy;
    if (cell_of(o, x_mm, y_mm, &ix, &iy)) {
        int n = iy * FFR_OBST_CELLS + ix;
        o->bits[n >> 3] = (uint8_t)(o->bits[n >> 3] | (1u << (n & 7)));
    }
}

int ffr_obst_at(const ffr_obstacles_t *o, float x_mm, float y_mm)
{
    int ix, iy;
    if (cell_of(o, x_mm, y_mm, &ix, &iy)) {
        int n = iy * FFR_OBST_CELLS + ix;
        return (o->bits[n >> 3] >> (n & 7)) & 1;
    }
    return 0;
}

void ffr_obst_record(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, const ffr_ir_geom_t *g,
                     const float ir_mm[FFR_IR_COUNT])
{
    float c = ffr_cosf(odo->heading_rad);
    float s = ffr_sinf(odo->heading_rad);
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        if (!ffr_ir_valid(cfg, ir_mm[i]) || ir_mm[i] > OBST_RANGE_MM) {
            continue;
        }
        ffr_obst_mark(o, odo->x_mm + c * g->hit_x_mm[i] - s * g->hit_y_mm[i],
                      odo->y_mm + s * g->hit_x_mm[i] + c * g->hit_y_mm[i]);
    }
}

/* The corridor from (x, y) heading (c, s): the body's width, from its front
 * on for reach_mm. Only the marked cells in the corridor's bounding box are
 * looked at (a row of the grid is three bytes, masked to the box's columns,
 * so an empty row costs a few integer operations); a marked cell whose
 * centre is more than its half-diagonal off the corridor is passed over
 * with two multiplications; one in it or across its edge is clipped to the
 * corridor's width exactly (the cell's four corners and where its edges
 * cross the corridor's sides). The distance is rounded up to AVOID_STEP_MM,
 * as the 20 mm samples the corridor was once looked along gave it. */
static float corridor_free(const ffr_obstacles_t *o, const ffr_config_t *cfg, float x_mm, float y_mm, float c, float s,
                           float fc, float fs, float reach_mm, float *lat_mm)
{
    const float h = 0.5f * OBST_CELL_MM;
    float w = cfg->body_half_width_mm + AVOID_SIDE_MM;
    float u0 = cfg->body_front_mm, u1 = cfg->body_front_mm + reach_mm;
    float ex = ffr_absf(s) * w, ey = ffr_absf(c) * w;
    float bx0 = x_mm + (c < 0.0f ? c * u1 : c * u0) - ex, bx1 = x_mm + (c < 0.0f ? c * u0 : c * u1) + ex;
    float by0 = y_mm + (s < 0.0f ? s * u1 : s * u0) - ey, by1 = y_mm + (s < 0.0f ? s * u0 : s * u1) + ey;
    float best = reach_mm + 1.0f, best_lat = 0.0f;
    float du[4], dv[4];
    /* a cell's half extent along the corridor (and across: a square) */
    float hu = h * (ffr_absf(c) + ffr_absf(s));
    int ix0, iy0, ix1, iy1, ix, iy, k, n;
    float lim = (float)FFR_OBST_CELLS * OBST_CELL_MM;
    bx0 -= (float)o->ox_mm;
    bx1 -= (float)o->ox_mm;
    by0 -= (float)o->oy_mm;
    by1 -= (float)o->oy_mm;
    if (reach_mm < 0.0f || bx1 < 0.0f || by1 < 0.0f || bx0 >= lim || by0 >= lim) {
        return reach_mm; /* the corridor is off the grid: nothing seen there */
    }
    ix0 = bx0 < 0.0f ? 0 : (int)(bx0 / OBST_CELL_MM);
    iy0 = by0 < 0.0f ? 0 : (int)(by0 / OBST_CELL_MM);
    ix1 = bx1 >= lim ? FFR_OBST_CELLS - 1 : (int)(bx1 / OBST_CELL_MM);
    iy1 = by1 >= lim ? FFR_OBST_CELLS - 1 : (int)(by1 / OBST_CELL_MM);
    /* a cell's corners from its centre, in the corridor's frame (u ahead,
     * v across), in order round it */
    for (k = 0; k < 4; ++k) {
        float ax = (k == 0 || k == 3) ? h : -h, ay = k < 2 ? h : -h;
        du[k] = ax * c + ay * s;
        dv[k] = -ax * s + ay * c;
    }
    /* rows, and cells in a row, from the robot's side outward: the first
     * mark found bounds the rest; a cell that cannot be nearer is passed
     * over on its centre's distance alone, a row whose nearest cell cannot
     * be ends the walk (the rows after it are farther still) */
    {
        float cx0 = (float)o->ox_mm + ((float)ix0 + 0.5f) * OBST_CELL_MM - x_mm; /* column ix0's centre, from the robot */
        float cx1 = (float)o->ox_mm + ((float)ix1 + 0.5f) * OBST_CELL_MM - x_mm;
        float row_u = c >= 0.0f ? cx0 * c : cx1 * c; /* the nearest column's share of u */
        int dir_x = c >= 0.0f ? 1 : -1;
        for (n = 0; n <= iy1 - iy0; ++n) {
            uint32_t bits;
            float dy;
            iy = s >= 0.0f ? iy0 + n : iy1 - n;
            dy = (float)o->oy_mm + ((float)iy + 0.5f) * OBST_CELL_MM - y_mm;
            if (row_u + dy * s - hu - u0 >= best) {
                break;
            }
            bits = row_bits(o, iy, ix0, ix1);
            for (ix = dir_x > 0 ? ix0 : ix1; bits != 0u; ix += dir_x) {
                float dx, uc, vc, umin, umax, a;
                if (!((bits >> ix) & 1u)) {
                    continue;
                }
                bits &= ~((uint32_t)1u << ix);
                dx = (float)o->ox_mm + ((float)ix + 0.5f) * OBST_CELL_MM - x_mm;
                uc = dx * c + dy * s;
                if (uc - hu - u0 >= best || uc + hu < u0 || uc - hu > u1) {
                    continue;
                }
                vc = -dx * s + dy * c;
                if (ffr_absf(vc) - hu > w) {
                    continue;
                }
                /* how far the marked cell's centre is off the flame's line of
                 * sight (from the robot): a whole cell is the candle's or not */
                if (ffr_absf(-dx * fs + dy * fc) < AVOID_CANDLE_LAT_MM) {
                    continue;
                }
                if (ffr_absf(vc) + hu <= w) {
                    /* wholly within the corridor's width */
                    umin = uc - hu;
                    umax = uc + hu;
                } else {
                    /* across one of its sides: clipped to the corridor */
                    umin = 1e9f;
                    umax = -1e9f;
                    for (k = 0; k < 4; ++k) {
                        int m = (k + 1) & 3;
                        float ua = uc + du[k], va = vc + dv[k], ub = uc + du[m], vb = vc + dv[m];
                        int side;
                        if (ffr_absf(va) <= w) {
                            umin = ua < umin ? ua : umin;
                            umax = ua > umax ? ua : umax;
                        }
                        for (side = -1; side <= 1; side += 2) {
                            float lw = (float)side * w;
                            if ((va - lw) * (vb - lw) < 0.0f) {
                                float uu = ua + (ub - ua) * (lw - va) / (vb - va);
                                umin = uu < umin ? uu : umin;
                                umax = uu > umax ? uu : umax;
                            }
                        }
                    }
                }
                if (umax < u0 || umin > u1) {
                    continue;
                }
                a = umin <= u0 ? 0.0f : AVOID_STEP_MM * (float)(int)((umin - u0) / AVOID_STEP_MM + 0.999f);
                if (a < best && a <= reach_mm) {
                    best = a;
                    best_lat = ffr_clampf(vc, -w, w);
                }
            }
        }
    }
    if (best > reach_mm) {
        return reach_mm;
    }
    if (lat_mm) {
        *lat_mm = best_lat;
    }
    return best;
}

float ffr_obst_free_mm(const ffr_obstacles_t *o, const ffr_config_t *cfg, float x_mm, float y_mm, float dir_rad,
                       float flame_rad, float reach_mm, float *lat_mm)
{
    return corridor_free(o, cfg, x_mm, y_mm, ffr_cosf(dir_rad), ffr_sinf(dir_rad), ffr_cosf(flame_rad),
                         ffr_sinf(flame_rad), reach_mm, lat_mm);
}

/* The search's i-th heading: offsets of 1, 1, 2, 2, ... steps, the first
 * side first */
static int8_t candidate(int8_t first, uint8_t i) { return (int8_t)((i & 1u ? -first : first) * (int)(i / 2u + 1u)); }

float ffr_obst_detour(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, float flame_rad,
                      float reach_mm, float *free_mm)
{
    float fc = ffr_cosf(flame_rad), fs = ffr_sinf(flame_rad);
    float lat = 0.0f;
    int n;
    if (reach_mm <= 0.0f) {
        /* nothing to look at: no detour, no search */
        o->offset = 0;
        o->first = 0;
        o->free_mm = 0;
    } else if (o->first == 0) {
        /* no search under way: the straight way looked along */
        float f = corridor_free(o, cfg, odo->x_mm, odo->y_mm, fc, fs, fc, fs, reach_mm, &lat);
        if (f >= reach_mm) {
            /* clear: no detour */
            o->offset = 0;
            o->free_mm = (int16_t)ffr_clampf(f, 0.0f, 32000.0f);
        } else {
            /* something in the way: a search begins on the next tick, the
             * side away from it first, or the side the detour already took
             * (no swapping sides past a piece); the detour so far is kept
             * until it ends */
            o->first = (int8_t)(o->offset != 0 ? (o->offset > 0 ? 1 : -1) : (lat < 0.0f ? 1 : -1));
            o->next = 0u;
            o->best = 0;
            o->best_free_mm = (int16_t)f;
        }
    } else {
        for (n = 0; n < AVOID_PER_TICK && o->first != 0; ++n) {
            int8_t k = candidate(o->first, o->next);
            /* the heading rotated from the flame's by a fixed offset:
             * cos and sin of 7, 14, ... 35 degrees */
            static const float kc[AVOID_OFFSET_STEPS] = {0.99254615f, 0.97029573f, 0.93358043f, 0.88294759f,
                                                         0.81915204f};
            static const float ks[AVOID_OFFSET_STEPS] = {0.12186934f, 0.24192190f, 0.35836795f, 0.46947156f,
                                                         0.57357644f};
            int m = (k < 0 ? -k : k) - 1;
            float oc = kc[m], os = k < 0 ? -ks[m] : ks[m];
            float fk = corridor_free(o, cfg, odo->x_mm, odo->y_mm, fc * oc - fs * os, fs * oc + fc * os, fc, fs,
                                     reach_mm, NULL);
            int done;
            o->next = (uint8_t)(o->next + 1u);
            if (fk > (float)o->best_free_mm) {
                o->best_free_mm = (int16_t)fk;
                o->best = k;
            }
            done = fk >= reach_mm || o->next >= 2u * AVOID_OFFSET_STEPS;
            if (done) {
                /* the first heading clear all the way, or the clearest: the
                 * detour until the next search ends; none if no way round
                 * from here (the approach's guards decide, as without
                 * furniture: they stop for what is about to touch) */
                o->offset = (float)o->best_free_mm < AVOID_MIN_FREE_MM ? 0 : o->best;
                o->free_mm = o->best_free_mm;
                o->first = 0;
            }
        }
    }
    if (free_mm) {
        *free_mm = (float)o->free_mm;
    }
    return (float)o->offset * AVOID_OFFSET_DEG * FFR_DEG;
}

float ffr_obst_nearest_mm(const ffr_obstacles_t *o, float x_mm, float y_mm, float radius_mm)
{
    /* squared distances compared, one square root at the end; a row's
     * cells read as one mask (obstacle_avoid.c's corridor does the same) */
    float best2 = radius_mm * radius_mm;
    int found = 0;
    int ix0, iy0, ix1, iy1, ix, iy;
    float lox = x_mm - radius_mm, loy = y_mm - radius_mm;
    float hix = x_mm + radius_mm, hiy = y_mm + radius_mm;
    float lim = (float)FFR_OBST_CELLS * OBST_CELL_MM - 1.0f;
    lox = ffr_clampf(lox - (float)o->ox_mm, 0.0f, lim);
    loy = ffr_clampf(loy - (float)o->oy_mm, 0.0f, lim);
    hix = ffr_clampf(hix - (float)o->ox_mm, 0.0f, lim);
    hiy = ffr_clampf(hiy - (float)o->oy_mm, 0.0f, lim);
    ix0 = (int)(lox / OBST_CELL_MM);
    iy0 = (int)(loy / OBST_CELL_MM);
    ix1 = (int)(hix / OBST_CELL_MM);
    iy1 = (int)(hiy / OBST_CELL_MM);
    for (iy = iy0; iy <= iy1; ++iy) {
        uint32_t bits = row_bits(o, iy, ix0, ix1);
        for (ix = ix0; bits != 0u; ++ix, bits &= ~((uint32_t)1u << (ix - 1))) {
            if ((bits >> ix) & 1u) {
                float dx = (float)o->ox_mm + ((float)ix + 0.5f) * OBST_CELL_MM - x_mm;
                float dy = (float)o->oy_mm + ((float)iy + 0.5f) * OBST_CELL_MM - y_mm;
                float d2 = dx * dx + dy * dy;
                if (d2 < best2) {
                    best2 = d2;
                    found = 1;
                }
            }
        }
    }
    return found ? ffr_sqrtf(best2) : radius_mm;
}
