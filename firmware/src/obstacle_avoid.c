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

/* a grid cell's side, mm (chosen: the thinnest piece is 10 cm; 32 cells
 * then cover 2 m, a room seen from its scan point) */
#define OBST_CELL_MM 64.0f
/* chosen: only hits this near are kept (a GP2D12 reads 2-3 cm off at 60 cm;
 * odometry's heading error over a scan moves far hits most) */
#define OBST_RANGE_MM 600.0f
/* the corridor's samples, mm apart, ahead and across */
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

void ffr_obst_reset(ffr_obstacles_t *o, float cx_mm, float cy_mm)
{
    unsigned k;
    o->ox_mm = (int16_t)ffr_clampf(cx_mm - 0.5f * (float)FFR_OBST_CELLS * OBST_CELL_MM, -32000.0f, 32000.0f);
    o->oy_mm = (int16_t)ffr_clampf(cy_mm - 0.5f * (float)FFR_OBST_CELLS * OBST_CELL_MM, -32000.0f, 32000.0f);
    for (k = 0; k < sizeof o->bits; ++k) {
        o->bits[k] = 0u;
    }
    o->offset_rad = 0.0f;
    o->trail_rad = 0.0f;
    o->n_via = 0u;
    o->retrace = 0u;
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

float ffr_obst_free_mm(const ffr_obstacles_t *o, const ffr_config_t *cfg, float x_mm, float y_mm, float dir_rad,
                       float flame_rad, float reach_mm, float *lat_mm)
{
    float c = ffr_cosf(dir_rad), s = ffr_sinf(dir_rad);
    float fc = ffr_cosf(flame_rad), fs = ffr_sinf(flame_rad);
    float w = cfg->body_half_width_mm + AVOID_SIDE_MM;
    float a, l;
    for (a = 0.0f; a <= reach_mm; a += AVOID_STEP_MM) {
        float ahead = cfg->body_front_mm + a;
        for (l = -w; l <= w; l += AVOID_STEP_MM) {
            float px = x_mm + c * ahead - s * l;
            float py = y_mm + s * ahead + c * l;
            int ix, iy;
            float off;
            if (!ffr_obst_at(o, px, py) || !cell_of(o, px, py, &ix, &iy)) {
                continue;
            }
            /* how far the marked cell's centre is off the flame's line of
             * sight (from the robot): a whole cell is the candle's or not */
            off = -((float)o->ox_mm + ((float)ix + 0.5f) * OBST_CELL_MM - x_mm) * fs
                  + ((float)o->oy_mm + ((float)iy + 0.5f) * OBST_CELL_MM - y_mm) * fc;
            if (ffr_absf(off) < AVOID_CANDLE_LAT_MM) {
                continue;
            }
            if (lat_mm) {
                *lat_mm = l;
            }
            return a;
        }
    }
    return reach_mm;
}

float ffr_obst_detour(ffr_obstacles_t *o, const ffr_config_t *cfg, const ffr_odometry_t *odo, float flame_rad,
                      float reach_mm, float *free_mm)
{
    float lat = 0.0f;
    float chosen = 0.0f;
    float best_free;
    float f = reach_mm > 0.0f ? ffr_obst_free_mm(o, cfg, odo->x_mm, odo->y_mm, flame_rad, flame_rad, reach_mm, &lat)
                              : reach_mm;
    best_free = f;
    if (f < reach_mm) {
        /* something in the way: the side away from it first, or the side the
         * detour already took (no swapping sides past a piece) */
        float first = o->offset_rad != 0.0f ? (o->offset_rad > 0.0f ? 1.0f : -1.0f) : (lat < 0.0f ? 1.0f : -1.0f);
        int k, done = 0;
        for (k = 1; k <= AVOID_OFFSET_STEPS && !done; ++k) {
            int side;
            for (side = 0; side < 2 && !done; ++side) {
                float off = (side ? -first : first) * (float)k * AVOID_OFFSET_DEG * FFR_DEG;
                float fk = ffr_obst_free_mm(o, cfg, odo->x_mm, odo->y_mm, flame_rad + off, flame_rad, reach_mm, NULL);
                if (fk > best_free) {
                    best_free = fk;
                    chosen = off;
                    done = fk >= reach_mm;
                }
            }
        }
    }
    if (best_free < AVOID_MIN_FREE_MM) {
        /* no way round from here: the approach's guards decide, as without
         * furniture (they stop for what is about to touch) */
        chosen = 0.0f;
    }
    o->offset_rad = chosen;
    if (free_mm) {
        *free_mm = best_free;
    }
    return chosen;
}

float ffr_obst_nearest_mm(const ffr_obstacles_t *o, float x_mm, float y_mm, float radius_mm)
{
    float best = radius_mm;
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
        for (ix = ix0; ix <= ix1; ++ix) {
            int n = iy * FFR_OBST_CELLS + ix;
            if ((o->bits[n >> 3] >> (n & 7)) & 1) {
                float dx = (float)o->ox_mm + ((float)ix + 0.5f) * OBST_CELL_MM - x_mm;
                float dy = (float)o->oy_mm + ((float)iy + 0.5f) * OBST_CELL_MM - y_mm;
                float d = ffr_sqrtf(dx * dx + dy * dy);
                if (d < best) {
                    best = d;
                }
            }
        }
    }
    return best;
}
