/*
 * home_orient.c: which way the robot faces at home, from a turn in place.
 * The rangers' readings come from a true pose among straight walls (rig.c);
 * odometry's frame is the world turned by an unknown angle, the robot's
 * start heading, which the sweep must find (modulo 90 degrees).
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* The rangers' distances as the firmware reads them (mV; none: 0 mV). */
static void feed(rig_t *r, const ffr_config_t *cfg, const float ir[FFR_IR_COUNT])
{
    int k;
    for (k = 0; k < FFR_IR_COUNT; ++k) {
        r->in.ir_mv[k] = ffr_ir_valid(cfg, ir[k]) ? rig_mv_for_mm(cfg, ir[k]) : 0u;
    }
}

#ifndef FFR_HOME_SKIP_MM
#define FFR_HOME_SKIP_MM_BUILT 0.0f
#else
#define FFR_HOME_SKIP_MM_BUILT FFR_HOME_SKIP_MM
#endif

#define PI_F 3.14159265f

/* the aim's allowance for a ranger reading short, as built (home_orient.c) */
#ifndef RANGE_SHORT_FRAC
#define RANGE_SHORT_FRAC_BUILT 0.25f
#else
#define RANGE_SHORT_FRAC_BUILT RANGE_SHORT_FRAC
#endif

/* A sweep in place at the world origin from true heading th0 through `sweep`
 * radians, odometry's frame the world turned by `rot`; the parts read
 * part_mm long (w). */
static void sweep(ffr_home_orient_t *o, const ffr_config_t *cfg, const rig_walls_t *w, float x, float y, float th0,
                  float sweep_rad, float rot)
{
    ffr_odometry_t odo;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    float th;
    int i, k, n = 80;
    ffr_odometry_reset(&odo);
    odo.x_mm = ffr_cosf(rot) * x - ffr_sinf(rot) * y;
    odo.y_mm = ffr_sinf(rot) * x + ffr_cosf(rot) * y;
    odo.heading_rad = th0 + rot;
    ffr_orient_reset(o, &odo);
    for (k = 0; k <= n; ++k) {
        th = th0 + sweep_rad * (float)k / (float)n;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            ir[i] = rig_beam_mm(cfg, w, i, x, y, th);
        }
        odo.heading_rad = th + rot;
        ffr_orient_record(o, cfg, &odo, rig_geom(&g, cfg, ir), ir);
    }
}

/* what a direction is off the nearest multiple of 90 degrees */
static float off90(float a)
{
    while (a > 0.25f * PI_F) {
        a -= 0.5f * PI_F;
    }
    while (a <= -0.25f * PI_F) {
        a += 0.5f * PI_F;
    }
    return a;
}

TEST(the_walls_direction_whatever_the_start_heading)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    /* a hallway's dead end: walls 230 mm left and right, one 250 mm ahead (+x) */
    rig_walls_t w = {230.0f, -230.0f, 250.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    int k;
    float worst = 0.0f;
    ffr_config_default(&cfg);
    /* every start heading over a full turn, both sweep directions, odometry's
     * frame turned by an unknown amount */
    for (k = 0; k < 72; ++k) {
        float th0 = (float)k * 5.0f * FFR_DEG;
        float rot = 0.7f - th0; /* odometry starts at 0.7 rad, whatever the true heading */
        float dir0, e;
        sweep(&o, &cfg, &w, 0.0f, 0.0f, th0, (k & 1 ? -100.0f : 100.0f) * FFR_DEG, rot);
        CHECK(o.w > 150.0f);
        dir0 = ffr_orient_square(&o);
        /* the world's walls run along 0 and 90 degrees: in odometry's frame, rot */
        e = ffr_absf(off90(dir0 - rot));
        worst = e > worst ? e : worst;
    }
    CHECK_NEAR(worst, 0.0f, 1.5f * FFR_DEG);
}

TEST(the_open_end_and_the_walls_around)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    rig_walls_t w = {230.0f, -230.0f, 250.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    float rot = 0.3f;
    ffr_config_default(&cfg);
    sweep(&o, &cfg, &w, 0.0f, 0.0f, 1.0f, 100.0f * FFR_DEG, rot);
    /* ahead (+x in the world: rot in odometry's frame) the end wall, 250 mm */
    CHECK_NEAR(ffr_orient_free_mm(&o, 130.0f, rot, 0.0f, 0.0f), 250.0f, 10.0f);
    CHECK_NEAR(ffr_orient_free_mm(&o, 130.0f, rot + 0.5f * PI_F, 0.0f, 0.0f), 230.0f, 10.0f);
    CHECK_NEAR(ffr_orient_free_mm(&o, 130.0f, rot - 0.5f * PI_F, 0.0f, 0.0f), 230.0f, 10.0f);
    /* behind: the open hallway, nothing seen */
    CHECK(ffr_orient_free_mm(&o, 130.0f, rot + PI_F, 0.0f, 0.0f) > 800.0f);
    /* the four at once: the same, from anywhere */
    {
        float f4[4];
        int k;
        for (k = 0; k < 4; ++k) {
            float cx = 30.0f * (float)(k - 1), cy = -20.0f * (float)k;
            int j;
            ffr_orient_free4(&o, 130.0f, rot, cx, cy, f4);
            for (j = 0; j < 4; ++j) {
                CHECK_NEAR(f4[j], ffr_orient_free_mm(&o, 130.0f, rot + (float)j * 0.5f * PI_F, cx, cy), 0.5f);
            }
        }
    }
    /* the only open way is back down the hallway, walls close both sides:
     * every rule picks it (k = 2: rot + 180 degrees) */
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    CHECK(ffr_orient_choose(&o, &cfg, rot, rot, 0.0f, 0.0f) == 2);
    cfg.home_wall_side = FFR_HOME_WALL_LEFT;
    CHECK(ffr_orient_choose(&o, &cfg, rot, rot, 0.0f, 0.0f) == 2);
    cfg.home_wall_side = FFR_HOME_WALL_ANY;
    CHECK(ffr_orient_choose(&o, &cfg, rot, rot, 0.0f, 0.0f) == 2);
}

/* a hit at (x, y) kept in its bin when it is the bin's nearest, as the
 * sweep keeps them (within 800 mm) */
static void keep_nearest(ffr_home_orient_t *o, float x, float y)
{
    float r = ffr_sqrtf(x * x + y * y), a = ffr_atan2f(y, x);
    int bin = (int)((a < 0.0f ? a + 2.0f * PI_F : a) / (2.0f * PI_F / (float)FFR_ORIENT_BINS));
    if (bin >= FFR_ORIENT_BINS) {
        bin = FFR_ORIENT_BINS - 1;
    }
    if (r < 800.0f && r < (float)o->bin_mm[bin]) {
        o->bin_mm[bin] = (uint16_t)r;
        o->bin_x_mm[bin] = x;
        o->bin_y_mm[bin] = y;
    }
}

/* bins filled by hand: a straight wall along a line through (px, py), direction (ux, uy) */
static void add_wall(ffr_home_orient_t *o, float px, float py, float ux, float uy)
{
    int b;
    for (b = -40; b <= 40; ++b) {
        keep_nearest(o, px + ux * 20.0f * (float)b, py + uy * 20.0f * (float)b);
    }
}

TEST(the_route_direction_by_the_wall_side_rule)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float dx, dy;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&odo);
    ffr_orient_reset(&o, &odo);
    /* a hallway's corner: a wall 310 mm east (+x), one 230 mm south; north
     * (+y) and west open, as the 2004 arena's home */
    add_wall(&o, 310.0f, 0.0f, 0.0f, 1.0f);
    add_wall(&o, 0.0f, -230.0f, 1.0f, 0.0f);
    /* open ahead, its wall on the right: north (k = 1); on the left: west (k = 2) */
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 1);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 0.0f, 0.0f) == 1);
    cfg.home_wall_side = FFR_HOME_WALL_LEFT;
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 2);
    /* any: one wall beside each way: the smaller turn */
    cfg.home_wall_side = FFR_HOME_WALL_ANY;
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.5f * PI_F, 0.0f, 0.0f) == 1);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 0.0f, 0.0f) == 2);
    /* where to stand: wall_target_mm (230) from the east wall, the south one
     * already there */
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, 310.0f - cfg.wall_target_mm, 15.0f);
    CHECK_NEAR(dy, 0.0f, 15.0f);
    /* two walls across an axis: the nearer one at wall_target_mm */
    add_wall(&o, -150.0f, 0.0f, 0.0f, 1.0f);
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, cfg.wall_target_mm - 150.0f, 15.0f);
    /* all four ways shut: none is open */
    add_wall(&o, 0.0f, 300.0f, 1.0f, 0.0f);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == -1);
}

/* bins filled by hand: a wall's stretch from (x0, y0) to (x1, y1), every
 * hit read `f` times its distance (a ranger reading short: f < 1) */
static void add_stretch(ffr_home_orient_t *o, float x0, float y0, float x1, float y1, float f)
{
    int k, n = 200;
    for (k = 0; k <= n; ++k) {
        keep_nearest(o, f * (x0 + (x1 - x0) * (float)k / (float)n), f * (y0 + (y1 - y0) * (float)k / (float)n));
    }
}

/* the centre's shift along x (dx) from bins holding only two hits, (x1, y1)
 * and (x2, y2), seen from the sweep's centre, the walls' direction 0 */
static float centre_dx_of_two(const ffr_config_t *cfg, float x1, float y1, float x2, float y2)
{
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float dx, dy;
    ffr_odometry_reset(&odo);
    ffr_orient_reset(&o, &odo);
    keep_nearest(&o, x1, y1);
    keep_nearest(&o, x2, y2);
    ffr_orient_centre(&o, cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    return dx;
}

/* a wall across one of the four axes farther out than the sweep's hits are
 * dense: the bins nearest the axis are 10 degrees wide, so on a wall 46 cm
 * off their nearest hits may lie 70-80 mm either side of it, outside the
 * centre's 40 mm band (fresh +-2.5 cm start seed 199: the robot stayed in
 * the middle hallway's mouth, the way north shut by its wall's end) */
TEST(a_far_wall_across_between_the_bins_places_the_robot)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float dx, dy, reach;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&odo);
    /* where the centre stands a wall across off its near one: 2 wall_target + half width,
     * as far as a ranger may read long (15 %) */
    reach = (2.0f * cfg.wall_target_mm + cfg.body_half_width_mm) * 1.15f;
    /* the south wall 233 mm off; the east one 466 mm off, hit either side of the axis only */
    ffr_orient_reset(&o, &odo);
    add_wall(&o, 0.0f, -233.0f, 1.0f, 0.0f);
    keep_nearest(&o, 466.0f, 78.0f);
    keep_nearest(&o, 470.0f, -68.0f);
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, 466.0f - cfg.wall_target_mm, 5.0f);
    CHECK_NEAR(dy, 0.0f, 5.0f);
    /* the same turned by 90 degrees (the axis along v) and seen from off the sweep's centre */
    ffr_orient_reset(&o, &odo);
    add_wall(&o, 233.0f, 0.0f, 0.0f, 1.0f);
    keep_nearest(&o, 78.0f, 466.0f + 30.0f);
    keep_nearest(&o, -68.0f, 470.0f + 30.0f);
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 30.0f, &dx, &dy);
    CHECK_NEAR(dy, 466.0f - cfg.wall_target_mm, 5.0f);
    CHECK_NEAR(dx, 0.0f, 5.0f);
    /* hits on one side of the axis only: a wall's end, no wall across */
    CHECK_NEAR(centre_dx_of_two(&cfg, 466.0f, 78.0f, 468.0f, 120.0f), 0.0f, 0.5f);
    /* either side, one read 21 % farther (two parts, one short, one long:
     * fresh start seed 372): one wall across, stood off the nearer */
    CHECK_NEAR(centre_dx_of_two(&cfg, 471.0f, 45.0f, 572.0f, -106.0f), 471.0f - cfg.wall_target_mm, 5.0f);
    /* either side, but farther apart than 30 mm + 25 % of the nearer: two walls' ends, none across */
    CHECK_NEAR(centre_dx_of_two(&cfg, 466.0f, 78.0f, 466.0f + 30.0f + 0.25f * 466.0f + 8.0f, -68.0f), 0.0f, 0.5f);
    /* farther off the axis than 15 degrees: not taken for a wall across */
    CHECK_NEAR(centre_dx_of_two(&cfg, 466.0f, 140.0f, 466.0f, -140.0f), 0.0f, 0.5f);
    /* a wall across read long, within the reach: stood at wall_target_mm from as read */
    ffr_orient_reset(&o, &odo);
    add_wall(&o, reach - 10.0f, 0.0f, 0.0f, 1.0f);
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, reach - 10.0f - cfg.wall_target_mm, 5.0f);
    /* beyond it: a far wall, no shift */
    ffr_orient_reset(&o, &odo);
    add_wall(&o, reach + 10.0f, 0.0f, 0.0f, 1.0f);
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, 0.0f, 0.5f);
}

/* the 2004 home hallway as a sweep from its centre records it (the test
 * below) */
static void home_hallway_seen(ffr_home_orient_t *o, ffr_odometry_t *odo)
{
    ffr_odometry_reset(odo);
    ffr_orient_reset(o, odo);
    add_stretch(o, 360.0f, -800.0f, 360.0f, 800.0f, 1.0f);
    add_stretch(o, -800.0f, -280.0f, 360.0f, -280.0f, 1.0f);
    add_stretch(o, -80.0f, 200.0f, -80.0f, 800.0f, 1.0f);
    add_stretch(o, -800.0f, 200.0f, -80.0f, 200.0f, 1.0f);
}

TEST(a_far_wall_read_short_does_not_shut_the_way_along_the_hallway)
{
    /* the 2004 home hallway seen from the sweep's centre: its outer wall
     * 360 mm east, the south wall 280 mm south, the island room's corner 80
     * mm west and 200 mm north (its side runs north, its bottom west). The
     * robot stands 130 mm east of the centre, in the hallway's middle, after
     * the shift. One bin holds a lone hit 96 mm west of the way north's axis,
     * `ahead` mm north: the north wall, ~740 mm off, read short (start seed
     * 9649 of the orientation bench: 526 mm). A hit that far may be 25 %
     * farther (RANGE_SHORT_FRAC): beyond the reach (2 wall_target_mm + half
     * width, 560 mm) it shuts no way, and north is the way; nearer, it may be
     * a wall's end in the body's path band, and north stays shut: west, its
     * island wall on the right, is then the one open way */
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float ahead;
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    for (ahead = 400.0f; ahead <= 560.0f; ahead += 20.0f) {
        int way;
        home_hallway_seen(&o, &odo);
        keep_nearest(&o, 130.0f - 96.0f, ahead);
        way = ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 130.0f, 0.0f);
        CHECK(way == ((1.0f + RANGE_SHORT_FRAC_BUILT) * ahead < 2.0f * cfg.wall_target_mm + cfg.body_half_width_mm
                          ? 2
                          : 1));
    }
    /* the hit grown along its ray from the sweep's centre, not from the
     * robot: standing 100 mm north of the centre, a hit 540 mm north of the
     * centre (440 mm ahead of the robot) may be 675 mm off the centre, 575
     * mm ahead: beyond the reach, north stays the way (grown from the robot,
     * 550 mm, it would shut it) */
    home_hallway_seen(&o, &odo);
    keep_nearest(&o, 130.0f - 96.0f, 540.0f);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 130.0f, 100.0f) == 1);
}

TEST(a_junction_read_short_keeps_the_way_with_its_wall)
{
    /* the 2004 home's junction: the outer wall 280 mm east, the hallway's
     * wall 230 mm south, the island room's corner 150 mm west and 225 mm
     * north of the robot (its side runs north, its bottom west). North is
     * open with the outer wall on the right; west is open with no wall
     * beside the body on its right (the island's bottom starts 150 mm on).
     * Every ranger reads 20 % short, as an uncalibrated GP2D12 may: the
     * island's side is seen 120 mm off the north axis, inside the body's
     * path band (130 mm), and its corner 120 mm along west, as if beside. */
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float f;
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    for (f = 0.8f; f <= 1.01f; f += 0.1f) {
        ffr_odometry_reset(&odo);
        ffr_orient_reset(&o, &odo);
        add_stretch(&o, 280.0f, -800.0f, 280.0f, 800.0f, f);
        add_stretch(&o, -800.0f, -230.0f, 280.0f, -230.0f, f);
        add_stretch(&o, -150.0f, 225.0f, -150.0f, 800.0f, f);
        add_stretch(&o, -800.0f, 225.0f, -150.0f, 225.0f, f);
        /* north (k = 1), from any heading */
        CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 1);
        CHECK(ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 0.0f, 0.0f) == 1);
        CHECK(ffr_orient_choose(&o, &cfg, 0.0f, -0.5f * PI_F, 0.0f, 0.0f) == 1);
        /* a wall across north 400 mm on (read short too) shuts it: west,
         * its island wall on the right, is then the one open way */
        add_stretch(&o, -800.0f, 400.0f, 800.0f, 400.0f, f);
        CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 2);
    }
}

TEST(a_narrow_hallway_off_its_middle_is_a_way)
{
    /* the junction again, the hallway north narrowed (a jittered arena):
     * the island's side read 90 mm west of the body's axis, 112 mm if read
     * 25 % short: inside its path band (130 mm) either way, clear of the
     * body (100 mm) as far out as it may be; the outer wall 255 mm east.
     * North is still the way (the wall following takes the body to its
     * line, 230 mm off the outer wall); west, with no wall beside the body
     * on its right, is not. */
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    ffr_odometry_reset(&odo);
    ffr_orient_reset(&o, &odo);
    add_stretch(&o, 255.0f, -800.0f, 255.0f, 800.0f, 1.0f);
    add_stretch(&o, -800.0f, -230.0f, 255.0f, -230.0f, 1.0f);
    add_stretch(&o, -90.0f, 175.0f, -90.0f, 800.0f, 1.0f);
    add_stretch(&o, -800.0f, 175.0f, -90.0f, 175.0f, 1.0f);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 1);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, PI_F, 0.0f, 0.0f) == 1);
    /* standing 40 mm farther west, the island's corner 50 mm off the axis
     * (62 mm if read short): in front of the body, north is shut; the only
     * open way is west */
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.5f * PI_F, -40.0f, 0.0f) == 2);
}

/* aimint's one-tick aim (branch aimint, 4d61471, AIM_PARTS 1): the
 * reference the firmware's faster scan (its bins turned into the walls'
 * frame once, distances compared by their bits, the hits beyond twice the
 * band off an axis skipped) must decide as. Since 30 Nov a side's hit
 * counts within the reach as far along as it may be (lu, lv), in both */
static int ref_choose(const ffr_home_orient_t *o, const ffr_config_t *cfg, float dir0, float heading, float cx,
                      float cy)
{
    float acc[20];
    float band = cfg->body_half_width_mm + 30.0f, grow = RANGE_SHORT_FRAC_BUILT, slope = 0.0875f;
    float reach = 2.0f * cfg->wall_target_mm + cfg->body_half_width_mm, near = cfg->open_mm;
    float c = ffr_cosf(dir0), s = ffr_sinf(dir0), cu = cx * c + cy * s, cv = cy * c - cx * s;
    float best_turn = 0.0f, best_beside = 65535.0f;
    int b, i, k, best = -1, best_score = -1, side = cfg->home_wall_side == FFR_HOME_WALL_LEFT ? 0 : 1;
    for (i = 0; i < 20; ++i) {
        acc[i] = 65535.0f;
    }
#define REF_MIN(i, x) acc[i] = (x) < acc[i] ? (x) : acc[i]
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        float u0, v0, u, v, au, av, lu, lv, gu, gv;
        if (o->bin_mm[b] == 0xFFFFu) {
            continue;
        }
        u0 = o->bin_x_mm[b] * c + o->bin_y_mm[b] * s;
        v0 = o->bin_y_mm[b] * c - o->bin_x_mm[b] * s;
        u = u0 - cu;
        v = v0 - cv;
        gu = ffr_absf(u + grow * u0);
        gv = ffr_absf(v + grow * v0);
        au = ffr_absf(u);
        av = ffr_absf(v);
        lu = gu > au ? gu : au;
        lv = gv > av ? gv : av;
        if (lv < band - slope * au) {
            REF_MIN(u > 0.0f ? 0 : 2, au);
        }
        if (lu < band - slope * av) {
            REF_MIN(v > 0.0f ? 1 : 3, av);
        }
        /* a side's hit within the reach as far along as it may be too */
        if (lu < reach) {
            REF_MIN(4 + 2 * (u > 0.0f ? 0 : 2) + ((v > 0.0f) == (u > 0.0f) ? 0 : 1), lv);
        }
        if (lv < reach) {
            REF_MIN(4 + 2 * (v > 0.0f ? 1 : 3) + ((u < 0.0f) == (v > 0.0f) ? 0 : 1), lu);
        }
        if (av < near) {
            REF_MIN(12 + (v > 0.0f ? 0 : 1), au);
            REF_MIN(12 + 4 + (v < 0.0f ? 0 : 1), au);
        }
        if (au < near) {
            REF_MIN(12 + 2 + (u < 0.0f ? 0 : 1), av);
            REF_MIN(12 + 6 + (u > 0.0f ? 0 : 1), av);
        }
    }
#undef REF_MIN
    for (k = 0; k < 4; ++k) {
        const float *side_mm = &acc[4 + 2 * k];
        int left_wall = acc[(k + 1) & 3] < cfg->open_mm, right_wall = acc[(k + 3) & 3] < cfg->open_mm, score;
        float turn = ffr_absf(ffr_wrap_pi(dir0 + (float)k * 0.5f * PI_F - heading));
        float beside = (cfg->home_wall_side == FFR_HOME_WALL_LEFT || cfg->home_wall_side == FFR_HOME_WALL_RIGHT)
                           ? acc[12 + 2 * k + side]
                           : 0.0f;
        if (side_mm[0] < cfg->body_half_width_mm || side_mm[1] < cfg->body_half_width_mm ||
            side_mm[0] + side_mm[1] < 2.0f * band) {
            continue;
        }
        score = cfg->home_wall_side == FFR_HOME_WALL_LEFT    ? left_wall
                : cfg->home_wall_side == FFR_HOME_WALL_RIGHT ? right_wall
                                                             : left_wall + right_wall;
        if (score > best_score || (score == best_score && (beside < best_beside - 40.0f ||
                                                           (beside <= best_beside + 40.0f && turn < best_turn)))) {
            best = k;
            best_score = score;
            best_turn = turn;
            best_beside = beside;
        }
    }
    return best;
}

static uint32_t lcg_next(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

static float lcg_uniform(uint32_t *s, float lo, float hi)
{
    return lo + (hi - lo) * (float)(lcg_next(s) % 10001u) / 10000.0f;
}

TEST(the_aim_decides_as_aimints_one_tick_aim)
{
    /* random junctions: up to four walls' stretches at random distances
     * (some inside a hallway's width, some off the axes, a few bins empty),
     * read 0.75..1 of their distance; random walls' direction, heading and
     * robot offset, each wall side rule, open_mm below and above a
     * hallway's width (560 mm) */
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    uint32_t seed = 2026u;
    int n, open = 0, shut = 0;
    ffr_config_default(&cfg);
    for (n = 0; n < 3000; ++n) {
        float f = lcg_uniform(&seed, 0.75f, 1.0f), dir0 = lcg_uniform(&seed, -PI_F, PI_F);
        float e = lcg_uniform(&seed, 150.0f, 700.0f), so = lcg_uniform(&seed, -700.0f, -150.0f);
        float we = lcg_uniform(&seed, -700.0f, -150.0f), no = lcg_uniform(&seed, 150.0f, 700.0f);
        float cx = lcg_uniform(&seed, -60.0f, 60.0f), cy = lcg_uniform(&seed, -60.0f, 60.0f);
        float heading = lcg_uniform(&seed, -PI_F, PI_F), c = ffr_cosf(dir0), s = ffr_sinf(dir0);
        int b, r, want;
        cfg.home_wall_side = (uint8_t)(n % 3 == 0 ? FFR_HOME_WALL_LEFT : n % 3 == 1 ? FFR_HOME_WALL_RIGHT
                                                                                    : FFR_HOME_WALL_ANY);
        /* a team's calibration may have open_mm beyond a hallway's width */
        cfg.open_mm = n % 5 == 4 ? 650.0f : 400.0f;
        ffr_odometry_reset(&odo);
        ffr_orient_reset(&o, &odo);
        /* in the walls' frame, then turned by dir0 into odometry's */
        add_stretch(&o, e, lcg_uniform(&seed, -800.0f, 0.0f), e, lcg_uniform(&seed, 0.0f, 800.0f), f);
        add_stretch(&o, lcg_uniform(&seed, -800.0f, 0.0f), so, lcg_uniform(&seed, 0.0f, 800.0f), so, f);
        if (n & 4) {
            add_stretch(&o, we, lcg_uniform(&seed, -800.0f, 0.0f), we, lcg_uniform(&seed, 0.0f, 800.0f), f);
        }
        if (n & 8) {
            add_stretch(&o, lcg_uniform(&seed, -800.0f, 0.0f), no, lcg_uniform(&seed, 0.0f, 800.0f), no, f);
        }
        for (b = 0; b < FFR_ORIENT_BINS; ++b) {
            float x = o.bin_x_mm[b], y = o.bin_y_mm[b];
            o.bin_x_mm[b] = x * c - y * s;
            o.bin_y_mm[b] = x * s + y * c;
        }
        want = ref_choose(&o, &cfg, dir0, heading, cx, cy);
        r = ffr_orient_choose(&o, &cfg, dir0, heading, cx, cy);
        CHECK(r == want);
        /* the firmware's own: the bins turned once, then aimed from */
        ffr_orient_to_walls(&o, dir0);
        CHECK(ffr_orient_aim(&o, &cfg, dir0, heading, cx, cy) == want);
        open += want >= 0;
        shut += want < 0;
    }
    CHECK(open > 1000 && shut > 100); /* both kinds of case were met */
}

#define ORIENT_PH_CENTRE 1u /* home_orient.c's PH_CENTRE */
#define ORIENT_PH_AIM 4u    /* home_orient.c's PH_AIM */
#define ORIENT_PH_TURN 5u   /* home_orient.c's PH_TURN */

TEST(the_aim_turns_on_its_own_tick)
{
    /* the centre's tick turns the bins into the walls' frame and decides
     * the shift; the aim's tick (the next, no shift) decides and starts
     * the turn: the start's timing as before the aim's rule grew. A
     * hallway along x, both ways open, walls either side 230 mm off: the
     * smaller turn (east) */
    ffr_state_t st;
    ffr_config_default(&st.cfg);
    st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
    ffr_odometry_reset(&st.odo);
    ffr_orient_reset(&st.orient, &st.odo);
    add_stretch(&st.orient, -700.0f, 230.0f, 700.0f, 230.0f, 1.0f);
    add_stretch(&st.orient, -700.0f, -230.0f, 700.0f, -230.0f, 1.0f);
    st.orient.dir0_rad = 0.0f;
    st.orient.phase = ORIENT_PH_CENTRE;
    st.cmd_v_mm_s = 0.0f;
    st.cmd_w_rad_s = 0.0f;
    st.odo.heading_rad = 0.2f;
    CHECK(ffr_orient_step(&st) == 0);
    CHECK(st.orient.phase == ORIENT_PH_AIM);
    CHECK(st.orient.bin_x_mm[9] > 60000.0f || ffr_absf(st.orient.bin_y_mm[9]) <= 231.0f); /* turned (dir0 0: as is) */
    CHECK(ffr_orient_step(&st) == 0);
    CHECK(st.orient.phase == ORIENT_PH_TURN);
    CHECK(ffr_cosf(st.orient.target_rad) > 0.99f);
}

#define ORIENT_PH_SHIFT_TURN 2u  /* home_orient.c's PH_SHIFT_TURN */
#define ORIENT_PH_SHIFT_DRIVE 3u /* home_orient.c's PH_SHIFT_DRIVE */
#define ORIENT_PH_DONE 6u        /* home_orient.c's PH_DONE */

/* odometry's wheel speeds of a body spinning at w (rad/s, + to the left) */
static void spin_at(ffr_state_t *st, float w)
{
    st->odo.v_mm_s[0] = -0.5f * w * st->cfg.track_width_mm;
    st->odo.v_mm_s[1] = 0.5f * w * st->cfg.track_width_mm;
}

TEST(the_shifts_turn_is_not_done_while_the_body_still_spins)
{
    /* the sweep ends at its full rate (200 degrees/s); a shift's direction
     * within 2 degrees of the heading there was reached at once, and the
     * body spun on ~30 degrees as the shift began backing (jittered start
     * seed 5884). Within the 2 degrees the shift's turn ends only below 160
     * degrees/s, turning toward its target until then; the aim's turn ends
     * within them at any rate, as before */
    static const float spins[6] = {-200.0f, 200.0f, -170.0f, 165.0f, -150.0f, 150.0f}; /* degrees/s */
    ffr_config_t cfg;
    rig_t r;
    int k, j;
    ffr_config_default(&cfg);
    for (k = 0; k < 2; ++k) {
        for (j = 0; j < 6; ++j) {
            rig_init(&r, &cfg);
            rig_tick(&r); /* the readings in: no walls */
            ffr_orient_begin(&r.st);
            r.st.orient.phase = k == 0 ? ORIENT_PH_SHIFT_TURN : ORIENT_PH_TURN;
            r.st.orient.reverse = 0u;
            r.st.orient.target_rad = r.st.odo.heading_rad + 1.5f * FFR_DEG;
            r.st.orient.goal_mm = 100.0f;
            spin_at(&r.st, spins[j] * FFR_DEG);
            ffr_orient_step(&r.st);
            if (k == 1) {
                CHECK(r.st.orient.phase == ORIENT_PH_DONE);
            } else if (j < 4) {
                CHECK(r.st.orient.phase == ORIENT_PH_SHIFT_TURN);
                CHECK(r.st.cmd_w_rad_s > 0.0f); /* toward the target, left */
            } else {
                CHECK(r.st.orient.phase == ORIENT_PH_SHIFT_DRIVE); /* braked below 160: there */
            }
        }
    }
}

TEST(the_firmware_orients_before_the_route)
{
    ffr_config_t cfg;
    rig_t r;
    int i, seen_orient = 0;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    r.in.start = 1;
    /* nothing in range anywhere: the robot sweeps, finds no wall to go by,
     * returns to the heading it was placed in and starts the route there */
    for (i = 0; i < 600 && r.out.state != FFR_ST_FOLLOW; ++i) {
        rig_tick(&r);
        if (r.out.state == FFR_ST_ORIENT) {
            ++seen_orient;
            CHECK(r.out.fan == 0);
        }
    }
    CHECK(seen_orient > 20);
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.out.step == 0);
    /* odometry's frame: heading 0 is the route's first direction */
    CHECK_NEAR(r.st.route.heading_ref_rad, 0.0f, 1e-6);
    CHECK_NEAR(r.st.odo.heading_rad, 0.0f, 3.0f * FFR_DEG);

    /* as placed: no orientation at all */
    rig_init(&r, &cfg);
    r.in.start = 1;
    rig_tick(&r);
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_FOLLOW);
}

/* the five rangers' readings at a pose among the rig's walls, as the
 * firmware's conversion gives them (closer than ir_min_mm reads ir_min_mm) */
static void readings(const ffr_config_t *cfg, const rig_walls_t *w, float x, float y, float th,
                     float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        ir[i] = rig_beam_mm(cfg, w, i, x, y, th);
        if (ffr_ir_valid(cfg, ir[i]) || ir[i] < cfg->ir_min_mm) {
            ir[i] = ir[i] < cfg->ir_min_mm ? cfg->ir_min_mm : ir[i];
        }
    }
}

TEST(the_nearest_wall_from_the_five_rangers)
{
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT], d, nx, ny;
    float gap;
    ffr_config_default(&cfg);
    CHECK_NEAR(ffr_orient_turn_radius_mm(&cfg), 156.2f, 0.1f);
    /* a wall along the left side, from touching the body (100 mm) to well
     * clear: the left pair's line gives its distance and side */
    for (gap = 105.0f; gap <= 300.0f; gap += 5.0f) {
        rig_walls_t w = {0.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        w.left_y = gap;
        readings(&cfg, &w, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ffr_orient_clearance(&cfg, rig_geom(&g, &cfg, ir), ir, &d, &nx, &ny));
        if (gap >= 190.0f) {
            /* beyond the turning radius + margin: no threat reported */
            CHECK(d >= ffr_orient_turn_radius_mm(&cfg) + 20.0f);
        } else if (gap >= 150.0f) {
            /* both side rangers in their span: the wall's own distance */
            CHECK_NEAR(d, gap, 2.0f);
        } else {
            /* closer than the rangers' span: never reported farther than
             * the turning radius */
            CHECK(d < ffr_orient_turn_radius_mm(&cfg));
        }
        if (gap < 190.0f) {
            CHECK(ny > 0.9f);
        }
    }
    /* the same on the right, ahead and behind, at every distance: a wall
     * within the turning radius + 20 mm reported no farther than it is, on
     * its side; beyond, no threat */
    for (gap = 125.0f; gap <= 300.0f; gap += 5.0f) {
        /* beyond the turning radius + margin, and beyond the centre
         * ranger's shortest range (nearer it reads its shortest: taken as
         * half of it, as near as that may be) */
        float far = ffr_orient_turn_radius_mm(&cfg) + 20.0f;
        int k;
        if (far < cfg.ir_x_mm[FFR_IR_CF] + cfg.ir_min_mm + 5.0f) {
            far = cfg.ir_x_mm[FFR_IR_CF] + cfg.ir_min_mm + 5.0f;
        }
        for (k = 0; k < 3; ++k) {
            rig_walls_t w = {2000.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
            float th = 0.0f;
            if (k == 0) {
                w.right_y = -gap;
            } else {
                w.ahead_x = gap; /* k == 2: facing away from it */
                th = k == 2 ? PI_F : 0.0f;
            }
            readings(&cfg, &w, 0.0f, 0.0f, th, ir);
            if (!ffr_orient_clearance(&cfg, rig_geom(&g, &cfg, ir), ir, &d, &nx, &ny)) {
                CHECK(gap >= far); /* a wall this close is always seen */
            } else if (gap < ffr_orient_turn_radius_mm(&cfg) + 20.0f) {
                CHECK(d <= gap + 2.0f);
                CHECK(k != 0 || ny < -0.9f);
                CHECK(k != 1 || nx > 0.9f);
                CHECK(k != 2 || nx < -0.9f);
            } else if (gap >= far) {
                CHECK(d >= ffr_orient_turn_radius_mm(&cfg) + 20.0f);
            }
        }
    }
    /* nothing within range: nothing to report */
    rig_no_walls(&cfg, ir);
    CHECK(!ffr_orient_clearance(&cfg, rig_geom(&g, &cfg, ir), ir, &d, &nx, &ny));
}

/* The whole firmware at home beside a wall it cannot turn next to: the
 * rig's drive is exact, so odometry is the true pose; the body (120 mm
 * ahead, 100 mm behind, 100 mm either side) must never reach a wall while
 * the robot orients, and it must orient and start the route. */
/* the default body's corners (body frame, mm) */
static const float k_corner_x[4] = {120.0f, 120.0f, -100.0f, -100.0f};
static const float k_corner_y[4] = {100.0f, -100.0f, 100.0f, -100.0f};

/* corner k of the body at (x, y, th) in the world frame */
static void body_corner(int k, float x, float y, float th, float *px, float *py)
{
    float c = ffr_cosf(th), s = ffr_sinf(th);
    *px = x + c * k_corner_x[k] - s * k_corner_y[k];
    *py = y + s * k_corner_x[k] + c * k_corner_y[k];
}

static int body_clear(const rig_walls_t *w, float x, float y, float th)
{
    int k;
    for (k = 0; k < 4; ++k) {
        float px, py;
        body_corner(k, x, y, th, &px, &py);
        if (py >= w->left_y || py <= w->right_y || (w->ahead_x != 0.0f && px >= w->ahead_x)) {
            return 0;
        }
    }
    return 1;
}

static int orient_among(const rig_walls_t *w, float th0)
{
    ffr_config_t cfg;
    rig_t r;
    float ir[FFR_IR_COUNT];
    int i, clear = 1, escaped = 0;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
    r.st.odo.heading_rad = th0;
    r.in.start = 1;
    for (i = 0; i < 1500; ++i) {
        readings(&cfg, w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        if (r.out.state != FFR_ST_ORIENT && i > 2) {
            break;
        }
        escaped |= r.st.orient.escapes > 0u;
        clear &= body_clear(w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
    }
    CHECK(r.out.state == FFR_ST_FOLLOW);
    return clear ? (escaped ? 2 : 1) : 0;
}

TEST(room_to_turn_first_then_the_sweep)
{
    ffr_config_t cfg;
    float gap, th;
    ffr_config_default(&cfg);
    /* a hallway 460 mm wide, the robot placed anywhere across it at any
     * heading its body fits (every 15 degrees): no contact while it
     * orients; closer to a wall than its turning radius it moves away
     * first. Not yet: facing along the hallway closer than 145 mm to a
     * wall (docs/firmware.md, "Start") */
    for (gap = 105.0f; gap <= 230.0f; gap += 5.0f) {
        for (th = 0.0f; th < 2.0f * PI_F - 0.01f; th += PI_F / 12.0f) {
            rig_walls_t w = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
            int res, along = ffr_absf(ffr_wrap_pi(2.0f * th)) < 0.2f;
            w.left_y = gap;
            w.right_y = gap - 460.0f;
            if (!body_clear(&w, 0.0f, 0.0f, th) || (along && gap < 145.0f)) {
                continue; /* it cannot be placed there; or the case not handled */
            }
            res = orient_among(&w, th);
            CHECK(res != 0);
            if (gap + 2.0f < ffr_orient_turn_radius_mm(&cfg)) {
                CHECK(res == 2);
            }
        }
    }
    /* a wall 20 mm off the front: straight back, then the sweep */
    {
        rig_walls_t w = {230.0f, -230.0f, 140.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        CHECK(orient_among(&w, 0.0f) == 2);
    }
}


/* The whole firmware beside one wall to the right of the way to go (+x),
 * as the 2004 arena's home, placed facing any way: it faces +x at the end,
 * no corner of the body reaches the wall, and it ends end_y off where it
 * was placed (gap - 230: it stands wall_target_mm off the wall). */
static void beside_one_wall(float gap, float end_y)
{
    ffr_config_t cfg;
    float th;
    ffr_config_default(&cfg);
    for (th = 0.0f; th < 2.0f * PI_F - 0.01f; th += PI_F / 12.0f) {
        rig_walls_t w = {5000.0f, -gap, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        rig_t r;
        float ir[FFR_IR_COUNT];
        float last_y = 0.0f, last_th = th;
        int i, clear = 1;
        rig_init(&r, &cfg);
        r.st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
        r.st.odo.heading_rad = th;
        r.in.start = 1;
        for (i = 0; i < 1500; ++i) {
            readings(&cfg, &w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
            feed(&r, &cfg, ir);
            last_y = r.st.odo.y_mm;
            last_th = r.st.odo.heading_rad;
            rig_tick(&r);
            if (r.out.state != FFR_ST_ORIENT && i > 2) {
                break;
            }
            clear &= body_clear(&w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
        }
        CHECK(r.out.state == FFR_ST_FOLLOW);
        CHECK(clear);
        CHECK_NEAR(last_y, end_y, 20.0f);
        CHECK(ffr_cosf(last_th) > ffr_cosf(8.0f * FFR_DEG));
    }
}

TEST(a_small_shift_across_the_way_is_not_made)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    ffr_odometry_t odo;
    float dx, dy;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&odo);
    ffr_orient_reset(&o, &odo);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    /* the 2004 arena's home: the east wall 310 mm off, the island room's
     * corner 150 mm west and 230 mm north; the way is north (k = 1) */
    add_wall(&o, 310.0f, 0.0f, 0.0f, 1.0f);
    {
        int b;
        for (b = 0; b < 30; ++b) { /* the island room's bottom wall, west of its corner */
            float x = -150.0f - 20.0f * (float)b, y = 230.0f;
            float a = ffr_atan2f(y, x);
            int bin = (int)(a / (2.0f * PI_F / (float)FFR_ORIENT_BINS));
            float r = ffr_sqrtf(x * x + y * y);
            if (bin < FFR_ORIENT_BINS && r < (float)o.bin_mm[bin]) {
                o.bin_mm[bin] = (uint16_t)r;
                o.bin_x_mm[bin] = x;
                o.bin_y_mm[bin] = y;
            }
        }
    }
    ffr_orient_centre(&o, &cfg, 0.0f, 0.0f, 0.0f, &dx, &dy);
    CHECK_NEAR(dx, 80.0f, 15.0f);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.5f * PI_F, dx, dy) == 1);
    /* 80 mm across it: not made with 100, made with 0 or 60 */
    {
        /* ffr_orient_skip reads the bins in the walls' frame, as the centre's tick leaves them */
        ffr_home_orient_t t = o;
        ffr_orient_to_walls(&t, 0.0f);
        CHECK(ffr_orient_skip(&t, &cfg, 0.0f, 0.5f * PI_F, 0.0f, 0.0f, dx, dy, 100.0f) == 1);
        CHECK(ffr_orient_skip(&t, &cfg, 0.0f, 0.5f * PI_F, 0.0f, 0.0f, dx, dy, 60.0f) == -1);
        CHECK(ffr_orient_skip(&t, &cfg, 0.0f, 0.5f * PI_F, 0.0f, 0.0f, dx, dy, 0.0f) == -1);
        /* along the way to go it is never skipped beyond 40 mm */
        CHECK(ffr_orient_skip(&t, &cfg, 0.0f, 0.5f * PI_F, 0.0f, 0.0f, dx, dy + 60.0f, 100.0f) == -1);
    }
    /* the whole firmware as built (FFR_HOME_SKIP_MM, default 0): every
     * shift over 40 mm is made */
    if (FFR_HOME_SKIP_MM_BUILT == 0.0f) {
        beside_one_wall(310.0f, -310.0f + cfg.wall_target_mm);
    }
    beside_one_wall(420.0f, -420.0f + cfg.wall_target_mm);
}

/* A GP2D12 closer to a wall than its span's bottom (rig: 55 mm .. 100 mm
 * reads ir_min_mm, 30 .. 55 mm folds back to read 100 .. 185 mm, chosen as
 * the simulated part's curve, docs/sensors.md) */
static float folded_mm(const ffr_config_t *cfg, float d)
{
    if (d >= cfg->ir_min_mm || !ffr_ir_valid(cfg, d)) {
        return d;
    }
    if (d >= 55.0f) {
        return cfg->ir_min_mm;
    }
    return cfg->ir_min_mm + (55.0f - (d < 30.0f ? 30.0f : d)) * 3.4f;
}

static void readings_folded(const ffr_config_t *cfg, const rig_walls_t *w, float x, float y, float th,
                            float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        ir[i] = folded_mm(cfg, rig_beam_mm(cfg, w, i, x, y, th));
    }
}

/* The whole firmware orienting from heading th0 among the walls w, read
 * folded back (readings_folded), home_wall_side `side`, until it leaves
 * ORIENT (or 1500 ticks): 1 if the body never met a wall on the way; r's
 * state is where it ended. `straight` (NULL: not wanted): how far it went
 * straight before its first turn, -1 if it never turned */
static int orient_folded(rig_t *r, const ffr_config_t *cfg, const rig_walls_t *w, float th0, uint8_t side,
                         float *straight)
{
    float ir[FFR_IR_COUNT];
    float x0, y0;
    int i, clear = 1;
    rig_init(r, cfg);
    r->st.cfg.home_wall_side = side;
    r->st.odo.heading_rad = th0;
    r->in.start = 1;
    x0 = r->st.odo.x_mm;
    y0 = r->st.odo.y_mm;
    if (straight) {
        *straight = -1.0f;
    }
    for (i = 0; i < 1500; ++i) {
        readings_folded(cfg, w, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad, ir);
        feed(r, cfg, ir);
        rig_tick(r);
        if (straight && *straight < 0.0f && ffr_absf(r->st.odo.heading_rad - th0) > 2.0f * FFR_DEG) {
            *straight = ffr_sqrtf((r->st.odo.x_mm - x0) * (r->st.odo.x_mm - x0) +
                                  (r->st.odo.y_mm - y0) * (r->st.odo.y_mm - y0));
        }
        if (r->out.state != FFR_ST_ORIENT && i > 2) {
            break;
        }
        clear &= body_clear(w, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad);
    }
    return clear;
}

TEST(a_reading_that_may_be_folded_back_counts_as_near)
{
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT], d, nx, ny;
    float gap;
    ffr_config_default(&cfg);
    /* across the fold-back span and beyond: which readings are suspects */
    rig_no_walls(&cfg, ir);
    CHECK(ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM) == 0u);
    ir[FFR_IR_RR] = cfg.ir_min_mm;
    CHECK(ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM) == 0u); /* the bottom: near anyway */
    ir[FFR_IR_RR] = 0.5f * (cfg.ir_min_mm + FFR_FOLD_MAX_MM);
    CHECK(ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM) == (1 << FFR_IR_RR));
    ir[FFR_IR_RR] = FFR_FOLD_MAX_MM + 1.0f;
    CHECK(ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM) == 0u);
    /* a wall square behind the body, from nearly touching to clear: the
     * rear rangers read it folded back; taken as folded it is never farther
     * than the turning radius, as read it may be well clear. Readings above
     * FFR_FOLD_MAX_MM (a wall within about 37 mm of the ranger, 7 mm of the
     * rear face) are not taken as folded back (docs/firmware.md) */
    for (gap = 2.0f; gap <= 30.0f; gap += 2.0f) {
        rig_walls_t w = {2000.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        uint8_t sus;
        w.ahead_x = 100.0f + gap; /* the rear face is 100 mm behind the axle: facing away from the wall */
        readings_folded(&cfg, &w, 0.0f, 0.0f, PI_F, ir);
        sus = ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM);
        rig_geom(&g, &cfg, ir);
        if (ir[FFR_IR_LR] > FFR_FOLD_MAX_MM && ir[FFR_IR_LR] < 200.0f) {
            CHECK(sus == 0u); /* folded back beyond the span taken: not handled */
            continue;
        }
        if (sus != 0u) {
            CHECK(ffr_orient_clearance_fold(&cfg, &g, ir, sus, 0u, sus, &d, &nx, &ny));
            CHECK(d < ffr_orient_turn_radius_mm(&cfg) + 20.0f); /* within the margin: it moves away */
            CHECK(nx < -0.5f); /* behind */
            /* and the probe's way for it: forward */
            CHECK(ffr_orient_probe_back(&g, sus) == 0);
        } else {
            /* not folded: both rear rangers at their span's bottom, near as it is */
            CHECK(ffr_orient_clearance(&cfg, &g, ir, &d, &nx, &ny));
            CHECK(d < ffr_orient_turn_radius_mm(&cfg));
        }
    }
    /* the centre ranger folded back alone: the probe goes backward */
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_CF] = 150.0f;
    CHECK(ffr_orient_probe_back(rig_geom(&g, &cfg, ir), ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM)) == 1);
    ir[FFR_IR_LR] = 150.0f; /* and a rear one too: forward */
    CHECK(ffr_orient_probe_back(rig_geom(&g, &cfg, ir), ffr_orient_fold_suspects(&cfg, ir, FFR_FOLD_MAX_MM)) == 0);
}

TEST(a_short_move_tells_folded_back_from_far)
{
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float before[FFR_IR_COUNT], after[FFR_IR_COUNT];
    float gap;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, before);
    rig_geom(&g, &cfg, before);
    /* a wall behind at any distance within the fold-back span or as far as
     * the same readings would put it; the robot moves 15 mm forward */
    for (gap = 2.0f; gap <= 150.0f; gap += 4.0f) {
        rig_walls_t w = {2000.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        uint8_t sus, genuine = 0u, folded = 0u, back = 0u;
        w.ahead_x = 100.0f + gap;
        readings_folded(&cfg, &w, 0.0f, 0.0f, PI_F, before);
        sus = ffr_orient_fold_suspects(&cfg, before, FFR_FOLD_MAX_MM);
        readings_folded(&cfg, &w, -15.0f, 0.0f, PI_F, after); /* facing -x: forward is -x */
        ffr_orient_probe_tell(&cfg, &g, 0, sus, before, after, &genuine, &folded);
        CHECK((genuine & folded) == 0u);
        if (sus == 0u) {
            CHECK(genuine == 0u && folded == 0u);
            continue;
        }
        /* every suspect told; folded back exactly where the wall is within 55 mm of the rangers */
        CHECK((genuine | folded) == sus);
        {
            int i;
            for (i = 0; i < FFR_IR_COUNT; ++i) {
                float d = rig_beam_mm(&cfg, &w, i, 0.0f, 0.0f, PI_F);
                if ((sus >> i) & 1) {
                    CHECK(((folded >> i) & 1) == (d < 55.0f ? 1 : 0));
                }
            }
        }
        /* the same move backward (toward the wall), watched from the far side */
        ffr_orient_probe_tell(&cfg, &g, 1, sus, after, before, &genuine, &back);
        (void)back;
    }
    /* a wall ahead approached: as far as read it comes nearer (genuine);
     * folded back it reads farther (folded) */
    {
        uint8_t genuine = 0u, folded = 0u;
        rig_no_walls(&cfg, before);
        rig_no_walls(&cfg, after);
        before[FFR_IR_CF] = 150.0f;
        after[FFR_IR_CF] = 140.0f;
        before[FFR_IR_LF] = 130.0f;
        after[FFR_IR_LF] = 150.0f;
        ffr_orient_probe_tell(&cfg, &g, 0, ffr_orient_fold_suspects(&cfg, before, FFR_FOLD_MAX_MM), before, after, &genuine, &folded);
        CHECK(genuine == (1 << FFR_IR_CF));
        CHECK(folded == (1 << FFR_IR_LF));
    }
}

/* The whole firmware with its back to a wall it reads folded back, at any
 * distance from 8 mm off the rear corners, facing away from it or turned up
 * to 40 degrees either way: the body never reaches the wall while it
 * orients. */
TEST(backed_up_to_a_wall_read_folded_back)
{
    ffr_config_t cfg;
    float gap, th;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM <= 0.0f) {
        /* built without the fold-back rules (the default): not exercised
         * here; `make firmware-test`'s second build (-DFFR_HOME_FOLD_MM=160.0f) runs it */
        CHECK(FFR_HOME_FOLD_MM == 0.0f);
        return;
    }
    for (gap = 8.0f; gap <= 40.0f; gap += 4.0f) { /* nearer: read above FFR_FOLD_MAX_MM */
        for (th = PI_F - 40.0f * FFR_DEG; th <= PI_F + 40.1f * FFR_DEG; th += 10.0f * FFR_DEG) {
            /* a hallway 460 mm wide along x, closed at x = ahead_x; the robot's rear toward it */
            rig_walls_t w = {230.0f, -230.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
            rig_t r;
            float c = ffr_cosf(th), s = ffr_sinf(th);
            int clear;
            /* the rear corners' farthest x: the wall that far plus the gap */
            float rear = -100.0f * c + 100.0f * ffr_absf(s);
            w.ahead_x = rear + gap;
            if (!body_clear(&w, 0.0f, 0.0f, th)) {
                continue;
            }
            clear = orient_folded(&r, &cfg, &w, th, FFR_HOME_WALL_ANY, NULL);
            CHECK(r.out.state == FFR_ST_FOLLOW);
            CHECK(clear);
        }
    }
}

/* The whole firmware as built by default (no fold-back probe), its back to
 * a wall a rear ranger reads within the fold-back span (folded back: the
 * rear corner 6-19 mm off), facing away from it or turned up to 20 degrees
 * either way: before any turn it drives straight forward the rear fold
 * move's 45 mm, and the body never reaches the wall while it orients.
 * Without the move the sweep's turn swings a rear corner out 41 mm onto it
 * (hallway start seed 57, docs/robustness.md). */
TEST(a_rear_corner_read_folded_back_moves_forward_before_the_turn)
{
    ffr_config_t cfg;
    float gap, th;
    int cases = 0;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM > 0.0f) {
        /* with the probe on, the probe does this (backed_up_to_a_wall_read_folded_back) */
        CHECK(FFR_HOME_FOLD_MM > 0.0f);
        return;
    }
    for (gap = 6.0f; gap <= 20.0f; gap += 2.0f) {
        for (th = PI_F - 20.0f * FFR_DEG; th <= PI_F + 20.1f * FFR_DEG; th += 5.0f * FFR_DEG) {
            rig_walls_t w = {2000.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
            rig_t r;
            float ir[FFR_IR_COUNT];
            float c = ffr_cosf(th), s = ffr_sinf(th);
            float straight;
            int i, clear, in_span = 0;
            w.ahead_x = -100.0f * c + 100.0f * ffr_absf(s) + gap; /* the rear corners' farthest x, plus the gap */
            readings_folded(&cfg, &w, 0.0f, 0.0f, th, ir);
            for (i = FFR_IR_LR; i <= FFR_IR_RR; ++i) {
                in_span |= ir[i] > cfg.ir_min_mm + 0.5f && ir[i] <= FFR_FOLD_MAX_MM;
            }
            if (!in_span) {
                continue; /* read at the span's bottom (near as it is) or above the span: other rules */
            }
            ++cases;
            clear = orient_folded(&r, &cfg, &w, th, FFR_HOME_WALL_ANY, &straight);
            CHECK(r.out.state == FFR_ST_FOLLOW);
            CHECK(clear);
            CHECK(straight >= 40.0f);
        }
    }
    CHECK(cases >= 10); /* the span is reached for many of these poses */
}

/* A front ranger reading within the fold-back span, every wall as read
 * clear of the turning circle (start seed 4694's first readings: the right
 * front corner ranger reads 128 mm, its wall 49 mm off it, the corner 1 mm
 * off the wall, docs/robustness.md "The front fold move"): before any turn
 * the robot backs straight FRONT_FOLD_MOVE_MM (30 mm), watching that
 * ranger. Without the move the sweep began at once and its turn put the
 * corner on the wall. Not with a rear ranger within the span too (the rear
 * fold move's, forward), nor with the floor behind shut. */
/* the orientation started with readings ir, at its first look (PH_CLEAR) */
static void look_from(rig_t *r, const ffr_config_t *cfg, const float ir[FFR_IR_COUNT])
{
    feed(r, cfg, ir);
    rig_tick(r);
    ffr_orient_begin(&r->st);
    r->st.started = 1;
}

enum { FRONT_ALONE, FRONT_AND_REAR, FRONT_BEHIND_SHUT };
static void front_fold_start(rig_t *r, const ffr_config_t *cfg, int kind)
{
    float ir[FFR_IR_COUNT];
    rig_init(r, cfg);
    rig_no_walls(cfg, ir);
    ir[FFR_IR_CF] = 194.0f;
    ir[FFR_IR_LF] = 326.0f;
    ir[FFR_IR_RF] = 128.0f;
    ir[FFR_IR_LR] = 243.0f;
    ir[FFR_IR_RR] = 523.0f;
    if (kind == FRONT_AND_REAR) {
        ir[FFR_IR_RR] = 120.0f;
    } else if (kind == FRONT_BEHIND_SHUT) {
        ir[FFR_IR_LR] = ir[FFR_IR_RR] = cfg->ir_min_mm; /* a wall close behind */
    }
    look_from(r, cfg, ir);
}

TEST(a_front_ranger_read_within_the_span_backs_straight_before_the_turn)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM > 0.0f) {
        CHECK(FFR_HOME_FOLD_MM > 0.0f); /* the move is off with the probe on */
        return;
    }
    for (kind = FRONT_ALONE; kind <= FRONT_BEHIND_SHUT; ++kind) {
        const ffr_home_orient_t *o = &r.st.orient;
        front_fold_start(&r, &cfg, kind);
        CHECK(ffr_orient_step(&r.st) == 0);
        if (kind == FRONT_ALONE) {
            CHECK(o->phase == 8u); /* PH_ESCAPE */
            CHECK(o->leg == 6u);   /* LEG_FOLD: straight */
            CHECK(o->reverse == 1u);
            CHECK(o->target_rad == 0.0f);
            CHECK(ffr_absf(o->goal_mm - r.st.odo.dist_mm - 30.0f) < 0.5f);
            CHECK(o->probed == (1u << FFR_IR_RF)); /* watched: a drop to the bottom is fold-back */
        } else if (kind == FRONT_AND_REAR) {
            CHECK(o->phase == 8u && o->leg == 6u);
            CHECK(o->reverse == 0u); /* the rear fold move: forward */
            CHECK(o->probed == (1u << FFR_IR_RR));
        } else {
            CHECK(!(o->phase == 8u && o->leg == 6u && o->reverse)); /* not back into that wall */
        }
    }
}

/* After the rear fold move, a rear ranger it moved away from whose reading
 * dropped to its span's bottom (or shrank) was folded back: it reads the
 * wall the move left behind, and is no reason for another move (taken as
 * read, a datasheet part at its span's bottom walked the robot on into the
 * middle hallway's mouth: held-out +-2.5 cm jitter start seed 51,
 * docs/robustness.md). The same reading with no such move before it is a
 * wall near the rear corner: an escape. A reading that grew is a wall as far
 * as read, and one that stayed is a wall along the move: both count. */
enum { FOLD_NONE, FOLD_DROPPED, FOLD_GREW, FOLD_ALONG };
static void after_fold_move(rig_t *r, const ffr_config_t *cfg, int kind)
{
    float ir[FFR_IR_COUNT];
    rig_init(r, cfg);
    rig_no_walls(cfg, ir);
    if (kind == FOLD_NONE || kind == FOLD_DROPPED) {
        ir[FFR_IR_LR] = cfg->ir_min_mm; /* the left rear ranger at its span's bottom */
    } else if (kind == FOLD_GREW) {
        ir[FFR_IR_LR] = ir[FFR_IR_RR] = 125.0f; /* a wall behind, 168 mm behind the axle */
    } else {
        ir[FFR_IR_LF] = ir[FFR_IR_LR] = 110.0f; /* a wall along the left side, 148 mm off the axis */
    }
    look_from(r, cfg, ir);
    if (kind != FOLD_NONE) {
        /* as the move's end leaves it: 45 mm forward made */
        r->st.orient.escapes = 1u;
        r->st.orient.leg = 6u; /* LEG_FOLD */
        r->st.orient.probed = (uint8_t)((1u << FFR_IR_LR) | (kind == FOLD_GREW ? 1u << FFR_IR_RR : 0u));
        r->st.orient.probe_mm[FFR_IR_LR] = kind == FOLD_DROPPED ? 120.0f : 110.0f;
        r->st.orient.probe_mm[FFR_IR_RR] = 110.0f;
    }
}

TEST(after_the_rear_fold_move_a_reading_that_did_not_grow_is_the_wall_left_behind)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM > 0.0f) {
        CHECK(FFR_HOME_FOLD_MM > 0.0f); /* the move is off with the probe on */
        return;
    }
    for (kind = FOLD_NONE; kind <= FOLD_ALONG; ++kind) {
        after_fold_move(&r, &cfg, kind);
        CHECK(ffr_orient_step(&r.st) == 0);
        if (kind == FOLD_DROPPED) {
            CHECK(r.st.orient.phase == 0u); /* PH_SWEEP: room to turn */
            CHECK(r.st.orient.escapes == 1u); /* no move more */
        } else {
            /* a wall within the turning radius + 20 mm: PH_ESCAPE, away from it */
            CHECK(r.st.orient.phase == 8u);
            CHECK(r.st.orient.escapes == (kind == FOLD_NONE ? 1u : 2u));
        }
    }
}

/* The aim's band narrows with the distance ahead: the end of a side wall
 * 48 cm ahead placed 10.5 cm off the axis by the sweep's heading error (a
 * realistic robot at the home circle: the end of room 1's east wall) does
 * not close the way, a wall straight across there still does. */
static void put_bin(ffr_home_orient_t *o, int b, float x, float y)
{
    o->bin_mm[b] = (uint16_t)ffr_sqrtf(x * x + y * y);
    o->bin_x_mm[b] = x;
    o->bin_y_mm[b] = y;
}

TEST(a_far_wall_end_beside_the_way_does_not_close_it)
{
    ffr_config_t cfg;
    ffr_home_orient_t o;
    int b;
    float f4[4];
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    for (b = 0; b < FFR_ORIENT_BINS; ++b) {
        o.bin_mm[b] = 0xFFFFu;
        o.bin_x_mm[b] = 0.0f;
        o.bin_y_mm[b] = 0.0f;
    }
    /* a wall on the right (230 mm) along the way, one behind (250 mm) */
    for (b = 0; b < 6; ++b) {
        put_bin(&o, b, -100.0f + 100.0f * (float)b, -230.0f);
    }
    put_bin(&o, 6, -250.0f, 0.0f);
    put_bin(&o, 7, -250.0f, 100.0f);
    /* ahead-left, the wall end: 482 mm along, 105 mm aside */
    put_bin(&o, 8, 482.0f, 105.0f);
    /* with the fixed band it closes the way ahead (within 560 mm) */
    ffr_orient_free4(&o, 130.0f, 0.0f, 0.0f, 0.0f, f4);
    CHECK_NEAR(f4[0], 482.0f, 0.5f);
    /* narrowed (5 degrees), the way ahead is open and chosen */
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 0);
    /* a wall straight across 440 mm ahead still closes it: even 25 %
     * farther (RANGE_SHORT_FRAC: 550 mm) it is within the reach (560 mm) */
    put_bin(&o, 9, 440.0f, 0.0f);
    put_bin(&o, 10, 440.0f, -60.0f);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) != 0);
    /* as read 482 mm ahead it may be 602 mm off, beyond the reach: it no
     * longer closes the way (30 Nov; before, any wall across within 560 mm
     * as read did: a far wall read short shut the way along the hallway,
     * a_far_wall_read_short_does_not_shut_the_way_along_the_hallway) */
    put_bin(&o, 9, 482.0f, 0.0f);
    put_bin(&o, 10, 482.0f, -60.0f);
    CHECK(ffr_orient_choose(&o, &cfg, 0.0f, 0.0f, 0.0f, 0.0f) == 0);
}

/* A wall at the front corner (the right wall steps in to 20 mm off the
 * side beyond x = 125, 5 mm ahead of the front-right corner): the front is
 * shut for an S, and nothing is seen behind, where the rear pair see no floor of the
 * body's path. The first move is straight back (no corner swung out over
 * the floor beside the rear), a later S forward; the body never reaches a
 * wall, and it orients. */
TEST(the_front_shut_straight_back_before_the_s)
{
    ffr_config_t cfg;
    rig_walls_t w = {1000.0f, -180.0f, 0.0f, 125.0f, 60.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    rig_t r;
    float ir[FFR_IR_COUNT];
    int i, clear = 1, first = -1, s_back = 0;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
    r.in.start = 1;
    for (i = 0; i < 1500; ++i) {
        float c, s;
        int k;
        readings(&cfg, &w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        if (r.out.state != FFR_ST_ORIENT && i > 2) {
            break;
        }
        if (first < 0 && r.st.orient.escapes > 0u) {
            /* the first move: straight back */
            first = r.st.orient.leg;
            CHECK(r.st.orient.reverse == 1u);
            CHECK(r.st.orient.target_rad == 0.0f);
        }
        s_back |= r.st.orient.leg == 1u && r.st.orient.reverse;
        c = ffr_cosf(r.st.odo.heading_rad);
        s = ffr_sinf(r.st.odo.heading_rad);
        for (k = 0; k < 4; ++k) {
            static const float bx[4] = {120.0f, 120.0f, -100.0f, -100.0f};
            static const float by[4] = {100.0f, -100.0f, 100.0f, -100.0f};
            float px = r.st.odo.x_mm + c * bx[k] - s * by[k];
            float py = r.st.odo.y_mm + s * bx[k] + c * by[k];
            float wall = px > w.jog_x ? w.right_y + w.jog_dy : w.right_y;
            clear &= py > wall && py < w.left_y;
        }
    }
    CHECK(first == 5); /* LEG_BACK */
    CHECK(!s_back);
    CHECK(clear);
    CHECK(r.out.state == FFR_ST_FOLLOW);
}

TEST(a_wall_line_in_the_sweep_brakes_at_once)
{
    /* the sweep at full rate, a wall's line found within the turning circle
     * (a corner beside the body comes round into a ranger's beam late): the
     * speed loop's ramp is not waited for (at 1.5 m/s2 the body turned on
     * ~20 degrees, into the corner); its references and integrals are
     * cleared, so the next output brakes against the wheels' motion */
    ffr_config_t cfg;
    rig_t r;
    int16_t pwm[2];
    float ir[FFR_IR_COUNT];
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    rig_no_walls(&cfg, ir);
    feed(&r, &cfg, ir);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    ffr_orient_begin(&r.st);
    ffr_orient_reset(&r.st.orient, &r.st.odo);
    r.st.orient.phase = 0u; /* PH_SWEEP */
    /* turning right at the sweep's rate: the wheels and their references */
    r.st.speed.v_ref[0] = 290.0f;
    r.st.speed.v_ref[1] = -290.0f;
    r.st.speed.pos_err_mm[0] = 8.0f;
    r.st.speed.pos_err_mm[1] = -8.0f;
    r.st.odo.v_mm_s[0] = 290.0f;
    r.st.odo.v_mm_s[1] = -290.0f;
    /* a wall's line seen 120 mm off on the left */
    r.st.orient.near_mm = 120.0f;
    r.st.orient.near_x_mm = 0.0f;
    r.st.orient.near_y_mm = 120.0f;
    CHECK(ffr_orient_step(&r.st) == 0);
    CHECK(r.st.orient.phase == 8u); /* PH_ESCAPE: away from it first */
    CHECK_NEAR(r.st.speed.v_ref[0], 0.0f, 1e-6f);
    CHECK_NEAR(r.st.speed.v_ref[1], 0.0f, 1e-6f);
    CHECK_NEAR(r.st.speed.pos_err_mm[0], 0.0f, 1e-6f);
    /* the next output with the wheels still turning: against them */
    ffr_speed_control(&r.st.speed, &r.st.cfg, &r.st.odo, 0.0f, 0.0f, 0.01f, pwm);
    CHECK(pwm[0] < 0);
    CHECK(pwm[1] > 0);
}

/* The sweep turning right (home_wall_side), `done` degrees into it, the
 * rangers reading ir (mm), before its tick. */
static void sweep_rig(rig_t *r, ffr_config_t *cfg, const float ir[FFR_IR_COUNT], float done_deg, uint8_t escapes)
{
    int i;
    ffr_config_default(cfg);
    rig_init(r, cfg);
    r->st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
    ffr_orient_begin(&r->st);
    ffr_orient_reset(&r->st.orient, &r->st.odo);
    r->st.orient.phase = 0u; /* PH_SWEEP */
    r->st.orient.escapes = escapes;
    r->st.odo.heading_rad = -done_deg * FFR_DEG;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        r->st.ir_mm[i] = ir[i];
    }
    ffr_ir_geom_update(&r->st.ir_geom, &r->st.cfg, r->st.ir_mm);
    r->st.speed.v_ref[0] = 290.0f;
    r->st.speed.v_ref[1] = -290.0f;
}

/* sweep_rig's sweep and one orientation tick. The phase after it. */
static uint8_t sweep_tick_reading(rig_t *r, ffr_config_t *cfg, const float ir[FFR_IR_COUNT], float done_deg,
                                  uint8_t escapes)
{
    sweep_rig(r, cfg, ir, done_deg, escapes);
    CHECK(ffr_orient_step(&r->st) == 0);
    return r->st.orient.phase;
}

TEST(a_ranger_on_the_sweeps_side_at_its_bottom_stops_the_sweep)
{
    /* turning right, a right ranger comes down to its span's bottom: a
     * face just off that corner, whose wall runs on toward the body. A
     * hard stop, then straight away from it: back from the front corner's,
     * forward from the rear corner's. Over the turn's extent and the
     * ranger's bottom reading and just above it */
    static const int side[2] = {FFR_IR_RF, FFR_IR_RR};
    static const float done[3] = {5.0f, 40.0f, 90.0f};
    unsigned k, j;
    for (k = 0; k < 2; ++k) {
        for (j = 0; j < 3; ++j) {
            ffr_config_t cfg;
            rig_t r;
            float ir[FFR_IR_COUNT];
            ffr_config_default(&cfg);
            rig_no_walls(&cfg, ir);
            ir[side[k]] = 100.0f; /* ir_min_mm: the span's bottom */
            CHECK(sweep_tick_reading(&r, &cfg, ir, done[j], 0u) == 8u); /* PH_ESCAPE */
            CHECK(r.st.orient.escapes == 1u);
            CHECK(r.st.orient.leg == 0u);                                /* straight */
            CHECK(r.st.orient.reverse == (side[k] == FFR_IR_RF ? 1u : 0u)); /* away from it */
            CHECK(r.st.orient.goal_mm - r.st.odo.dist_mm > 40.0f && r.st.orient.goal_mm - r.st.odo.dist_mm < 55.0f);
            CHECK_NEAR(r.st.speed.v_ref[0], 0.0f, 1e-6f); /* the hard stop */
            CHECK_NEAR(r.st.speed.v_ref[1], 0.0f, 1e-6f);
            /* a part reading 2 mm above the bottom: the sweep turns on */
            ir[side[k]] = 102.0f;
            CHECK(sweep_tick_reading(&r, &cfg, ir, done[j], 0u) == 0u);
            CHECK(r.st.cmd_w_rad_s < 0.0f);
        }
    }
}

TEST(a_ranger_at_its_bottom_off_the_sweeps_side_or_late_does_not_stop_it)
{
    ffr_config_t cfg;
    rig_t r;
    float ir[FFR_IR_COUNT];
    int i;
    /* the other side's (the turn takes its corners away) and the centre's */
    static const int others[3] = {FFR_IR_LF, FFR_IR_LR, FFR_IR_CF};
    ffr_config_default(&cfg);
    for (i = 0; i < 3; ++i) {
        rig_no_walls(&cfg, ir);
        ir[others[i]] = 100.0f;
        CHECK(sweep_tick_reading(&r, &cfg, ir, 40.0f, 0u) == 0u);
        CHECK(r.st.cmd_w_rad_s < 0.0f);
    }
    /* on the turn's first degree: the clearance judged what was read before it */
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RF] = 100.0f;
    CHECK(sweep_tick_reading(&r, &cfg, ir, 0.5f, 0u) == 0u);
    /* the escapes spent: the sweep goes ahead regardless */
    CHECK(sweep_tick_reading(&r, &cfg, ir, 40.0f, FFR_ORIENT_ESCAPE_TRIES) == 0u);
    CHECK(r.st.cmd_w_rad_s < 0.0f);
}

TEST(the_sweep_keeps_how_far_each_rangers_last_stretch_of_wall_passes)
{
    /* the body moves along a wall on its right (odometry 0, 50, 100 mm
     * ahead), the right rear ranger reading it 150 mm off: its hits run
     * along the line y = -70 - 150 sin 45 (the sensor 70 mm right of the
     * axle). A stretch of 50 mm is recorded and its line's distance from
     * the axle kept; a reading out of range, or a jump past a stretch's
     * length, forgets it */
    ffr_config_t cfg;
    ffr_odometry_t odo;
    ffr_home_orient_t o;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    const float line = 70.0f + 150.0f * 0.70710678f;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&odo);
    ffr_orient_reset(&o, &odo);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RR] = 150.0f;
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], 0.0f, 1e-6f); /* one hit: no stretch yet */
    odo.x_mm = 50.0f;
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], line, 0.5f);
    odo.x_mm = 70.0f; /* within a stretch's start: kept */
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], line, 0.5f);
    CHECK_NEAR(o.probe_mm[FFR_IR_LR], 0.0f, 1e-6f); /* the others saw nothing */
    odo.x_mm = 250.0f; /* 200 mm on: a jump */
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], 0.0f, 1e-6f);
    odo.x_mm = 300.0f;
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], line, 0.5f);
    ir[FFR_IR_RR] = 400.0f; /* beyond the stretches' range */
    ffr_orient_record(&o, &cfg, &odo, rig_geom(&g, &cfg, ir), ir);
    CHECK_NEAR(o.probe_mm[FFR_IR_RR], 0.0f, 1e-6f);
}

/* sweep_rig's sweep with ranger `line`'s last stretch of hits passing
 * line_mm from the axle, and one orientation tick. The phase after it. */
static uint8_t sweep_tick_line(rig_t *r, ffr_config_t *cfg, const float ir[FFR_IR_COUNT], float done_deg, int line,
                               float line_mm)
{
    sweep_rig(r, cfg, ir, done_deg, 0u);
    r->st.orient.probe_mm[line] = line_mm;
    CHECK(ffr_orient_step(&r->st) == 0);
    return r->st.orient.phase;
}

TEST(a_ranger_at_its_bottom_along_a_wall_outside_the_turning_circle_does_not_stop_the_sweep)
{
    /* turning right, a right ranger at its span's bottom, the line of its
     * last stretch of hits passing beyond the room a turn needs (the front
     * corners' 156 mm + 20) + 10 (a part reading short, a wall across the
     * beam farther off): the sweep turns on. That line nearer (a face
     * running on toward the body, or a corner just past the stretch), or
     * no stretch seen: the stop, as before. Over the turn's extent and both
     * the turning side's rangers */
    static const int side[2] = {FFR_IR_RF, FFR_IR_RR};
    static const float done[3] = {5.0f, 40.0f, 90.0f};
    static const float far_mm[3] = {187.0f, 206.0f, 400.0f};
    static const float near_mm[3] = {0.0f, 120.0f, 185.0f};
    unsigned k, j, n;
    for (k = 0; k < 2; ++k) {
        for (j = 0; j < 3; ++j) {
            for (n = 0; n < 3; ++n) {
                ffr_config_t cfg;
                rig_t r;
                float ir[FFR_IR_COUNT];
                ffr_config_default(&cfg);
                rig_no_walls(&cfg, ir);
                ir[side[k]] = 100.0f; /* ir_min_mm */
                CHECK(sweep_tick_line(&r, &cfg, ir, done[j], side[k], far_mm[n]) == 0u); /* PH_SWEEP: turning on */
                CHECK(r.st.cmd_w_rad_s < 0.0f);
                CHECK(r.st.orient.escapes == 0u);
                CHECK(sweep_tick_line(&r, &cfg, ir, done[j], side[k], near_mm[n]) == 8u); /* PH_ESCAPE */
                CHECK(r.st.orient.escapes == 1u);
                /* the other side ranger's far line is not this one's */
                CHECK(sweep_tick_line(&r, &cfg, ir, done[j], side[1u - k], far_mm[n]) == 8u);
            }
        }
    }
}

TEST(the_sweep_turns_away_from_a_wall_beside)
{
    /* escapes spent with a wall beside within the turning circle: the sweep
     * turns away from it (its front corner, 156 mm out, swings off the wall;
     * only the rear corner, 141 mm, swings toward it), whatever
     * home_wall_side would pick; no such wall: home_wall_side's way */
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    float gap;
    rig_t r;
    ffr_config_default(&cfg);
    for (gap = 110.0f; gap <= 170.0f; gap += 10.0f) {
        rig_walls_t right = {2000.0f, 0.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        rig_walls_t left = {0.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        right.right_y = -gap;
        left.left_y = gap;
        readings(&cfg, &right, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 1);
        readings(&cfg, &left, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == -1);
    }
    {
        /* a wall ahead, or one beside but clear of the turning circle: 0 */
        rig_walls_t ahead = {2000.0f, -2000.0f, 150.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        rig_walls_t far = {2000.0f, -240.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        readings(&cfg, &ahead, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
        readings(&cfg, &far, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    }
    {
        /* in the firmware: the moves spent, a wall 130 mm off on the right,
         * home_wall_side right (a right sweep otherwise): it turns left */
        rig_walls_t right = {2000.0f, -130.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        rig_init(&r, &cfg);
        r.st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT;
        readings(&cfg, &right, 0.0f, 0.0f, 0.0f, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r); /* the readings in */
        ffr_orient_begin(&r.st);
        r.st.orient.escapes = FFR_ORIENT_ESCAPE_TRIES;
        CHECK(ffr_orient_step(&r.st) == 0);
        CHECK(r.st.orient.sweep_side == 1);
        CHECK(r.st.cmd_w_rad_s > 0.0f);
        /* nothing near: the right sweep as before */
        rig_no_walls(&cfg, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        ffr_orient_begin(&r.st);
        CHECK(ffr_orient_step(&r.st) == 0);
        CHECK(r.st.orient.sweep_side == 0);
        CHECK(r.st.cmd_w_rad_s < 0.0f);
    }
}

TEST(the_sweep_turns_away_from_a_front_corner_read_folded_back)
{
    /* nothing near as read, but a front corner ranger reading within the
     * fold-back span: its wall may be 3-5.5 cm off it, the front corner on
     * it. The sweep turns away from that side, whatever home_wall_side
     * would pick (turning toward it, that corner meets the wall at once:
     * start circle seeds 629 and 635, docs/robustness.md) */
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT], gap, th;
    int cases = 0;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RF] = 120.0f;
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 1);
    ir[FFR_IR_RF] = FFR_FOLD_CORNER_MAX_MM + 1.0f; /* above the span: as read, clear */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_LF] = 120.0f;
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == -1);
    ir[FFR_IR_RF] = 120.0f; /* both: no side to prefer */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RR] = 120.0f; /* a rear ranger: the rear fold move's case */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    /* the whole firmware: a wall on the right, the body heading into it at
     * 20-35 degrees, its front right corner 1-7 mm off; home_wall_side
     * right (a right sweep otherwise). It leaves ORIENT with no contact */
    for (th = -20.0f * FFR_DEG; th >= -35.1f * FFR_DEG; th -= 5.0f * FFR_DEG) {
        for (gap = 1.0f; gap <= 7.0f; gap += 2.0f) {
            rig_walls_t w = {2000.0f, 0.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
            rig_t r;
            int clear;
            w.right_y = 120.0f * ffr_sinf(th) - 100.0f * ffr_cosf(th) - gap; /* the front right corner's y */
            readings_folded(&cfg, &w, 0.0f, 0.0f, th, ir);
            if (!(ir[FFR_IR_RF] > cfg.ir_min_mm + 0.5f && ir[FFR_IR_RF] <= FFR_FOLD_CORNER_MAX_MM)) {
                continue;
            }
            ++cases;
            clear = orient_folded(&r, &cfg, &w, th, FFR_HOME_WALL_RIGHT, NULL);
            CHECK(r.out.state == FFR_ST_FOLLOW);
            CHECK(clear);
        }
    }
    CHECK(cases >= 8);
}

TEST(the_sweep_turns_toward_a_front_corner_read_folded_back_with_the_centre)
{
    /* a front corner ranger and the centre one both within the fold-back
     * span: the wall is across the front, that corner nearest it. Turning
     * away from its side would swing the corner forward into the wall; the
     * sweep turns toward its side, whatever home_wall_side would pick */
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RF] = 120.0f;
    ir[FFR_IR_CF] = 120.0f;
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == -1);
    ir[FFR_IR_CF] = FFR_FOLD_CORNER_MAX_MM + 1.0f; /* the centre clear as read: away, as before */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 1);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_LF] = 120.0f;
    ir[FFR_IR_CF] = 110.0f;
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 1);
    ir[FFR_IR_RF] = 120.0f; /* both corners: no side to prefer */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_CF] = 110.0f; /* the centre alone: no corner, no side */
    CHECK(ffr_orient_sweep_side(&cfg, rig_geom(&g, &cfg, ir), ir) == 0);
    /* the whole firmware on such starts: tests/scenario/test_start_pose.py */
}

/* the S's first arc: leg 1, or 9 where the wide S begins gently (LEG_SOFT) */
static int s_first_arc(const ffr_home_orient_t *o) { return o->leg == 1u || o->leg == 9u; }

/* The rig at the origin facing +x with the readings ir in, ORIENT begun and
 * its first step taken: the first move chosen */
static void first_move(rig_t *r, const ffr_config_t *cfg, const float ir[FFR_IR_COUNT])
{
    rig_init(r, cfg);
    feed(r, cfg, ir);
    rig_tick(r);
    ffr_orient_begin(&r->st);
    CHECK(ffr_orient_step(&r->st) == 0);
}

TEST(a_wall_beside_below_the_span_is_no_end_of_the_s)
{
    /* a wall 140 mm off on the right: its corner and rear rangers read
     * below their span (at its bottom). Those hits, placed at half the
     * span's bottom, lie inside the arc's band at both ends; taken as ends
     * they shut both and the escape could not move (start seed 120). Read as
     * the wall beside, with the floor ahead free for the whole S: it drives
     * the S forward, turning away (left) */
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    rig_t r;
    rig_walls_t right = {2000.0f, -140.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_default(&cfg);
    readings(&cfg, &right, 0.0f, 0.0f, 0.0f, ir);
    CHECK(ir[FFR_IR_RF] <= cfg.ir_min_mm + 0.5f && ir[FFR_IR_RR] <= cfg.ir_min_mm + 0.5f);
    first_move(&r, &cfg, ir);
    CHECK(s_first_arc(&r.st.orient) && r.st.orient.reverse == 0u && r.st.orient.target_rad > 0.0f);
    CHECK(ffr_orient_step(&r.st) == 0); /* ESCAPE: it moves */
    CHECK(r.st.cmd_v_mm_s > 0.0f && r.st.cmd_w_rad_s > 0.0f);
    {
        /* a wall across 200 mm ahead as well: no room for the S there; it does
         * not drive forward (as before) */
        rig_walls_t corner = {2000.0f, -140.0f, 200.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        readings(&cfg, &corner, 0.0f, 0.0f, 0.0f, ir);
        first_move(&r, &cfg, ir);
        (void)ffr_orient_step(&r.st);
        CHECK(r.st.cmd_v_mm_s <= 0.0f); /* not forward into it */
    }
    {
        /* the wall beside 27 mm off the left side: the corner ranger reads at
         * its span's bottom, the rear one, a part reading 25 mm long, just
         * above it (105 mm). A wall that near the rear corner is the wall
         * beside, not a wall's end at the front corner: the S forward, and
         * the whole start with no contact (fresh +-2.5 cm start seed 414: the
         * front taken as shut, the escapes spent without moving, and the
         * sweep's turn swung the rear corner into it) */
        rig_walls_t left = {127.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 25.0f, 0.0f}};
        readings(&cfg, &left, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ir[FFR_IR_LF] <= cfg.ir_min_mm + 0.5f);
        CHECK(ir[FFR_IR_LR] > cfg.ir_min_mm + 0.5f && ir[FFR_IR_LR] <= cfg.ir_min_mm + 30.0f);
        first_move(&r, &cfg, ir);
        CHECK(s_first_arc(&r.st.orient) && r.st.orient.reverse == 0u && r.st.orient.target_rad < 0.0f);
        CHECK(orient_among(&left, 0.0f) == 2);
        /* the rear ranger reading more than 30 mm above its span's bottom
         * (BESIDE_REAR_MM): its wall may be another, the corner ranger's a
         * wall's end at the front corner (the_front_shut_straight_back_before_the_s);
         * the front stays shut, not the S forward */
        left.part_mm[FFR_IR_LR] = 0.0f;
        readings(&cfg, &left, 0.0f, 0.0f, 0.0f, ir);
        ir[FFR_IR_LR] = cfg.ir_min_mm + 31.0f;
        first_move(&r, &cfg, ir);
        CHECK(!(s_first_arc(&r.st.orient) && r.st.orient.reverse == 0u));
        ir[FFR_IR_LR] = cfg.ir_min_mm + 30.0f; /* just within: the wall beside */
        first_move(&r, &cfg, ir);
        CHECK(s_first_arc(&r.st.orient) && r.st.orient.reverse == 0u);
    }
}

TEST(a_wall_beside_this_near_gets_the_wider_s_where_the_floor_allows)
{
    /* A wall along the left side 14 mm off, both rangers on that side at
     * their span's bottom (the wall beside, its distance not measured). The
     * S's first arc swings the rear corner out toward it: about 19 mm on
     * the 150 mm arc, 12 mm on a 300 mm one (ESCAPE_WIDE_MM). With the
     * floor ahead free for the wider S it drives that one, and the whole
     * start has no contact (fresh +-2.5 cm start seed 605: 14 mm off the
     * south wall, the 150 mm arc put the rear corner on it). With a wall
     * across 450 mm ahead the wider S does not fit: the 150 mm one, as before */
    static const float ahead_x[2] = {0.0f, 450.0f}, radius[2] = {300.0f, 150.0f};
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    rig_t r;
    int k;
    ffr_config_default(&cfg);
    for (k = 0; k < 2; ++k) {
        rig_walls_t w = {114.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        w.ahead_x = ahead_x[k];
        readings(&cfg, &w, 0.0f, 0.0f, 0.0f, ir);
        CHECK(ir[FFR_IR_LF] <= cfg.ir_min_mm + 0.5f && ir[FFR_IR_LR] <= cfg.ir_min_mm + 0.5f);
        first_move(&r, &cfg, ir);
        CHECK(s_first_arc(&r.st.orient) && r.st.orient.reverse == 0u);
        CHECK_NEAR(r.st.orient.target_rad, -1.0f / radius[k], 1e-6f);
        CHECK(r.st.orient.leg == (k == 0 ? 9u : 1u)); /* the wide one begun gently (LEG_SOFT) */
        if (k == 0) {
            CHECK(orient_among(&w, 0.0f) == 2); /* the whole start: no contact */
        }
    }
}

/* The whole firmware orienting from heading 0 beside the walls w, read
 * folded back, the left corner ranger reading at least lf_min: the first S
 * forward's leg and curvature (leg -1: none began) */
static void first_s_forward(const rig_walls_t *w, float lf_min, int *leg, float *rad)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
    r.in.start = 1;
    *leg = -1;
    *rad = 0.0f;
    for (i = 0; i < 1500 && *leg < 0; ++i) {
        readings_folded(&cfg, w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        ir[FFR_IR_LF] = ir[FFR_IR_LF] < lf_min ? lf_min : ir[FFR_IR_LF];
        feed(&r, &cfg, ir);
        rig_tick(&r);
        if (r.out.state != FFR_ST_ORIENT && i > 2) {
            break;
        }
        if (r.st.orient.phase == 8u && s_first_arc(&r.st.orient) && !r.st.orient.reverse) { /* PH_ESCAPE */
            *leg = r.st.orient.leg;
            *rad = r.st.orient.target_rad;
        }
    }
}

TEST(a_front_ranger_just_above_its_bottom_still_gets_the_wider_s)
{
    /* A wall along the left side 5 mm off and parallel: both rangers on that
     * side fold back to read a few mm above their span's bottom (the rig's
     * curve, as the nominal part's: a wall 8 mm off read 104 and 102 mm in
     * the simulation). Not a wall's end at the front corner: the wall
     * beside. After the fold move forward the S forward is the wide one
     * begun gently (LEG_SOFT, 300 mm), whose rear corner swings out ~7 mm,
     * not the 150 mm arc's ~19 (nominal start seed 7636: 8 mm off the
     * south wall, the front ranger at 104 mm; taken as the wall beside only
     * at its very bottom, the 150 mm arc met the wall at 0.73 s, and the
     * wide S gets it home). A part reading 20 mm long there: the wide S as
     * well; 41 mm above the bottom, beyond WIDE_FRONT_MM (40 mm): the 150 mm
     * arc, as before. (In this rig a wall nearer than 11 mm is still met
     * after the soft arc, old rule or new: docs/robustness.md) */
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT], rad;
    int leg;
    rig_walls_t w = {105.0f, -2000.0f, 0.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_default(&cfg);
    readings_folded(&cfg, &w, 0.0f, 0.0f, 0.0f, ir);
    CHECK(ir[FFR_IR_LF] > cfg.ir_min_mm + 0.5f && ir[FFR_IR_LF] < cfg.ir_min_mm + 40.0f);
    CHECK(ir[FFR_IR_LR] > cfg.ir_min_mm + 0.5f && ir[FFR_IR_LR] < cfg.ir_min_mm + 30.0f);
    first_s_forward(&w, 0.0f, &leg, &rad);
    CHECK(leg == 9); /* LEG_SOFT */
    CHECK_NEAR(rad, -1.0f / 300.0f, 1e-6f);
    first_s_forward(&w, cfg.ir_min_mm + 20.0f, &leg, &rad); /* a part reading 20 mm long */
    CHECK(leg == 9);
    CHECK_NEAR(rad, -1.0f / 300.0f, 1e-6f);
    first_s_forward(&w, cfg.ir_min_mm + 41.0f, &leg, &rad); /* beyond: the 150 mm arc */
    CHECK(leg == 1);
    CHECK_NEAR(rad, -1.0f / 150.0f, 1e-6f);
}

TEST(back_first_from_a_wall_beside_nearer_at_the_front)
{
    /* Nominal start seed 6803's first look: 3.5 mm off the south wall on
     * its right, 12 degrees toward it. The right rear ranger reads 139 mm
     * (within the fold-back span), the right front one 111 mm, near its
     * bottom: that wall is nearer at the front corner (folded back there,
     * ~5 cm off the ranger). The rear fold move forward met it at 0.2 s;
     * the front fold move, straight back, first. With the other rear
     * ranger reading a wall 229 mm off (a wall behind: arbitrary start seed
     * 2051), a front ranger 16 mm above its bottom, one not 20 mm below
     * the rear one, or one at its very bottom (not a suspect: the wall
     * beside, a_wall_beside_below_the_span_is_no_end_of_the_s): the rear
     * fold move forward, as before */
    static const float seen[FFR_IR_COUNT] = {190.0f, 229.0f, 111.0f, 300.0f, 139.0f}; /* CF LF RF LR RR */
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    rig_t r;
    int i, k;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM > 0.0f) {
        CHECK(FFR_HOME_FOLD_MM > 0.0f); /* the fold moves are off with the probe on */
        return;
    }
    for (k = 0; k < 5; ++k) {
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            ir[i] = seen[i];
        }
        if (k == 1) {
            ir[FFR_IR_LR] = 229.0f;
        } else if (k == 2) {
            ir[FFR_IR_RF] = cfg.ir_min_mm + 16.0f;
        } else if (k == 3) {
            ir[FFR_IR_RF] = 110.0f;
            ir[FFR_IR_RR] = 129.0f;
        } else if (k == 4) {
            ir[FFR_IR_RF] = cfg.ir_min_mm;
        }
        first_move(&r, &cfg, ir);
        if (k == 4) {
            /* no fold move forward either (the front shut at the bottom's
             * hit): not the front fold move back, at least */
            CHECK(!(r.st.orient.phase == 8u && r.st.orient.leg == 6u && r.st.orient.reverse == 1u));
            continue;
        }
        CHECK(r.st.orient.phase == 8u && r.st.orient.leg == 6u); /* PH_ESCAPE, LEG_FOLD */
        CHECK(r.st.orient.target_rad == 0.0f);
        CHECK(r.st.orient.reverse == (k == 0 ? 1u : 0u));
    }
}

TEST(room_to_turn_again_after_the_shift)
{
    /* the shift drove backward toward a wall across its axis, read long in
     * the sweep, and ended 140 mm from it (the rear face 40 mm off): the
     * aim's turn in place would swing a rear corner (141 mm) into it. At the
     * shift's end the rear pair, reading 25 mm long (as a datasheet part
     * may), measure it as a line square to the walls: one straight move
     * away (forward) by the missing room, then the aim, whose turn has room.
     * A shift that ends clear of every wall goes to the aim at once */
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    float need;
    rig_t r;
    int i, clear = 1, aimed = 0;
    float x_end = 0.0f;
    rig_walls_t w = {2000.0f, -2000.0f, 140.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 25.0f, 25.0f}};
    ffr_config_default(&cfg);
    need = ffr_orient_turn_radius_mm(&cfg) + 20.0f;
    rig_init(&r, &cfg);
    r.st.odo.heading_rad = PI_F; /* facing away from the wall at x = 140 */
    readings(&cfg, &w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
    CHECK(ir[FFR_IR_LR] > cfg.ir_min_mm + 0.5f && ir[FFR_IR_RR] > cfg.ir_min_mm + 0.5f); /* in their span */
    feed(&r, &cfg, ir);
    rig_tick(&r); /* the readings in */
    ffr_orient_begin(&r.st);
    r.st.orient.phase = 3u; /* PH_SHIFT_DRIVE, at its end; the walls along x and y (dir0 0) */
    r.st.orient.reverse = 1u;
    r.st.orient.target_rad = r.st.odo.heading_rad;
    r.st.orient.goal_mm = r.st.odo.dist_mm;
    CHECK(ffr_orient_step(&r.st) == 0);
    CHECK(r.st.orient.phase == 8u); /* PH_ESCAPE */
    CHECK(r.st.orient.reverse == 0u && r.st.orient.target_rad == 0.0f && r.st.orient.after_shift == 1u);
    /* the whole firmware from here: the move, then the aim's turn, no corner on the wall */
    r.st.started = 1;
    for (i = 0; i < 600 && r.st.state == FFR_ST_ORIENT; ++i) {
        readings(&cfg, &w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        CHECK(r.st.orient.phase != 7u); /* no fresh look (PH_CLEAR): no sweep again */
        if (r.st.orient.phase == 8u) {
            x_end = r.st.odo.x_mm;
            clear &= body_clear(&w, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
        } else {
            aimed = 1; /* the aim, its turn and odometry's frame turned to the way */
        }
    }
    CHECK(aimed);
    CHECK(clear);
    CHECK(140.0f - x_end >= ffr_orient_turn_radius_mm(&cfg)); /* room for the turn's corners */
    CHECK(140.0f - x_end < need + 30.0f);                      /* and no farther than needed */
    {
        /* the wall 250 mm off: no move, the aim next */
        rig_walls_t far = {2000.0f, -2000.0f, 250.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
        rig_init(&r, &cfg);
        r.st.odo.heading_rad = PI_F;
        readings(&cfg, &far, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        ffr_orient_begin(&r.st);
        r.st.orient.phase = 3u;
        r.st.orient.reverse = 1u;
        r.st.orient.target_rad = r.st.odo.heading_rad;
        r.st.orient.goal_mm = r.st.odo.dist_mm;
        CHECK(ffr_orient_step(&r.st) == 0);
        CHECK(r.st.orient.phase == ORIENT_PH_AIM && r.st.orient.after_shift == 0u);
    }
}

/* The rangers' readings of one straight wall: the points p with n . p = c
 * (world frame, n a unit normal pointing away from the robot), robot at
 * (x, y, th); below the span's bottom as the bottom (readings()' rule). The
 * right corner ranger is a part that reads rf_long mm long near its span's
 * bottom and folds back below 55 mm (folded_mm): it never reads the bottom. */
static void slant_readings(const ffr_config_t *cfg, float nx, float ny, float c, float rf_long, float x, float y,
                           float th, float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float mx, my, ux, uy, un, t;
        rig_ray(cfg, i, x, y, th, &mx, &my, &ux, &uy);
        un = ux * nx + uy * ny;
        t = un > 0.05f ? (c - (mx * nx + my * ny)) / un : -1.0f;
        if (t <= 0.0f || t > cfg->ir_max_mm) {
            ir[i] = FFR_IR_NONE(cfg);
        } else if (i == FFR_IR_RF) {
            ir[i] = t < 55.0f ? folded_mm(cfg, t) : t + rf_long;
        } else {
            ir[i] = t < cfg->ir_min_mm ? cfg->ir_min_mm : t;
        }
    }
}

TEST(a_straight_escape_stops_short_of_a_wall_across_at_a_slant)
{
    /* a straight escape forward (200 mm to go) toward a wall across its
     * way at 45 degrees, the front right corner 150 mm from it along the
     * move, the right corner ranger reading 45 mm long near its span's
     * bottom (a realistic robot's, start seed 23): the centre ranger reads
     * the wall ~220 mm beyond the front and the corner ranger never at its
     * span's bottom, so the body's path looks free for the whole move and
     * the corner would meet the wall after 150 mm. The line through the two
     * rangers' hits tells: it stops with the corner short of the wall */
    const float nx = 0.70710678f, ny = -0.70710678f, gap0 = 150.0f;
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    float c, x0, corner_gap = 0.0f;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    /* the wall: gap0 along +x beyond the front right corner (120, -100) */
    c = (120.0f + gap0) * nx + (-100.0f) * ny;
    rig_init(&r, &cfg);
    slant_readings(&cfg, nx, ny, c, 45.0f, 0.0f, 0.0f, 0.0f, ir);
    CHECK(ffr_ir_valid(&cfg, ir[FFR_IR_CF]) && ir[FFR_IR_CF] + cfg.ir_x_mm[FFR_IR_CF] > 300.0f);
    feed(&r, &cfg, ir);
    rig_tick(&r); /* the readings in */
    ffr_orient_begin(&r.st);
    r.st.orient.phase = 8u; /* PH_ESCAPE: straight (curvature 0), forward */
    r.st.orient.leg = 0u;
    r.st.orient.reverse = 0u;
    r.st.orient.target_rad = 0.0f;
    r.st.orient.escapes = 1u;
    r.st.orient.goal_mm = r.st.odo.dist_mm + 200.0f;
    r.st.orient.slant_watch = 1u; /* as the escape's start sets it: the corner 150 mm (>= 100) off */
    r.st.started = 1;
    x0 = r.st.odo.x_mm;
    for (i = 0; i < 400 && r.st.orient.phase == 8u; ++i) {
        slant_readings(&cfg, nx, ny, c, 45.0f, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
    }
    CHECK(r.st.orient.phase != 8u);
    /* the front right corner's gap to the wall along the move */
    corner_gap = (c - ((r.st.odo.x_mm + 120.0f) * nx + (r.st.odo.y_mm - 100.0f) * ny)) / nx;
    CHECK(corner_gap > 40.0f); /* 60 mm here; without the rule it drives on to 7 mm */
    CHECK(r.st.odo.x_mm - x0 < 110.0f);
    CHECK(r.st.odo.x_mm - x0 > 20.0f); /* it did move: the wall was not in the way at once */
}

/* Readings in a box of straight walls (world frame: n_k . p = c_k, each n_k
 * a unit normal pointing out of the box), the robot at (x, y, th): each
 * beam's nearest wall (box_beam_mm: ranger i's, unclipped); below the
 * span's bottom as the bottom (box_readings). */
static float box_beam_mm(const ffr_config_t *cfg, const float n[][3], int walls, int i, float x, float y, float th)
{
    float mx, my, ux, uy, best = FFR_IR_NONE(cfg);
    int k;
    rig_ray(cfg, i, x, y, th, &mx, &my, &ux, &uy);
    for (k = 0; k < walls; ++k) {
        float un = ux * n[k][0] + uy * n[k][1];
        float t = un > 0.05f ? (n[k][2] - (mx * n[k][0] + my * n[k][1])) / un : -1.0f;
        if (t > 0.0f && t < best) {
            best = t;
        }
    }
    return best;
}

static void box_readings(const ffr_config_t *cfg, const float n[][3], int walls, float x, float y, float th,
                         float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float best = box_beam_mm(cfg, n, walls, i, x, y, th);
        ir[i] = best > cfg->ir_max_mm ? FFR_IR_NONE(cfg) : (best < cfg->ir_min_mm ? cfg->ir_min_mm : best);
    }
}

/* the same, read folded back below the span (folded_mm) */
static void box_readings_folded(const ffr_config_t *cfg, const float n[][3], int walls, float x, float y, float th,
                                float ir[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        float best = box_beam_mm(cfg, n, walls, i, x, y, th);
        ir[i] = best > cfg->ir_max_mm ? FFR_IR_NONE(cfg) : folded_mm(cfg, best);
    }
}

TEST(a_straight_escape_is_not_refused_by_a_line_across_a_corner)
{
    /* the rear 30 mm from a wall behind, the left side 50 mm from a wall
     * beside, a wall 210 mm beyond the front: room to turn needs a straight
     * move forward. The line through the centre ranger's hit (the wall
     * ahead) and the left corner ranger's (the wall beside) cuts across the
     * corner ahead-left, under 100 mm from the front left corner: two
     * walls, not one across the move. The escape begins that near it, so it
     * does not watch for it (ffr_orient_watch_leg), and moves. Before, it was
     * refused at once, the next escapes likewise, and with the four spent
     * the sweep turned with the rear 30 mm from the wall */
    static const float box[3][3] = {{-1.0f, 0.0f, 130.0f}, {0.0f, 1.0f, 150.0f}, {1.0f, 0.0f, 330.0f}};
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    float x0, moved = 0.0f;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    box_readings(&cfg, box, 3, 0.0f, 0.0f, 0.0f, ir);
    feed(&r, &cfg, ir);
    rig_tick(&r); /* the readings in */
    ffr_orient_begin(&r.st); /* PH_CLEAR: room to turn first */
    r.st.started = 1;
    x0 = r.st.odo.x_mm;
    for (i = 0; i < 300 && r.st.orient.escapes <= 1u; ++i) {
        box_readings(&cfg, box, 3, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r);
        if (r.st.orient.phase == 8u && r.st.orient.escapes == 1u) { /* the first move */
            CHECK(r.st.orient.target_rad == 0.0f && r.st.orient.reverse == 0u); /* straight, forward */
            moved = r.st.odo.x_mm - x0;
        }
    }
    CHECK(moved > 50.0f); /* 70 mm: the move it planned, 176 - 115 + 10 */
    CHECK(r.st.odo.x_mm + 120.0f < 330.0f); /* the front clear of the wall ahead */
}

TEST(a_wall_square_to_the_walls_from_two_measured_hits)
{
    /* the rear pair on a wall across behind, 160 mm off: a line square to
     * the walls (walls' direction 0 in the body frame), found at its
     * distance; the same hits with the walls at 30 degrees: a slanted line,
     * two walls' hits across a corner, not taken; a reading at the span's
     * bottom (a bound, not a measurement): no line */
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT], d, nx, ny;
    rig_walls_t w = {2000.0f, -2000.0f, 160.0f, 0.0f, 0.0f, {0.0f, 0.0f, 0.0f, 0.0f, 0.0f}};
    ffr_config_default(&cfg);
    readings(&cfg, &w, 0.0f, 0.0f, PI_F, ir);
    CHECK(ffr_orient_square_wall(&cfg, rig_geom(&g, &cfg, ir), ir, 0.0f, &d, &nx, &ny));
    CHECK_NEAR(d, 160.0f, 2.0f);
    CHECK(nx < -0.99f);
    CHECK(!ffr_orient_square_wall(&cfg, rig_geom(&g, &cfg, ir), ir, 30.0f * FFR_DEG, &d, &nx, &ny));
    CHECK(ffr_orient_square_wall(&cfg, rig_geom(&g, &cfg, ir), ir, 0.5f * PI_F + 5.0f * FFR_DEG, &d, &nx, &ny));
    ir[FFR_IR_RR] = cfg.ir_min_mm;
    CHECK(!ffr_orient_square_wall(&cfg, rig_geom(&g, &cfg, ir), ir, 0.0f, &d, &nx, &ny));
}

/* box_readings, the rear right ranger a part reading rr_long mm long near
 * its span's bottom and folded back below 55 mm (folded_mm): as
 * slant_readings' corner ranger, it never reads the bottom */
static void box_readings_rr(const ffr_config_t *cfg, const float n[][3], int walls, float rr_long, float x, float y,
                            float th, float ir[FFR_IR_COUNT])
{
    float t = box_beam_mm(cfg, n, walls, FFR_IR_RR, x, y, th);
    box_readings(cfg, n, walls, x, y, th, ir);
    if (t <= cfg->ir_max_mm) {
        ir[FFR_IR_RR] = t < 55.0f ? folded_mm(cfg, t) : t + rr_long;
    }
}

/* One tick of the rig among the walls of `box`: the readings at odometry's
 * pose (the true one: the rig's wheels do not slip), the rear right part
 * reading rr_long mm long */
static void box_tick_rr(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls, float rr_long)
{
    float ir[FFR_IR_COUNT];
    box_readings_rr(cfg, box, walls, rr_long, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad, ir);
    feed(r, cfg, ir);
    rig_tick(r);
}

/* A straight escape backward (phase 8, leg 0) among the walls of `box`,
 * from the origin heading 0, goal_mm to go: where it ended (odometry x) */
static float straight_back(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls, float rr_long,
                           float goal_mm)
{
    int i;
    rig_init(r, cfg);
    box_tick_rr(r, cfg, box, walls, rr_long); /* the readings in */
    ffr_orient_begin(&r->st);
    r->st.orient.phase = 8u; /* PH_ESCAPE: straight (curvature 0), backward */
    r->st.orient.leg = 0u;
    r->st.orient.reverse = 1u;
    r->st.orient.target_rad = 0.0f;
    r->st.orient.escapes = 1u;
    r->st.orient.goal_mm = r->st.odo.dist_mm + goal_mm;
    r->st.started = 1;
    ffr_orient_watch_leg(&r->st); /* as the escape's start does */
    for (i = 0; i < 600 && r->st.orient.phase == 8u; ++i) {
        box_tick_rr(r, cfg, box, walls, rr_long);
    }
    CHECK(r->st.orient.phase != 8u);
    return r->st.odo.x_mm;
}

TEST(a_straight_escape_back_stops_as_the_rear_pairs_chord_nears)
{
    /* fresh +-2.5 cm start seed 476: straight back toward a corner behind,
     * its walls at 38 and 52 degrees to the move, each square to one rear
     * ranger's beam (175 and 209 mm); the rear right ranger a part reading
     * 45 mm long near its span's bottom, folded back below it. The rear
     * right corner would meet the first wall after 177 mm of the 200 mm
     * move, and the watch of the body's own band behind sees it only when
     * the ranger's reading folds back into the band: without the chord's
     * watch it stops 20 mm off the wall. The line through the rear pair's
     * hits comes nearer as the robot backs: it stops 59 mm off */
    static const float box[2][3] = {{-0.788f, -0.616f, 280.0f}, {-0.616f, 0.788f, 310.8f}};
    ffr_config_t cfg;
    rig_t r;
    float x, gap;
    ffr_config_default(&cfg);
    x = straight_back(&r, &cfg, box, 2, 45.0f, 200.0f);
    /* the rear right corner's gap to the first wall, along its normal */
    gap = box[0][2] - (box[0][0] * (x - 100.0f) + box[0][1] * (-100.0f));
    CHECK(gap > 30.0f);
    CHECK(x < -30.0f);  /* it did move: the chord was not near at first */
}

TEST(a_straight_escape_back_between_walls_beside_goes_its_length)
{
    /* a hallway: walls 60 mm off both sides. The rear pair's hits (127 mm
     * each) make a chord 90 mm behind them, nearer than REAR_CHORD_MM, but
     * it does not come nearer as the robot backs along the walls: the move
     * goes its whole 150 mm */
    static const float box[2][3] = {{0.0f, 1.0f, 160.0f}, {0.0f, -1.0f, 160.0f}};
    ffr_config_t cfg;
    rig_t r;
    ffr_config_default(&cfg);
    CHECK(straight_back(&r, &cfg, box, 2, 0.0f, 150.0f) < -140.0f);
}

/* every corner of the body at (x, y, th) inside every wall of `box` */
static int box_clear(const float box[][3], int walls, float x, float y, float th)
{
    int j, k;
    for (k = 0; k < 4; ++k) {
        float px, py;
        body_corner(k, x, y, th, &px, &py);
        for (j = 0; j < walls; ++j) {
            if (px * box[j][0] + py * box[j][1] >= box[j][2]) {
                return 0;
            }
        }
    }
    return 1;
}

/* What the orientation did in a closed loop among a box's walls
 * (orient_run) */
typedef struct {
    int clear;      /* the body never met a wall                                */
    int s_forward;  /* an S forward began (PH_ESCAPE, the S's first arc, forward) */
    int first_leg;  /* the first escape's leg (-1: none)                        */
    int first_back; /* ... and it was straight back                             */
    int backed_s;   /* back_for_s's move (LEG_BACK_S) was taken                 */
    float first_rad; /* the first escape's curvature (target_rad, 1/mm)         */
    int soft_arcs;  /* on LEG_SOFT's ticks: bit 0 driven at 1/ESCAPE_SOFT_MM
                       (600 mm), bit 1 at 1/300 mm, as commanded              */
    int probed_back; /* a probe backward (PH_PROBE) began                       */
    int unfolded;   /* unfold_front's move back after its probe (LEG_ALONG) began */
    float x_min;    /* how far back it went before the sweep (odometry x)       */
    float probe_end_x; /* where the last probe ended (odometry x)               */
    float probe_drift; /* the most any probe ended from where it began (mm)    */
    int back_after_unfold; /* a straight move back for the S (LEG_BACK, LEG_BACK_S)
                              began after unfold_front's move back            */
    int s_after_unfold; /* an S began after it (its first arc, either way)     */
    int probed;         /* a probe (PH_PROBE) began, either way                  */
} orient_run_t;

/* The whole firmware orienting among the walls of `box` from the origin
 * heading 0 until it leaves ORIENT (or 1500 ticks): the rangers read as
 * box_readings, or folded back below their span (folded_mm); the wheels
 * rolling forward at v0 mm/s at first (a move before cut short) */
static orient_run_t orient_run_read(const ffr_config_t *cfg, const float box[][3], int walls, int folded, float v0)
{
    rig_t r;
    float ir[FFR_IR_COUNT];
    orient_run_t run = {1, 0, -1, 0, 0, 0.0f, 0, 0, 0, 0.0f, 0.0f, 0.0f, 0, 0, 0};
    int i, swept = 0, probing = 0;
    float this_probe_x = 0.0f;
    rig_init(&r, cfg);
    r.st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
    r.in.start = 1;
    for (i = 0; i < 1500; ++i) {
        const ffr_home_orient_t *o = &r.st.orient;
        (folded ? box_readings_folded : box_readings)(cfg, box, walls, r.st.odo.x_mm, r.st.odo.y_mm,
                                                      r.st.odo.heading_rad, ir);
        feed(&r, cfg, ir);
        if (i == 0) {
            r.st.speed.v_ref[0] = v0;
            r.st.speed.v_ref[1] = v0;
        }
        rig_tick(&r);
        if (r.out.state != FFR_ST_ORIENT && i > 2) {
            break;
        }
        run.probed |= o->phase == 9u;
        run.probed_back |= o->phase == 9u && o->reverse;  /* PH_PROBE */
        if (run.unfolded && o->phase == 8u) { /* PH_ESCAPE after LEG_ALONG's move */
            run.back_after_unfold |= o->leg == 5u || o->leg == 8u;
            run.s_after_unfold |= s_first_arc(o);
        }
        run.unfolded |= o->phase == 8u && o->leg == 11u; /* PH_ESCAPE, LEG_ALONG */
        if (!probing && o->phase == 9u) {
            this_probe_x = r.st.odo.x_mm;
        }
        if (probing && o->phase != 9u) {
            run.probe_end_x = r.st.odo.x_mm;
            if (ffr_absf(r.st.odo.x_mm - this_probe_x) > run.probe_drift) {
                run.probe_drift = ffr_absf(r.st.odo.x_mm - this_probe_x);
            }
        }
        probing = o->phase == 9u;
        swept |= i > 0 && o->phase == 0u; /* PH_SWEEP */
        run.x_min = !swept && r.st.odo.x_mm < run.x_min ? r.st.odo.x_mm : run.x_min;
        if (run.first_leg < 0 && o->escapes > 0u) {
            run.first_leg = o->leg;
            run.first_back = o->reverse && o->target_rad == 0.0f;
            run.first_rad = o->target_rad;
        }
        if (o->phase == 8u && o->leg == 9u && r.st.cmd_v_mm_s > 0.0f) { /* PH_ESCAPE, LEG_SOFT */
            float k = ffr_absf(r.st.cmd_w_rad_s / r.st.cmd_v_mm_s);
            run.soft_arcs |= (ffr_absf(k * 600.0f - 1.0f) < 0.01f ? 1 : 0) | (ffr_absf(k * 300.0f - 1.0f) < 0.01f ? 2 : 0);
        }
        run.s_forward |= o->phase == 8u && s_first_arc(o) && !o->reverse; /* PH_ESCAPE */
        run.backed_s |= o->phase == 8u && o->leg == 8u;                  /* PH_ESCAPE, LEG_BACK_S */
        run.clear &= box_clear(box, walls, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
    }
    return run;
}

static orient_run_t orient_run(const ffr_config_t *cfg, const float box[][3], int walls)
{
    return orient_run_read(cfg, box, walls, 0, 0.0f);
}

/* orient_run: 1 if the body never met a wall; *s_forward: whether an S
 * forward began */
static int orient_in_box(const ffr_config_t *cfg, const float box[][3], int walls, int *s_forward)
{
    orient_run_t run = orient_run(cfg, box, walls);
    *s_forward = run.s_forward;
    return run.clear;
}

/* A shift (phase 2, its turn done at once, then 3) of goal_mm, driven
 * backward or forward, among the walls of `box`, from the origin heading 0,
 * the rear right part reading rr_long mm long, toward a wall across its axis
 * that the sweep measured toward_mm off (0: by no wall ahead; as the
 * centre's tick sets near_mm), and the orientation on to its end (the look
 * after the shift, the aim's turn): where the shift stopped (odometry x);
 * *clear 0 if a corner met a wall on the way */
static float shift_run(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls, float rr_long,
                       uint8_t backward, float toward_mm, float goal_mm, int *clear)
{
    float x_shift = 0.0f;
    int i;
    rig_init(r, cfg);
    box_tick_rr(r, cfg, box, walls, rr_long); /* the readings in */
    ffr_orient_begin(&r->st);
    r->st.orient.phase = 2u; /* PH_SHIFT_TURN, already facing the way: the drive next */
    r->st.orient.reverse = backward;
    r->st.orient.target_rad = r->st.odo.heading_rad;
    r->st.orient.goal_mm = goal_mm;
    r->st.orient.near_mm = toward_mm > 0.0f ? toward_mm : 65535.0f;
    r->st.started = 1;
    *clear = 1;
    for (i = 0; i < 1500 && r->st.state == FFR_ST_ORIENT; ++i) {
        box_tick_rr(r, cfg, box, walls, rr_long);
        if (r->st.state != FFR_ST_ORIENT) {
            break; /* odometry's frame turned to the route's way: the rig's walls are no longer in it */
        }
        *clear &= box_clear(box, walls, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad);
        if (r->st.orient.phase == 2u || r->st.orient.phase == 3u) {
            x_shift = r->st.odo.x_mm;
        }
    }
    CHECK(r->st.state != FFR_ST_ORIENT); /* the aim's turn done: the route begins */
    return x_shift;
}

static float shift_back(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls, float rr_long,
                        float goal_mm, int *clear)
{
    return shift_run(r, cfg, box, walls, rr_long, 1u, 0.0f, goal_mm, clear);
}

static float shift_forward(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls, float toward_mm,
                           float goal_mm, int *clear)
{
    return shift_run(r, cfg, box, walls, 0.0f, 0u, toward_mm, goal_mm, clear);
}

TEST(a_shift_backward_stops_with_room_to_turn_before_the_wall_behind)
{
    /* +-2.5 cm start seeds 2297, 2377, 3624 (`ffr sweep --arena-jitter 0.025
     * --start random --noise datasheet --rooms 1 --candles default`): the
     * sweep read the wall behind long, and the shift backed 290-310 mm, to
     * within the turning radius of it, with both rear rangers at their
     * span's bottom; the aim's turn met it. Here the wall 380 mm behind the
     * axle and a 300 mm shift (walls 230 mm off both sides, the rear right
     * part 25 mm long): it stops where the rear pair's chord comes within
     * the turning radius, the look after the shift measures the wall and
     * moves away from it, and the aim's turn has room: no corner meets a
     * wall. Along a hallway with nothing behind, the chord through the
     * side walls' hits does not come nearer: the whole shift */
    static const float box[3][3] = {{-1.0f, 0.0f, 380.0f}, {0.0f, 1.0f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    ffr_config_t cfg;
    rig_t r;
    float x;
    int clear;
    ffr_config_default(&cfg);
    x = shift_back(&r, &cfg, box, 3, 25.0f, 300.0f, &clear);
    CHECK(clear);
    CHECK(x > -300.0f + 40.0f); /* cut short */
    CHECK(380.0f + x < ffr_orient_turn_radius_mm(&cfg) + 40.0f); /* not long before */
    x = shift_back(&r, &cfg, &box[1], 2, 0.0f, 300.0f, &clear);
    CHECK(clear);
    CHECK(x < -290.0f);
}

TEST(a_shift_backward_stops_where_a_rear_ranger_reaches_its_bottom)
{
    /* orientation bench start seed 7878 (`ffr sweep --arena-jitter 0.025
     * --start random --noise datasheet --rooms 1 --candles default`): the
     * shift backed 100 mm too far, its right rear ranger reached its span's
     * bottom and the rear pair's chord was no longer measured; the aim's
     * turn met the wall. Here a wall behind at 20 degrees to the rear face,
     * the rear right corner 202 mm from it, nothing else near (the left rear
     * ranger reads it beyond CLEAR_RANGE_MM: no chord at all), a 300 mm
     * shift: it stops once the right rear ranger reads its bottom (after
     * ~149 mm), moves 30 mm forward, and the aim's turn has room: no corner
     * meets a wall (without the stop the rear corner meets it after
     * ~215 mm). Along a hallway 20 mm off its right wall, the right rear
     * and front rangers both at their bottom (a wall beside): the whole
     * shift (the aim's turn there, within the turning radius of that wall,
     * is not this rule's to judge) */
    static const float behind[1][3] = {{-0.94f, -0.342f, 330.0f}};
    static const float hallway[2][3] = {{0.0f, 1.0f, 340.0f}, {0.0f, -1.0f, 120.0f}};
    ffr_config_t cfg;
    rig_t r;
    float x;
    int clear;
    ffr_config_default(&cfg);
    x = shift_back(&r, &cfg, behind, 1, 0.0f, 300.0f, &clear);
    CHECK(clear);
    CHECK(x > -200.0f); /* cut short */
    x = shift_back(&r, &cfg, hallway, 2, 0.0f, 300.0f, &clear);
    CHECK(x < -290.0f);
}

TEST(a_shift_toward_a_wall_read_short_ends_on_the_front_ranger)
{
    /* hallway +-2.5 cm start seed 1029 (`ffr sweep --start hallway
     * --arena-jitter 0.025 --noise datasheet --candles default`): the sweep
     * read a corridor's far wall, 780 mm off, as 589 mm, and the shift of
     * 359 mm toward it left the body 150 mm short of the corridor's middle;
     * the wall following's first leg met the mouth's jamb. Here that wall
     * 780 mm ahead, walls 230 mm off both sides: the front ranger takes the
     * shift on to where the wall ahead is wall_target_mm off the axle */
    static const float corridor[3][3] = {{1.0f, 0.0f, 780.0f}, {0.0f, 1.0f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    static const float open[2][3] = {{0.0f, 1.0f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    static const float near[3][3] = {{1.0f, 0.0f, 500.0f}, {0.0f, 1.0f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    static const float slant[3][3] = {{1.0f, 0.0f, 780.0f}, {0.208f, 0.978f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    ffr_config_t cfg;
    rig_t r;
    float x;
    int clear;
    ffr_config_default(&cfg);
    x = shift_forward(&r, &cfg, corridor, 3, 589.0f, 359.0f, &clear);
    CHECK(clear);
    CHECK(ffr_absf(780.0f - x - cfg.wall_target_mm) < 25.0f);
    /* the same shift going by no wall ahead: its length as measured */
    x = shift_forward(&r, &cfg, corridor, 3, 0.0f, 359.0f, &clear);
    CHECK(ffr_absf(x - 359.0f) < 15.0f);
    /* nothing in the front ranger's span: the length as measured */
    x = shift_forward(&r, &cfg, open, 2, 589.0f, 359.0f, &clear);
    CHECK(ffr_absf(x - 359.0f) < 15.0f);
    /* no farther than the wall may be when read short: the wall 780 mm
     * off measured as 480 (a shift of 250) ends 120 mm short */
    x = shift_forward(&r, &cfg, corridor, 3, 480.0f, 250.0f, &clear);
    CHECK(clear);
    CHECK(x < 250.0f + 0.34f * 480.0f + 10.0f && x > 250.0f + 0.33f * 480.0f - 25.0f);
    /* read long, nearer than measured: stopped at the stand */
    x = shift_forward(&r, &cfg, near, 3, 589.0f, 359.0f, &clear);
    CHECK(clear);
    CHECK(ffr_absf(500.0f - x - cfg.wall_target_mm) < 25.0f);
    /* on past its length only on floor free ahead: the walls' direction
     * taken 12 degrees off (hallway start seed 1958), the left wall closing
     * in on the way (its front corner meets it ~515 mm on) */
    x = shift_forward(&r, &cfg, slant, 3, 589.0f, 359.0f, &clear);
    CHECK(clear);
    CHECK(x < 450.0f);
}

/* box_readings, both rear rangers parts whose output peaks above the span's
 * bottom: 28 mm long at 8 cm (their peak, 108 mm as read) and beyond, folded
 * back nearer (2.5 mm longer per mm nearer): such a part never reads its
 * span's bottom, and a wall it nears past 8 cm reads farther and farther */
static void box_tick_peak(rig_t *r, const ffr_config_t *cfg, const float box[][3], int walls)
{
    float ir[FFR_IR_COUNT];
    int i;
    box_readings(cfg, box, walls, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad, ir);
    for (i = FFR_IR_LR; i <= FFR_IR_RR; ++i) {
        float t = box_beam_mm(cfg, box, walls, i, r->st.odo.x_mm, r->st.odo.y_mm, r->st.odo.heading_rad);
        if (t <= cfg->ir_max_mm) {
            ir[i] = t < 80.0f ? 108.0f + (80.0f - t) * 2.5f : t + 28.0f;
        }
    }
    feed(r, cfg, ir);
    rig_tick(r);
}

TEST(a_move_back_stops_when_a_rear_ranger_passes_its_peak)
{
    /* orientation bench start seeds 4412 and 8343 (`ffr sweep --arena-jitter
     * 0.025 --start random --noise datasheet --rooms 1 --candles default`):
     * moving back, a rear ranger's reading came down to its peak and rose
     * again as the wall behind came nearer, and the rear corner met it 0.4-0.7 s
     * later. Here a shift of 300 mm backward toward a wall behind at 30
     * degrees to the rear face (the rear pair's chord stop,
     * shift_back_blocked, does not end it), the rear right corner 193 mm
     * from it:
     * the rear right ranger's beam meets the wall at 80 mm (its peak) after
     * 171 mm and its reading has grown 6 mm after 174 mm; the shift stops
     * there, braking from the cruise speed, within 213 mm; the forward
     * move's 45 mm count from the stop's tick, braking included; and the
     * aim's turn has room: no corner meets a wall (without the rule
     * the corner meets it after 223 mm). Along a hallway with nothing
     * behind: the whole shift */
    static const float box[3][3] = {{-0.866f, -0.5f, 330.0f}, {0.0f, 1.0f, 230.0f}, {0.0f, -1.0f, 230.0f}};
    ffr_config_t cfg;
    rig_t r;
    int k;
    ffr_config_default(&cfg);
    for (k = 0; k < 2; ++k) {
        const float (*b)[3] = k == 0 ? box : &box[1];
        int walls = k == 0 ? 3 : 2, clear = 1, i, stopped = 0, looked = 0;
        float x_min = 0.0f;
        rig_init(&r, &cfg);
        box_tick_peak(&r, &cfg, b, walls); /* the readings in */
        ffr_orient_begin(&r.st);
        r.st.orient.phase = 2u; /* PH_SHIFT_TURN, already facing the way: the drive next */
        r.st.orient.reverse = 1u;
        r.st.orient.target_rad = r.st.odo.heading_rad;
        r.st.orient.goal_mm = 300.0f;
        r.st.started = 1;
        for (i = 0; i < 1500 && r.st.state == FFR_ST_ORIENT; ++i) {
            box_tick_peak(&r, &cfg, b, walls);
            if (r.st.state != FFR_ST_ORIENT) {
                break; /* odometry's frame turned to the route's way */
            }
            clear &= box_clear(b, walls, r.st.odo.x_mm, r.st.odo.y_mm, r.st.odo.heading_rad);
            x_min = r.st.odo.x_mm < x_min ? r.st.odo.x_mm : x_min;
            stopped |= r.st.orient.phase == 8u && r.st.orient.leg == 6u; /* PH_ESCAPE, LEG_FOLD */
            looked |= stopped && r.st.orient.phase == 7u; /* PH_CLEAR after it */
        }
        CHECK(r.st.state != FFR_ST_ORIENT); /* the aim's turn done: the route begins */
        CHECK(clear);
        if (k == 0) {
            CHECK(stopped);
            CHECK(!looked); /* from the shift, the move forward ends in the aim (after_shift), no look again */
            CHECK(x_min > -223.0f + 10.0f); /* stopped short of the wall (the shift brakes from 300 mm/s) */
            CHECK(x_min < -150.0f);         /* and not long before the peak (171 mm) */
        } else {
            CHECK(!stopped);
            CHECK(x_min < -290.0f);
        }
    }
}

TEST(a_line_across_a_corner_with_no_floor_for_the_s_is_no_wall_beside)
{
    /* fresh +-2.5 cm start seed 703: the south wall ahead-left, the east
     * wall behind-left, both ~200 mm or more off the axle: room to turn in
     * place. The left front ranger reads the first (142 mm), the left rear
     * one the second below its span (its bottom; in the seed a part reading
     * short, here the wall 20 mm nearer): the line through their hits looks
     * like a wall beside, and the S forward away from it began with less
     * floor ahead than it needs (in the seed its front left corner met the
     * south wall). Such a line, with no floor for the S: the sweep turns in
     * place */
    static const float box[2][3] = {{0.857f, 0.515f, 243.0f}, {-0.515f, 0.857f, 196.0f}};
    ffr_config_t cfg;
    int s_forward;
    ffr_config_default(&cfg);
    CHECK(orient_in_box(&cfg, box, 2, &s_forward));
    CHECK(!s_forward);
}

TEST(a_wall_beside_with_little_floor_ahead_still_gets_the_s)
{
    /* one wall along the left side, 40 mm off, a wall across 380 mm ahead,
     * less than the S needs: both left rangers at their span's bottom, a
     * wall along the side, not a corner. The S forward as before (turning in
     * place would swing the rear corner 41 mm out). Only the choice is
     * checked: here the S cannot go far and the escapes are spent, with or
     * without the rule (the sweep then meets the wall) */
    static const float box[2][3] = {{0.0f, 1.0f, 140.0f}, {1.0f, 0.0f, 380.0f}};
    /* the wall 5 degrees off the side, 22 mm off the rear corner, one
     * across 330 mm ahead: the front corner ranger measures the first at
     * 105 mm, the rear one reads the bottom (start circle seeds 574, 936:
     * 106 and 109 mm); with CHORD_FRONT_MM 0, no S */
    static const float slant[2][3] = {{-0.0872f, 0.9962f, 130.3f}, {1.0f, 0.0f, 330.0f}};
    ffr_config_t cfg;
    int s_forward;
    ffr_config_default(&cfg);
    (void)orient_in_box(&cfg, box, 2, &s_forward);
    CHECK(s_forward);
    (void)orient_in_box(&cfg, slant, 2, &s_forward);
    CHECK(s_forward);
}

/* A wall along the right side 10-30 mm off, nearer than the rangers
 * measure (RF and RR at their span's bottom), and one across 230 mm beyond
 * the front: the S forward away from the first needs more floor ahead than
 * that, so it stopped on the tick it began; with its four tries so spent,
 * the sweep's turn swung the rear corner into the wall beside (orientation
 * bench start seed 6830: CF 275, LF 500, RF and RR at the bottom, LR 322).
 * With a way's far wall read behind on the other side (here one across
 * 208 mm behind the rear, LR reading it at 322 mm), the first move is
 * straight back for the S's floor, and the orientation ends with no
 * contact. Without it (seed 4392: LR nothing; the wall beside may converge
 * on the rear corner) no such move: the escape as before. */
TEST(an_s_short_of_floor_ahead_backs_straight_first_with_a_far_wall_behind)
{
    ffr_config_t cfg;
    float gap;
    ffr_config_default(&cfg);
    for (gap = 10.0f; gap <= 30.0f; gap += 5.0f) {
        const float b[3][3] = {
            {0.0f, -1.0f, cfg.body_half_width_mm + gap}, {1.0f, 0.0f, 330.0f}, {-1.0f, 0.0f, 308.0f}};
        orient_run_t run = orient_run(&cfg, b, 3);
        CHECK(run.clear);
        CHECK(run.first_leg == 8 && run.first_back); /* LEG_BACK_S */
        /* no wall behind: the left rear ranger reads nothing */
        run = orient_run(&cfg, b, 2);
        CHECK((run.first_leg == 1 || run.first_leg == 9) && !run.backed_s); /* the S's first arc */
    }
}

/* A wall across ahead at 77 degrees to the heading, the front left corner
 * 5-9 mm off it, and a wall beside on the left converging behind at 13
 * degrees, the rear left corner ~50 mm off: the body wedged in a corner
 * (fresh +-2.5 cm start seed 1390: 11 mm, the wall beside 12 mm farther,
 * its rear part reading short). Read folded back (folded_mm): the centre
 * ranger, 48-52 mm off the wall ahead, reads within the fold-back span,
 * the left pair at their span's bottom, a wall beside as read. The S
 * forward away from it has no floor ahead as read and would stop on the
 * tick it begins: on main's build the four tries were spent standing and
 * the sweep's turn put the front left corner on the wall ahead. Now the
 * probe backward finds the centre ranger folded back, the robot backs on
 * its whole 30 mm (backing along the wall beside, the left front ranger's
 * reading grows a few mm: still the wall beside), and the orientation ends
 * with no contact. On the last of the four tries: no probe (no try would
 * be left for the move back). */
TEST(a_wall_ahead_read_folded_back_in_a_corner_is_backed_from_first)
{
    ffr_config_t cfg;
    float gap;
    ffr_config_default(&cfg);
    for (gap = 5.0f; gap <= 9.0f; gap += 1.0f) {
        const float c = 0.9755f, s = 0.2198f; /* cos, sin 12.7 degrees */
        const float ahead = c * cfg.body_front_mm + s * cfg.body_half_width_mm + gap;
        const float b[2][3] = {{c, s, ahead}, {-s, c, 170.0f}};
        orient_run_t run = orient_run_read(&cfg, b, 2, 1, 0.0f);
        rig_t r;
        float ir[FFR_IR_COUNT];
        CHECK(run.clear);
        CHECK(run.probed_back && run.unfolded);
        CHECK(run.x_min < -15.0f - 27.0f); /* backed on past the probe's 15 mm, by the whole 30 */
        /* that move was the straight back: the S follows, with no second
         * straight back before it (was_back) */
        CHECK(run.s_after_unfold && !run.back_after_unfold);
        /* the same first look with three tries spent: the last one stands */
        rig_init(&r, &cfg);
        r.st.cfg.home_wall_side = FFR_HOME_WALL_ANY;
        box_readings_folded(&cfg, b, 2, 0.0f, 0.0f, 0.0f, ir);
        feed(&r, &cfg, ir);
        rig_tick(&r); /* the readings in */
        ffr_orient_begin(&r.st);
        r.st.orient.escapes = FFR_ORIENT_ESCAPE_TRIES - 1u;
        r.st.started = 1;
        rig_tick(&r);
        CHECK(r.st.orient.escapes == FFR_ORIENT_ESCAPE_TRIES && r.st.orient.phase != 9u); /* not PH_PROBE */
        /* the centre ranger known folded back from another move (as a
         * front fold move leaves it), the probe done: no move back follows
         * the refused S (only unfold_front's own probe's finding starts it) */
        ffr_orient_begin(&r.st);
        r.st.orient.escapes = 1u;
        r.st.orient.probe_done = 1u;
        r.st.orient.folded = (uint8_t)(1u << FFR_IR_CF);
        rig_tick(&r);
        CHECK(r.st.orient.escapes == 2u && r.st.orient.leg != 11u); /* not LEG_ALONG */
    }
}

/* The look's own probe (clear_step's, with the fold-back rules built in),
 * not unfold_front's: a wall square behind, 55-90 mm off the rear face,
 * read as it is by both rear rangers within the fold-back span (folded
 * back it would be within the rear corners' turning circle). The probe
 * forward sees the readings grow, as a wall that far, and the robot
 * returns to where it stood (LEG_PROBE_RETURN, its way back asked of
 * escape_free, as far as it came): the sweep turns there, with no
 * contact. */
TEST(the_looks_probe_finding_the_wall_as_read_returns_to_where_it_stood)
{
    ffr_config_t cfg;
    float behind;
    int probed = 0;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM <= 0.0f) {
        /* built without the fold-back rules (the default): no such probe;
         * `make firmware-test` runs it in its second build */
        CHECK(FFR_HOME_FOLD_MM == 0.0f);
        return;
    }
    for (behind = 155.0f; behind <= 190.0f; behind += 5.0f) {
        const float b[1][3] = {{-1.0f, 0.0f, behind}};
        orient_run_t run = orient_run(&cfg, b, 1);
        CHECK(run.clear);
        CHECK(!run.unfolded);
        if (!run.probed) {
            continue; /* no probe: not near even if folded back */
        }
        probed++;
        CHECK(run.probe_drift < 3.0f); /* every probe back where it began */
        CHECK(run.x_min > -3.0f); /* forward and back: never behind where it began */
    }
    CHECK(probed >= 4);
}

/* The same S forward with no floor ahead as read, the centre ranger
 * reading a wall square ahead as it is, within the fold-back span (130
 * mm), the left pair at their span's bottom on a wall along the side 25 mm
 * off: the probe backward finds the reading grown, as a wall that far, and
 * the robot returns to where it stood; no move back follows (the tries go
 * as before, standing: with the wall beside that near the sweep's turn
 * then meets it, as on main's build). The way back retraces the floor the
 * body has just left, with no look at the room: in a corner ahead-left
 * with a wall behind-left (the left rear ranger reading it at its bottom,
 * the pair taken for a wall beside), the probe's 15 mm back brings that
 * reading up into the fold-back span, the wall beside is no longer
 * skipped and its hit shuts the floor ahead as read; a return that looked
 * stopped there, and the next move backed into the wall behind (found in
 * review). It returns, and the orientation ends with no contact. */
TEST(a_wall_ahead_read_as_it_is_gets_the_probe_and_no_move_back)
{
    static const float b[2][3] = {{1.0f, 0.0f, 230.0f}, {0.0f, 1.0f, 125.0f}};
    static const float corner[3][3] = {
        {0.8940f, 0.4480f, 207.6f}, {0.2321f, 0.9727f, 156.0f}, {-0.8620f, 0.5069f, 159.8f}};
    ffr_config_t cfg;
    orient_run_t run;
    float v0;
    ffr_config_default(&cfg);
    run = orient_run_read(&cfg, b, 2, 1, 0.0f);
    CHECK(run.probed_back);
    CHECK(!run.backed_s);
    CHECK(run.x_min > -15.0f - 5.0f); /* no farther than the probe's 15 mm */
    CHECK(ffr_absf(run.probe_end_x) < 3.0f); /* and back where it stood */
    run = orient_run_read(&cfg, corner, 3, 1, 0.0f);
    CHECK(run.probed_back && !run.unfolded);
    CHECK(ffr_absf(run.probe_end_x) < 3.0f);
    CHECK(run.clear);
    /* begun with the body still rolling forward (an S cut short before):
     * the 15 mm are net travel, and the way back ends where it began, not
     * the roll's length beyond (found in review: 14.7 mm at 120 mm/s) */
    for (v0 = 40.0f; v0 <= 120.0f; v0 += 40.0f) {
        run = orient_run_read(&cfg, b, 2, 1, v0);
        CHECK(run.probed_back && !run.unfolded);
        CHECK(run.probe_drift < 3.0f); /* every probe back where it began */
    }
}

/* The body along a wall 7-12 mm off its left side, parallel to it, in a
 * 46 cm hallway with the floor ahead free: both left rangers read their
 * span's bottom. The wide S's first arc (300 mm) swings the rear corner
 * ~12 mm toward the wall before the body's angle carries it off: on the
 * build before, the corner met it at 7-11 mm (orientation bench start seed
 * 11437: 6 mm off the south wall, met at once). The first arc begins at
 * ESCAPE_SOFT_MM (600 mm, ~7 mm) and tightens to 300 mm once the body has
 * turned far enough (both curvatures commanded): the whole orientation
 * with no contact. Nearer than ~7 mm it meets the wall too. A wall across
 * 520 mm ahead leaves room for the wide S but not for the longer first
 * arc: the wide S as before (leg 1 at 300 mm). */
TEST(a_body_along_a_wall_leaves_it_by_an_s_begun_gently)
{
    ffr_config_t cfg;
    float gap;
    ffr_config_default(&cfg);
    for (gap = 7.0f; gap <= 12.0f; gap += 1.0f) {
        const float b[3][3] = {
            {0.0f, 1.0f, cfg.body_half_width_mm + gap}, {0.0f, -1.0f, 460.0f - cfg.body_half_width_mm - gap},
            {1.0f, 0.0f, 520.0f}};
        orient_run_t run = orient_run(&cfg, b, 2);
        CHECK(run.clear);
        CHECK(run.first_leg == 9 && run.s_forward); /* LEG_SOFT */
        CHECK(run.soft_arcs == 3);                   /* 600 mm, then 300 mm */
        run = orient_run(&cfg, b, 3);
        CHECK(run.first_leg == 1 && run.soft_arcs == 0);
        CHECK_NEAR(run.first_rad, -1.0f / 300.0f, 1e-6f); /* the wide S */
    }
}

/* the first look with the left front and rear rangers both within the
 * span (112 and 118 mm): the rear fold move's readings; ir: as fed */
static void rear_fold_start(rig_t *r, const ffr_config_t *cfg, float ir[FFR_IR_COUNT])
{
    rig_init(r, cfg);
    rig_no_walls(cfg, ir);
    ir[FFR_IR_LF] = 112.0f;
    ir[FFR_IR_LR] = 118.0f;
    look_from(r, cfg, ir);
}

/* A fold move forward (the rear fold move, or the move after a rear peak
 * passed) watches its leading end. A front ranger that read within the
 * fold-back span when the move began and now reads LEAD_GROW_MM (8 mm)
 * longer is folded back, its wall nearer than the front corner's turning
 * room: the move turns back (LEG_TURNED), to where it began and on the
 * front fold move's 30 mm, and watches that ranger as the front fold move
 * does. A wall converging ahead, 5 cm off the front corner ranger, reads
 * 10-13 cm, the rear ranger on that side as it is, alike (start seeds 4427,
 * 5964, 7248, 7840: docs/robustness.md "A fold move watches its leading end").
 * Not for a reading grown less, for one that began outside the span (a wall
 * as it is, receding), on a move backward (rear_passed watches that), nor on
 * the last of the four moves before the sweep. */
enum { GROWN, GROWN_LESS, BEGAN_FAR, BACKWARD, LAST_MOVE };
static void fold_move_watched(rig_t *r, const ffr_config_t *cfg, int kind)
{
    float ir[FFR_IR_COUNT];
    rear_fold_start(r, cfg, ir);
    /* as the rear fold move leaves it, 14 mm on */
    r->st.orient.phase = 8u;  /* PH_ESCAPE */
    r->st.orient.leg = 6u;    /* LEG_FOLD */
    r->st.orient.escapes = kind == LAST_MOVE ? FFR_ORIENT_ESCAPE_TRIES : 1u;
    r->st.orient.reverse = kind == BACKWARD ? 1u : 0u;
    r->st.orient.target_rad = 0.0f;
    r->st.orient.leg_mm = 45.0f;
    r->st.orient.goal_mm = r->st.odo.dist_mm + 45.0f - 14.0f;
    r->st.orient.probed = (uint8_t)(1u << FFR_IR_LR); /* LF not probed: watched, but for the move's way */
    r->st.orient.probe_mm[FFR_IR_LF] = kind == BEGAN_FAR ? 170.0f : 112.0f;
    r->st.orient.probe_mm[FFR_IR_LR] = 118.0f;
    ir[FFR_IR_LF] = kind == GROWN_LESS ? 119.0f : (kind == BEGAN_FAR ? 180.0f : 121.0f);
    ir[FFR_IR_LR] = kind == BACKWARD ? 127.0f : 118.0f;
    feed(r, cfg, ir);
    rig_tick(r);
}

TEST(a_fold_move_forward_turns_back_when_its_front_ranger_reads_longer)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    for (kind = GROWN; kind <= LAST_MOVE; ++kind) {
        const ffr_home_orient_t *o = &r.st.orient;
        float dist;
        fold_move_watched(&r, &cfg, kind);
        dist = r.st.odo.dist_mm;
        CHECK(o->phase == 8u);
        if (kind == GROWN) {
            CHECK(o->leg == 7u); /* LEG_TURNED */
            CHECK(o->reverse == 1u);
            CHECK(o->target_rad == 0.0f);
            CHECK(ffr_absf(o->goal_mm - dist - (14.0f + 30.0f)) < 0.5f);
            CHECK(o->probed == (1u << FFR_IR_LF)); /* watched as the front fold move watches */
        } else {
            CHECK(o->leg == 6u); /* on as it was */
            CHECK(o->reverse == (kind == BACKWARD ? 1u : 0u));
            CHECK(ffr_absf(o->goal_mm - dist - 31.0f) < 0.5f);
        }
    }
}

/* The same from the first look, tick by tick: those two readings begin the
 * rear fold move (forward, 45 mm); the front ranger reading 9 mm longer
 * after some of it, the move turns back as far as it came and 30 mm on.
 * That ranger's reading dropping to its span's bottom on the way back, the
 * look after it counts it folded back (clear_step, as after the front fold
 * move), not a wall at the front corner: the sweep begins, no other move
 * (taken as read, the bottom puts a wall within the turning circle). */
TEST(a_fold_move_turned_back_goes_as_far_as_it_came_and_tells_fold_back)
{
    ffr_config_t cfg;
    rig_t r;
    const ffr_home_orient_t *o = &r.st.orient;
    float ir[FFR_IR_COUNT], dist0, came;
    int i;
    ffr_config_default(&cfg);
    if (FFR_HOME_FOLD_MM > 0.0f) {
        CHECK(FFR_HOME_FOLD_MM > 0.0f); /* the fold moves are off with the probe on */
        return;
    }
    rear_fold_start(&r, &cfg, ir);
    dist0 = r.st.odo.dist_mm;
    for (i = 0; i < 20; ++i) { /* the first look, then on into the move */
        feed(&r, &cfg, ir);
        rig_tick(&r);
    }
    CHECK(o->phase == 8u && o->leg == 6u && o->reverse == 0u); /* PH_ESCAPE, LEG_FOLD, forward */
    CHECK(ffr_absf(o->leg_mm - 45.0f) < 0.5f);
    came = r.st.odo.dist_mm - dist0;
    CHECK(came > 1.0f && came < 40.0f); /* on its way */
    ir[FFR_IR_LF] = 121.0f;
    feed(&r, &cfg, ir);
    rig_tick(&r);
    came = r.st.odo.dist_mm - dist0;
    CHECK(o->leg == 7u && o->reverse == 1u); /* LEG_TURNED */
    CHECK(ffr_absf(o->goal_mm - r.st.odo.dist_mm - (came + 30.0f)) < 0.5f);
    ir[FFR_IR_LF] = cfg.ir_min_mm; /* dropped as the body backs away: folded back */
    for (i = 0; i < 400 && o->leg == 7u; ++i) {
        feed(&r, &cfg, ir);
        rig_tick(&r);
    }
    CHECK(o->leg != 7u);   /* the way back ended and the look came */
    CHECK(o->phase == 0u); /* PH_SWEEP */
    CHECK(o->escapes == 1u);
}

/* A line across a corner with too little floor ahead for the S
 * (corner_chord: the right front ranger measures its wall, 173 mm, the right
 * rear one reads its span's bottom; the centre one a wall 204 mm ahead:
 * start seed 4632's first readings). Before,
 * the escapes were given up at once and the sweep turned in place: if the
 * line is one wall along the side at a slant, nearest at the rear corner,
 * the turn swings that corner into it (start seeds 4632, 8130, 9434, 41-49
 * mm off it along the rear beam). First, on the orientation's first move, a
 * straight step forward (CHORD_STEP_MM, 45 mm), the floor ahead allowing;
 * on a later look, or with the floor ahead shut, given up as before. */
enum { CHORD_FIRST, CHORD_LATER, CHORD_SHUT };
TEST(a_line_across_a_corner_first_steps_forward_when_the_floor_allows)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    for (kind = CHORD_FIRST; kind <= CHORD_SHUT; ++kind) {
        const ffr_home_orient_t *o = &r.st.orient;
        float ir[FFR_IR_COUNT];
        rig_init(&r, &cfg);
        rig_no_walls(&cfg, ir);
        /* start seed 4632's first readings */
        ir[FFR_IR_CF] = kind == CHORD_SHUT ? 120.0f : 204.0f;
        ir[FFR_IR_LF] = 662.0f;
        ir[FFR_IR_RF] = 173.0f;
        ir[FFR_IR_LR] = 531.0f;
        ir[FFR_IR_RR] = cfg.ir_min_mm;
        look_from(&r, &cfg, ir);
        if (kind == CHORD_LATER) {
            r.st.orient.escapes = 1u; /* one move made already */
        }
        CHECK(ffr_orient_step(&r.st) == 0);
        if (kind == CHORD_FIRST) {
            CHECK(o->phase == 8u); /* PH_ESCAPE */
            CHECK(o->leg == 0u && o->reverse == 0u && o->target_rad == 0.0f);
            CHECK(ffr_absf(o->goal_mm - r.st.odo.dist_mm - 45.0f) < 0.5f);
            CHECK(o->escapes == 1u);
        } else {
            CHECK(o->escapes == FFR_ORIENT_ESCAPE_TRIES); /* given up, the sweep next */
            CHECK(o->phase == 7u);   /* PH_CLEAR */
        }
    }
}

/* The orientation's first look from where look_from left it: with `steps`,
 * the 100 mm straight step forward begins (first_step); else the sweep's
 * turn begins at once. No escape is counted either way. */
static void first_look_steps_or_sweeps(rig_t *r, int steps)
{
    const ffr_home_orient_t *o = &r->st.orient;
    CHECK(ffr_orient_step(&r->st) == 0);
    CHECK(o->escapes == 0u);
    if (steps) {
        CHECK(o->phase == 8u); /* PH_ESCAPE */
        CHECK(o->leg == 0u && o->reverse == 0u && o->target_rad == 0.0f);
        CHECK(ffr_absf(o->goal_mm - r->st.odo.dist_mm - 100.0f) < 0.5f);
    } else {
        CHECK(o->phase == 0u); /* PH_SWEEP: the turn begins here */
        CHECK(r->st.cmd_v_mm_s == 0.0f && r->st.cmd_w_rad_s != 0.0f);
    }
}

/* The arbitrary start: placed in a hallway, a wall's end may stand a
 * centimetre beside the body where no ranger sees it (the fresh +-2.5 cm
 * hallway row's start seed 298: a jamb 16 mm off the left side at the axle,
 * its wall running back between the left rangers' beams; the sweep's turn
 * met it at 0.2 s). With a rear ranger reading no wall (open floor behind
 * that side), the first look steps straight forward 100 mm before the
 * sweep. Not with walls read behind on both sides, nor from the home
 * circle, nor with the floor ahead shut, nor once the robot has moved. */
enum { STEP_OPEN_BEHIND, STEP_WALLS_BEHIND, STEP_FROM_HOME, STEP_FRONT_SHUT, STEP_MOVED };
TEST(from_a_hallway_open_behind_the_first_look_steps_forward_before_the_sweep)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    for (kind = STEP_OPEN_BEHIND; kind <= STEP_MOVED; ++kind) {
        float ir[FFR_IR_COUNT];
        cfg.start_area = kind == STEP_FROM_HOME ? FFR_START_HOME : FFR_START_HALLWAY;
        rig_init(&r, &cfg);
        rig_no_walls(&cfg, ir);
        /* start seed 298's first readings (CF, LR, RR: no wall) */
        ir[FFR_IR_LF] = 436.0f;
        ir[FFR_IR_RF] = 266.0f;
        if (kind == STEP_WALLS_BEHIND) {
            ir[FFR_IR_LR] = 423.0f;
            ir[FFR_IR_RR] = 495.0f;
        } else if (kind == STEP_FRONT_SHUT) {
            ir[FFR_IR_CF] = 170.0f; /* 270 mm ahead of the axle, above the fold-back span: no room for the step */
        }
        look_from(&r, &cfg, ir);
        if (kind == STEP_MOVED) {
            r.st.odo.dist_mm = 5.0f;
        }
        first_look_steps_or_sweeps(&r, kind == STEP_OPEN_BEHIND);
    }
}

/* From the home circle: a junction's outer corner (the end of a block
 * between two open ways) may stand 25-50 mm off a side between its two
 * rangers' beams, where none sees it (orientation bench start seeds 6724,
 * 7729, 9211: the middle room's outer corner by the right side). The sweep
 * turns toward home_wall_side (right); with nothing near as read, both
 * rangers of that side reading no wall within 400 mm and both of the other
 * side reading one, the first look steps straight forward 100 mm before the
 * sweep. Not with a wall read on the turning side, nor with the open side
 * the other one, nor with no wall along the other side (one wall behind:
 * beside_one_wall's), nor with the floor ahead shut. */
enum { HOME_OPEN_TURN_SIDE, HOME_WALL_TURN_SIDE, HOME_OPEN_OTHER_SIDE, HOME_NOTHING_BESIDE, HOME_FRONT_SHUT };
TEST(from_home_both_rangers_open_on_the_sweeps_side_the_first_look_steps_forward)
{
    ffr_config_t cfg;
    rig_t r;
    int kind;
    ffr_config_default(&cfg);
    for (kind = HOME_OPEN_TURN_SIDE; kind <= HOME_FRONT_SHUT; ++kind) {
        float ir[FFR_IR_COUNT];
        rig_init(&r, &cfg);
        r.st.cfg.home_wall_side = FFR_HOME_WALL_RIGHT; /* the sweep turns right */
        rig_no_walls(&cfg, ir);
        /* start seed 6724's first readings: the left pair on the hallway's
         * far wall, the right pair past the corner (RF, RR: nothing) */
        ir[FFR_IR_CF] = 365.0f;
        ir[FFR_IR_LF] = 311.0f;
        ir[FFR_IR_LR] = 224.0f;
        if (kind == HOME_WALL_TURN_SIDE) {
            ir[FFR_IR_RR] = 380.0f;
        } else if (kind == HOME_OPEN_OTHER_SIDE) {
            ir[FFR_IR_LF] = FFR_IR_NONE(&cfg);
            ir[FFR_IR_LR] = FFR_IR_NONE(&cfg);
            ir[FFR_IR_RF] = 311.0f;
            ir[FFR_IR_RR] = 224.0f;
        } else if (kind == HOME_NOTHING_BESIDE) {
            /* beside_one_wall facing 105 degrees: only the wall behind */
            ir[FFR_IR_CF] = FFR_IR_NONE(&cfg);
            ir[FFR_IR_LF] = FFR_IR_NONE(&cfg);
            ir[FFR_IR_LR] = 375.0f;
            ir[FFR_IR_RR] = 721.0f;
        } else if (kind == HOME_FRONT_SHUT) {
            ir[FFR_IR_CF] = 170.0f; /* 270 mm ahead of the axle: no room for the step */
        }
        look_from(&r, &cfg, ir);
        first_look_steps_or_sweeps(&r, kind == HOME_OPEN_TURN_SIDE);
    }
}

SUITE(home_orient,
      TEST_REF(the_walls_direction_whatever_the_start_heading),
      TEST_REF(the_open_end_and_the_walls_around),
      TEST_REF(the_route_direction_by_the_wall_side_rule),
      TEST_REF(a_far_wall_across_between_the_bins_places_the_robot),
      TEST_REF(a_far_wall_read_short_does_not_shut_the_way_along_the_hallway),
      TEST_REF(a_junction_read_short_keeps_the_way_with_its_wall),
      TEST_REF(a_narrow_hallway_off_its_middle_is_a_way),
      TEST_REF(the_aim_decides_as_aimints_one_tick_aim),
      TEST_REF(the_aim_turns_on_its_own_tick), TEST_REF(the_shifts_turn_is_not_done_while_the_body_still_spins),
      TEST_REF(the_firmware_orients_before_the_route),
      TEST_REF(the_nearest_wall_from_the_five_rangers),
      TEST_REF(room_to_turn_first_then_the_sweep),
      TEST_REF(a_small_shift_across_the_way_is_not_made),
      TEST_REF(a_reading_that_may_be_folded_back_counts_as_near),
      TEST_REF(a_short_move_tells_folded_back_from_far),
      TEST_REF(backed_up_to_a_wall_read_folded_back),
      TEST_REF(a_rear_corner_read_folded_back_moves_forward_before_the_turn),
      TEST_REF(a_front_ranger_read_within_the_span_backs_straight_before_the_turn),
      TEST_REF(after_the_rear_fold_move_a_reading_that_did_not_grow_is_the_wall_left_behind),
      TEST_REF(a_far_wall_end_beside_the_way_does_not_close_it),
      TEST_REF(the_front_shut_straight_back_before_the_s),
      TEST_REF(a_wall_line_in_the_sweep_brakes_at_once),
      TEST_REF(a_ranger_on_the_sweeps_side_at_its_bottom_stops_the_sweep),
      TEST_REF(a_ranger_at_its_bottom_off_the_sweeps_side_or_late_does_not_stop_it),
      TEST_REF(the_sweep_keeps_how_far_each_rangers_last_stretch_of_wall_passes),
      TEST_REF(a_ranger_at_its_bottom_along_a_wall_outside_the_turning_circle_does_not_stop_the_sweep),
      TEST_REF(the_sweep_turns_away_from_a_wall_beside),
      TEST_REF(the_sweep_turns_away_from_a_front_corner_read_folded_back),
      TEST_REF(the_sweep_turns_toward_a_front_corner_read_folded_back_with_the_centre),
      TEST_REF(a_wall_beside_below_the_span_is_no_end_of_the_s),
      TEST_REF(a_wall_beside_this_near_gets_the_wider_s_where_the_floor_allows),
      TEST_REF(a_front_ranger_just_above_its_bottom_still_gets_the_wider_s),
      TEST_REF(back_first_from_a_wall_beside_nearer_at_the_front),
      TEST_REF(room_to_turn_again_after_the_shift),
      TEST_REF(a_straight_escape_stops_short_of_a_wall_across_at_a_slant),
      TEST_REF(a_straight_escape_is_not_refused_by_a_line_across_a_corner),
      TEST_REF(a_wall_square_to_the_walls_from_two_measured_hits),
      TEST_REF(a_straight_escape_back_stops_as_the_rear_pairs_chord_nears),
      TEST_REF(a_straight_escape_back_between_walls_beside_goes_its_length),
      TEST_REF(a_line_across_a_corner_with_no_floor_for_the_s_is_no_wall_beside),
      TEST_REF(a_wall_beside_with_little_floor_ahead_still_gets_the_s),
      TEST_REF(an_s_short_of_floor_ahead_backs_straight_first_with_a_far_wall_behind),
      TEST_REF(a_wall_ahead_read_folded_back_in_a_corner_is_backed_from_first),
      TEST_REF(the_looks_probe_finding_the_wall_as_read_returns_to_where_it_stood),
      TEST_REF(a_wall_ahead_read_as_it_is_gets_the_probe_and_no_move_back),
      TEST_REF(a_body_along_a_wall_leaves_it_by_an_s_begun_gently),
      TEST_REF(a_fold_move_forward_turns_back_when_its_front_ranger_reads_longer),
      TEST_REF(a_fold_move_turned_back_goes_as_far_as_it_came_and_tells_fold_back),
      TEST_REF(a_line_across_a_corner_first_steps_forward_when_the_floor_allows),
      TEST_REF(from_a_hallway_open_behind_the_first_look_steps_forward_before_the_sweep),
      TEST_REF(from_home_both_rangers_open_on_the_sweeps_side_the_first_look_steps_forward),
      TEST_REF(a_shift_backward_stops_with_room_to_turn_before_the_wall_behind),
      TEST_REF(a_move_back_stops_when_a_rear_ranger_passes_its_peak),
      TEST_REF(a_shift_backward_stops_where_a_rear_ranger_reaches_its_bottom),
      TEST_REF(a_shift_toward_a_wall_read_short_ends_on_the_front_ranger));
