/*
 * Each side's two-ranger wall angle, calibrated from travel.
 *
 * The wall line through a side's two rangers' hits (wall_follow.c) gives the
 * wall's angle at once, but each GP2D12 reads long or short by its own
 * calibration: two parts at opposite ends of the datasheet's spread tilt that
 * line by up to ~6 degrees, and a robot steering and holding its corridor
 * heading by it carries the tilt into every turn that follows. How the wall's
 * distance changes over a stretch of travel does not depend on the parts'
 * offsets (they cancel in the difference; a gain error only scales a small
 * angle), so over each window of travel beside one straight wall the wall's
 * direction is the mean heading plus the slope of distance against travel
 * (least squares over every tick), and the mean of (heading + two-ranger
 * angle) minus that direction is the tilt of this side's pair. It is learned
 * per side (a running mean over the first windows, then a slow average) and
 * taken off the two-ranger angle from then on (ffr_wall_cal_correct).
 *
 * A window needs both rangers on one straight wall every tick, the distance
 * close to a straight line and the pair's line steady; a gap, a side change,
 * a turn or a new route step starts a new one.
 *
 * The openings also take the tilt, split half each between the two parts
 * (ffr_wall_cal_split, at the end).
 */
#include "ffr_internal.h"

/* the window: this much travel, turning less than this on the way */
#define WINDOW_MM 100.0f
#define WINDOW_TURN_DEG 8.0f
/* the pair's tilt: a running mean over this many windows, then an average
 * with that weight; samples beyond the limit are another wall, not a tilt */
#define BIAS_WINDOWS 8u
#define BIAS_MAX_DEG 12.0f
/* a window on one straight wall: the distance within this of a straight line
 * and the wall line's direction within this of constant (rms); on the
 * datasheet's parts with typical noise they stay under half of that, a hit
 * on another wall (a corner ahead, a junction behind) goes over */
#define FIT_RESID_MM 3.0f
#define FIT_SPREAD_DEG 1.0f

void ffr_wall_cal_restart(ffr_wall_cal_t *c)
{
    c->s0_mm = 0.0f;
    c->sum_s = c->sum_d = c->sum_ss = c->sum_sd = c->sum_dd = 0.0f;
    c->sum_h = 0.0f;
    c->sum_a = c->sum_aa = 0.0f;
    c->h0_rad = 0.0f;
    c->d0_mm = 0.0f;
    c->n = 0u;
    c->side = -1;
    c->reserved = 0u;
}

void ffr_wall_cal_reset(ffr_wall_cal_t *c)
{
    ffr_wall_cal_restart(c);
    ffr_wall_dir_reset(c);
    c->bias_rad[0] = c->bias_rad[1] = 0.0f;
    c->bias_n[0] = c->bias_n[1] = 0u;
    c->reserved2[0] = c->reserved2[1] = 0u;
}

void ffr_wall_cal_correct(const ffr_wall_cal_t *c, ffr_wall_t *w, int side)
{
    if (w->angle_valid && (side == FFR_SIDE_LEFT || side == FFR_SIDE_RIGHT)) {
        w->angle_rad -= c->bias_rad[side];
    }
}

float ffr_off_square(float dir)
{
    float q = 0.5f * FFR_PI;
    float k = (float)(int32_t)(dir / q + (dir >= 0.0f ? 0.5f : -0.5f));
    return dir - k * q;
}

static void start(ffr_wall_cal_t *c, int side, float heading_rad, float dist_mm)
{
    ffr_wall_cal_restart(c);
    c->side = (int8_t)side;
    c->s0_mm = dist_mm;
    c->h0_rad = heading_rad;
}

/* The window is complete: what it says, then a new one from here. */
static void close_window(ffr_wall_cal_t *c, int side, float heading_rad, float dist_mm)
{
    float n = (float)c->n;
    float sxx = c->sum_ss - c->sum_s * c->sum_s / n;
    float sxy = c->sum_sd - c->sum_s * c->sum_d / n;
    float syy = c->sum_dd - c->sum_d * c->sum_d / n;
    float saa = c->sum_aa - c->sum_a * c->sum_a / n;
    /* how far the distance strays from a straight line, and the wall line's
     * direction from constant (mm, rad rms): a hit on another wall shows in both */
    float resid = sxx > 0.0f ? (syy - sxy * sxy / sxx) / n : 0.0f;
    float spread = saa / n;
    if (sxx > 0.0f && resid < FIT_RESID_MM * FIT_RESID_MM
        && spread < (FIT_SPREAD_DEG * FFR_DEG) * (FIT_SPREAD_DEG * FFR_DEG)) {
        /* moving away from a left wall means it runs to the left of the heading */
        float slope = ffr_clampf(sxy / sxx, -0.4f, 0.4f);
        float rel = (side == FFR_SIDE_LEFT ? 1.0f : -1.0f) * slope; /* asin(x) ~ x here */
        float wall_rel = c->sum_h / n + rel; /* from the window's first heading */
        float tilt = c->sum_a / n - wall_rel;
        if (ffr_absf(tilt) < BIAS_MAX_DEG * FFR_DEG) {
            if (c->bias_n[side] < BIAS_WINDOWS) {
                c->bias_n[side] = (uint8_t)(c->bias_n[side] + 1u);
            }
            c->bias_rad[side] += (tilt - c->bias_rad[side]) / (float)c->bias_n[side];
        }
    }
    start(c, side, heading_rad, dist_mm);
}

void ffr_wall_cal_update(ffr_wall_cal_t *c, const ffr_wall_t *w, int side, float heading_rad, float dist_mm)
{
    float s, d, h;
    if (!w->angle_valid || (side != FFR_SIDE_LEFT && side != FFR_SIDE_RIGHT)) {
        ffr_wall_cal_restart(c);
        return;
    }
    if (c->side != side) {
        start(c, side, heading_rad, dist_mm);
    }
    if (ffr_absf(heading_rad - c->h0_rad) > WINDOW_TURN_DEG * FFR_DEG) {
        /* turning too much for a straight-travel measurement: start again */
        start(c, side, heading_rad, dist_mm);
    }
    if (c->n == 0u) {
        c->d0_mm = w->dist_mm;
    }
    /* sums of small numbers, relative to the window's start: float32 keeps them exact enough */
    s = dist_mm - c->s0_mm;
    d = w->dist_mm - c->d0_mm;
    h = heading_rad - c->h0_rad;
    c->sum_s += s;
    c->sum_d += d;
    c->sum_ss += s * s;
    c->sum_sd += s * d;
    c->sum_dd += d * d;
    c->sum_h += h;
    c->sum_a += h + w->angle_rad;
    c->sum_aa += (h + w->angle_rad) * (h + w->angle_rad);
    c->n = (uint16_t)(c->n + 1u);
    if (s >= WINDOW_MM && c->n >= 4u) {
        close_window(c, side, heading_rad, dist_mm);
    }
}

/* The pair's tilt says how much farther out the front ranger reads than the
 * rear one on a wall beside, not which of the two is off: for two parts of
 * the same spread, half each is the likeliest split. The side rangers' hits
 * moved along their beams by that half (for where walls end: openings.c);
 * the tilt was learned at the followed wall's distance, so the lateral error
 * is taken as there: tilt x the hits' spacing on such a wall. The spacing
 * depends on the configuration only, but is worked out each call: the state
 * is at FFR_STATE_MAX (docs/contract.md) and has no room to keep it. */
void ffr_wall_cal_split(const ffr_wall_cal_t *c, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT],
                        ffr_ir_geom_t *g)
{
    int side;
    for (side = 0; side < 2; ++side) {
        int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
        int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
        float sf = ffr_absf(g->beam_sin[f]), sr = ffr_absf(g->beam_sin[r]);
        float t = cfg->wall_target_mm, spacing, half, d;
        if (c->bias_n[side] == 0u || sf < 0.3f || sr < 0.3f) {
            continue;
        }
        spacing = cfg->ir_x_mm[f] + (t - ffr_absf(cfg->ir_y_mm[f])) * g->beam_cos[f] / sf
                  - (cfg->ir_x_mm[r] + (t - ffr_absf(cfg->ir_y_mm[r])) * g->beam_cos[r] / sr);
        half = 0.5f * c->bias_rad[side] * spacing * (side == FFR_SIDE_LEFT ? 1.0f : -1.0f);
        if (ffr_ir_valid(cfg, ir_mm[f])) {
            d = -half / sf;
            g->hit_x_mm[f] += d * g->beam_cos[f];
            g->hit_y_mm[f] += d * g->beam_sin[f];
        }
        if (ffr_ir_valid(cfg, ir_mm[r])) {
            d = half / sr;
            g->hit_x_mm[r] += d * g->beam_cos[r];
            g->hit_y_mm[r] += d * g->beam_sin[r];
        }
    }
}
