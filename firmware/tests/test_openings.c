#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* a step's start with no wall in sight: the default config, every ranger
 * reading nothing, the openings reset */
static void fresh_step(ffr_config_t *cfg, ffr_openings_t *op, float ir[FFR_IR_COUNT])
{
    ffr_config_default(cfg);
    rig_no_walls(cfg, ir);
    ffr_openings_reset(op);
}

TEST(open_from_the_start_is_no_opening)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    /* no wall seen, so no opening (a corridor behind a junction is not a door) */
    fresh_step(&cfg, &op, ir);
    rig_travel(&op, &cfg, ir, &d, 50);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_wall_then_open_is_an_opening_and_stays_one)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    /* a wall for 150 mm, then open */
    fresh_step(&cfg, &op, ir);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    {
        float wall_end = op.open_at_mm[FFR_SIDE_LEFT];
        /* the hit point is ahead of the origin by x + d cos(45) */
        CHECK_NEAR(wall_end, (d - 3.0f) + 80.0f + 226.0f * 0.70710678f, 0.5);
    }
    /* the beam through the opening meets a far wall (565 mm to the side) */
    ir[FFR_IR_LF] = 700.0f;
    rig_travel(&op, &cfg, ir, &d, 5);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT)); /* 15 mm < confirm */
    rig_travel(&op, &cfg, ir, &d, 5);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_LEFT], 0.0, 1e-6);
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_RIGHT], 0.0, 1e-6); /* nothing there reads open */
    /* latched: a wall seen again (the far side of a junction) does not undo it */
    ir[FFR_IR_LF] = 200.0f;
    rig_travel(&op, &cfg, ir, &d, 40);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_dropout_counts_half)
{
    /* no reading at all counts half: 30 mm of it is not an opening, 42 mm is */
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    fresh_step(&cfg, &op, ir);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    ir[FFR_IR_LF] = FFR_IR_NONE(&cfg);
    rig_travel(&op, &cfg, ir, &d, 10);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    rig_travel(&op, &cfg, ir, &d, 4);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_hit_jumping_out_is_past_the_wall_end_a_drift_is_followed)
{
    /* the front hit jumping out 100 mm to the side (through a door, still
     * inside open_mm) is past the wall's end */
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    int i;
    fresh_step(&cfg, &op, ir);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    ir[FFR_IR_LF] = 226.0f + 100.0f / 0.70710678f;
    {
        ffr_ir_geom_t g;
        float px, py;
        CHECK(ffr_hit_beside(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_IR_LF, &px, &py));
    }
    rig_travel(&op, &cfg, ir, &d, 8);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
    /* and the wall's end is the last hit on the wall, not the far one */
    CHECK_NEAR(op.open_at_mm[FFR_SIDE_LEFT], 147.0f + 80.0f + 226.0f * 0.70710678f, 0.5);
    /* a slow drift out is followed, not taken for an opening */
    ffr_openings_reset(&op);
    for (i = 0; i < 100; ++i, d += 3.0f) {
        ffr_ir_geom_t g;
        ir[FFR_IR_LF] = 226.0f + (float)i * 1.5f;
        ffr_openings_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, -1);
    }
    CHECK(op.seen[FFR_SIDE_LEFT] && !ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_wall_across_behind_receding_is_no_wall_seen)
{
    /* leaving a room into a wide hallway: nothing beside on the right within
     * open_mm, but the rear right ranger's beam meets the wall square across
     * behind (the 2001 plan's west outer wall, seeds 66, 72, 83). Each mm of
     * travel puts that hit 1 mm farther to the side: the range grows by
     * sqrt(2) mm. In a step that ends at the right's opening, no opening
     * (before REAR_SEEN_DRIFT_MM it opened at 60 mm of travel: 41 checks fail) */
    ffr_config_t cfg;
    ffr_openings_t op;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    int i;
    fresh_step(&cfg, &op, ir);
    for (i = 0; i < 60; ++i, d += 3.0f) {
        ir[FFR_IR_RR] = 188.0f + 1.41421356f * d;
        ffr_openings_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, FFR_SIDE_RIGHT);
        CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
    }
    CHECK(!op.seen[FFR_SIDE_RIGHT]);
    /* a wall alongside read by the rear ranger alone (its reading a few mm
     * either way) is still seen, and its end is an opening */
    ffr_openings_reset(&op);
    d = 0.0f;
    for (i = 0; i < 40; ++i, d += 3.0f) {
        ir[FFR_IR_RR] = 226.0f + (float)((i % 5) - 2) * 4.0f;
        ffr_openings_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, -1);
    }
    CHECK(op.seen[FFR_SIDE_RIGHT] && !ffr_opening(&op, FFR_SIDE_RIGHT));
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    rig_travel(&op, &cfg, ir, &d, 20);
    CHECK(ffr_opening(&op, FFR_SIDE_RIGHT));
}

/* From a hallway start (the explorer's legs), the front corner ranger's
 * first hit of a step more than THROUGH_MM (120 mm) farther to the side
 * than the wall the rear ranger passes along is seen through an opening in
 * that wall (a door's far side, a room's wall beyond it: +-2.5 cm hallway
 * start seed 2415, the front right ranger at 446 mm, 385 mm to the side,
 * the rear one's wall at ~220): it is no wall, and the opening's end is
 * where the rear ranger last hit its wall. Taken for the wall, its hit put
 * the end 30 cm past the door's near jamb and the probe met the far one. A
 * first hit in line with the rear's wall (within THROUGH_MM) is the wall,
 * and the route's legs (a home start) keep the plain rule, the far hit
 * putting the end, as before. */
TEST(from_a_hallway_start_a_front_hit_beyond_the_rear_rangers_wall_is_no_wall_end)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    int area, far;
    for (area = FFR_START_HOME; area <= FFR_START_HALLWAY; ++area) {
        for (far = 0; far <= 1; ++far) {
            float d = 0.0f, rx, ry, fx, fy, rear_at, front_at;
            int i;
            fresh_step(&cfg, &op, ir);
            cfg.start_area = (uint8_t)area;
            /* the rear ranger passes along a wall, its reading a few mm either way */
            for (i = 0; i < 40; ++i, d += 3.0f) {
                ir[FFR_IR_RR] = 226.0f + (float)((i % 5) - 2) * 4.0f;
                ffr_openings_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, -1);
            }
            CHECK(ffr_hit_beside(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_IR_RR, &rx, &ry));
            rear_at = d + rx; /* its last hit: the next tick, the front one's */
            CHECK(op.seen[FFR_SIDE_RIGHT] && !ffr_opening(&op, FFR_SIDE_RIGHT));
            /* the front one meets a face: far beyond that wall, or in line with it */
            ir[FFR_IR_RF] = far ? 446.0f : 280.0f;
            CHECK(ffr_hit_beside(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_IR_RF, &fx, &fy));
            CHECK(far ? ffr_absf(fy) - op.rear_lat0_mm[FFR_SIDE_RIGHT] > 150.0f
                      : ffr_absf(fy) - op.rear_lat0_mm[FFR_SIDE_RIGHT] < 60.0f);
            front_at = d + fx;
            rig_travel(&op, &cfg, ir, &d, 1);
            /* then open, and the rear ranger leaves its wall */
            ir[FFR_IR_RF] = FFR_IR_NONE(&cfg);
            ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
            rig_travel(&op, &cfg, ir, &d, 20);
            CHECK(ffr_opening(&op, FFR_SIDE_RIGHT));
            CHECK_NEAR(op.open_at_mm[FFR_SIDE_RIGHT], (far && area == FFR_START_HALLWAY) ? rear_at : front_at, 0.5);
        }
    }
}

/* ---- whole openings (GAP events): a corridor of wall segments ---------- */

/* Axis-aligned wall faces, mm: x0 == x1 (across the corridor) or y0 == y1 (along it). */
typedef struct {
    float x0, y0, x1, y1;
} seg_t;

/* The corridor runs along +x, the left wall at y = +230 all along. On the
 * right (y = -230): a wall to x = 460, a door to 920 with a room's wall
 * going off to the right at x = 920 (20 mm thick), a hallway from 940 to
 * 1400 where the wall resumes, going on to the right too. */
static const seg_t k_corridor[] = {
    {-2000.0f, 230.0f, 4000.0f, 230.0f},
    {-2000.0f, -230.0f, 460.0f, -230.0f},
    {920.0f, -230.0f, 920.0f, -1500.0f},   /* the room's far wall's near face (its underside) */
    {920.0f, -230.0f, 940.0f, -230.0f},    /* its end                                         */
    {940.0f, -230.0f, 940.0f, -1500.0f},   /* its other face, the hallway's side              */
    {1400.0f, -230.0f, 1400.0f, -1500.0f}, /* the hallway's far side                          */
    {1400.0f, -230.0f, 4000.0f, -230.0f},
};
#define N_CORRIDOR ((int)(sizeof(k_corridor) / sizeof(k_corridor[0])))

static float lo_f(float a, float b) { return a < b ? a : b; }
static float hi_f(float a, float b) { return a > b ? a : b; }

/* ranger i's range from the true pose (mm, rad) to the nearest face, FFR_IR_NONE past range */
static float seg_beam_mm(const ffr_config_t *cfg, float x, float y, float th, int i)
{
    float mx, my, ux, uy;
    float best = FFR_IR_NONE(cfg);
    int k;
    rig_ray(cfg, i, x, y, th, &mx, &my, &ux, &uy);
    for (k = 0; k < N_CORRIDOR; ++k) {
        const seg_t *w = &k_corridor[k];
        float t = -1.0f, p;
        if (w->x0 == w->x1 && ffr_absf(ux) > 1e-4f) {
            t = (w->x0 - mx) / ux;
            p = my + t * uy;
            if (p < lo_f(w->y0, w->y1) || p > hi_f(w->y0, w->y1)) {
                t = -1.0f;
            }
        } else if (w->y0 == w->y1 && ffr_absf(uy) > 1e-4f) {
            t = (w->y0 - my) / uy;
            p = mx + t * ux;
            if (p < lo_f(w->x0, w->x1) || p > hi_f(w->x0, w->x1)) {
                t = -1.0f;
            }
        }
        if (t > 0.0f && t < best) {
            best = t;
        }
    }
    return ffr_ir_valid(cfg, best) ? best : FFR_IR_NONE(cfg);
}

/* Drive from (x0, y0) along heading th in 3 mm ticks to x_end, feeding
 * ffr_gaps_update the corridor's readings; yaw_rad is what it is told the
 * heading is off the corridor. The odometry distance starts at 0. */
static void gaps_drive(ffr_openings_t *op, const ffr_config_t *cfg, float x0, float y0, float th, float x_end,
                       float yaw_rad)
{
    float d = 0.0f;
    float x = x0, y = y0;
    ffr_openings_reset(op);
    while (x < x_end) {
        float ir[FFR_IR_COUNT];
        ffr_ir_geom_t g;
        int i;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            ir[i] = seg_beam_mm(cfg, x, y, th, i);
        }
        ffr_gaps_update(op, cfg, rig_geom(&g, cfg, ir), ir, d, 3.0f, yaw_rad);
        d += 3.0f;
        x += 3.0f * ffr_cosf(th);
        y += 3.0f * ffr_sinf(th);
    }
}

TEST(gaps_a_door_then_a_hallway_are_two_openings_each_put_by_its_far_edge)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    ffr_config_default(&cfg);
    /* the wall seen, then the door: one opening once the room's far wall is
     * seen beside (its underside, ~30 cm ahead at first) */
    gaps_drive(&op, &cfg, 0.0f, 0.0f, 0.0f, 500.0f, 0.0f);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 0 && !ffr_gap(&op, FFR_SIDE_RIGHT, 1));
    gaps_drive(&op, &cfg, 0.0f, 0.0f, 0.0f, 760.0f, 0.0f);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 1);
    CHECK(ffr_gap(&op, FFR_SIDE_RIGHT, 0) && ffr_gap(&op, FFR_SIDE_RIGHT, 1) && !ffr_gap(&op, FFR_SIDE_RIGHT, 2));
    /* its far edge: the room's wall; the robot goes to half a hallway before it */
    CHECK_NEAR(op.gap_end_mm[FFR_SIDE_RIGHT], 920.0, 3.0);
    CHECK_NEAR(ffr_gap_middle_mm(&op, &cfg, FFR_SIDE_RIGHT), 690.0, 6.0);
    /* on: the room's wall end, then the hallway, then the wall after it: the second */
    gaps_drive(&op, &cfg, 0.0f, 0.0f, 0.0f, 1250.0f, 0.0f);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 2 && ffr_gap(&op, FFR_SIDE_RIGHT, 2));
    CHECK_NEAR(op.gap_end_mm[FFR_SIDE_RIGHT], 1400.0, 3.0);
    CHECK_NEAR(ffr_gap_middle_mm(&op, &cfg, FFR_SIDE_RIGHT), 1170.0, 6.0);
    /* the left wall never opened */
    CHECK(op.gaps[FFR_SIDE_LEFT] == 0);
}

TEST(gaps_a_step_that_starts_in_an_opening_counts_it_from_its_far_edge)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    ffr_config_default(&cfg);
    /* started in the door: open at once, the wall before it never seen: the
     * door still counts, its far edge where it is */
    gaps_drive(&op, &cfg, 300.0f, 0.0f, 0.0f, 600.0f, 0.0f);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 1);
    CHECK_NEAR(op.gap_end_mm[FFR_SIDE_RIGHT], 920.0 - 300.0, 3.0);
    CHECK_NEAR(ffr_gap_middle_mm(&op, &cfg, FFR_SIDE_RIGHT), 920.0f - 300.0f - cfg.hallway_half_mm, 3.0);
    /* a step that starts seeing the room's wall through the door: the hallway is the first */
    gaps_drive(&op, &cfg, 700.0f, 0.0f, 0.0f, 1250.0f, 0.0f);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 1);
    CHECK_NEAR(ffr_gap_middle_mm(&op, &cfg, FFR_SIDE_RIGHT) + 700.0f, 1170.0, 6.0);
}

TEST(gaps_a_yawed_robot_puts_the_far_edge_along_the_corridor)
{
    /* heading 9 degrees off the corridor: the far wall's first hit, 35 cm to
     * the side, is 5 cm further along the corridor than the robot frame's x
     * says; told the yaw, the edge is where it is */
    ffr_config_t cfg;
    ffr_openings_t op;
    float th = 9.0f * FFR_DEG;
    float err_told, err_not;
    ffr_config_default(&cfg);
    gaps_drive(&op, &cfg, 300.0f, 0.0f, th, 650.0f, th);
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 1);
    /* the path is 1.2 % longer than its run along x: compare in path length */
    err_told = op.gap_end_mm[FFR_SIDE_RIGHT] - (920.0f - 300.0f) / ffr_cosf(th);
    gaps_drive(&op, &cfg, 300.0f, 0.0f, th, 650.0f, 0.0f);
    err_not = op.gap_end_mm[FFR_SIDE_RIGHT] - (920.0f - 300.0f) / ffr_cosf(th);
    CHECK(ffr_absf(err_told) < 10.0f);
    CHECK(err_not < -35.0f);
}

TEST(gaps_the_far_edge_is_refined_from_nearer_hits_on_its_face)
{
    /* a part whose output is 60 mV low (within a GP2D12's datasheet spread
     * of +-150 mV) reads ~5 cm long at 47 cm but 1.5 cm at 24 cm: the far
     * wall's first hit is put ~2 cm beyond the edge; the later hits on the same face, each from nearer, bring the
     * edge back; the hits on the wall end and the side after it (moving on
     * with the robot) are not taken */
    ffr_config_t cfg;
    ffr_openings_t op;
    float d = 0.0f, x = 300.0f;
    float first_err = 0.0f;
    ffr_config_default(&cfg);
    ffr_openings_reset(&op);
    for (; x < 760.0f; x += 3.0f, d += 3.0f) {
        float ir[FFR_IR_COUNT];
        ffr_ir_geom_t g;
        int i;
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            ir[i] = seg_beam_mm(&cfg, x, 0.0f, 0.0f, i);
        }
        if (ffr_ir_valid(&cfg, ir[FFR_IR_RF])) {
            float mv = cfg.ir_k_mv_mm / (ir[FFR_IR_RF] + cfg.ir_d0_mm) - 60.0f;
            ir[FFR_IR_RF] = cfg.ir_k_mv_mm / mv - cfg.ir_d0_mm;
        }
        ffr_gaps_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, 0.0f);
        if (op.gaps[FFR_SIDE_RIGHT] == 1 && first_err == 0.0f) {
            first_err = op.gap_end_mm[FFR_SIDE_RIGHT] - (920.0f - 300.0f);
        }
    }
    CHECK(op.gaps[FFR_SIDE_RIGHT] == 1);
    CHECK(first_err > 15.0f);
    /* about half of it left, what the part's error is at the corner's range */
    CHECK(ffr_absf(op.gap_end_mm[FFR_SIDE_RIGHT] - (920.0f - 300.0f)) < 0.6f * first_err);
}

TEST(gaps_a_spike_is_no_wall_and_a_dropout_no_opening)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    int i;
    fresh_step(&cfg, &op, ir);
    /* open, then one short reading beside (a spike) among open ones: no wall,
     * no opening counted */
    for (i = 0; i < 60; ++i, d += 3.0f) {
        ffr_ir_geom_t g;
        ir[FFR_IR_LF] = (i == 30) ? 300.0f : FFR_IR_NONE(&cfg);
        ffr_gaps_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, 0.0f);
    }
    CHECK(op.gap_open[FFR_SIDE_LEFT] && op.gaps[FFR_SIDE_LEFT] == 0);
    /* a wall beside for wall_seen_mm: one opening */
    for (i = 0; i < 20; ++i, d += 3.0f) {
        ffr_ir_geom_t g;
        ir[FFR_IR_LF] = 300.0f;
        ffr_gaps_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, 0.0f);
    }
    CHECK(op.gaps[FFR_SIDE_LEFT] == 1 && !op.gap_open[FFR_SIDE_LEFT]);
    /* then the wall with missing readings of 15 mm (counted half: 7.5 mm) now
     * and then: still the wall, no second opening begun */
    for (i = 0; i < 100; ++i, d += 3.0f) {
        ffr_ir_geom_t g;
        ir[FFR_IR_LF] = (i % 10 < 5) ? FFR_IR_NONE(&cfg) : 300.0f;
        ffr_gaps_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f, 0.0f);
    }
    CHECK(!op.gap_open[FFR_SIDE_LEFT] && op.gaps[FFR_SIDE_LEFT] == 1);
}

/* The route step end to end: FOLLOW LEFT until the n-th opening on the right,
 * the firmware driving in the corridor above (true pose from its PWM). */
static float follow_to_gap(uint8_t n)
{
    ffr_config_t cfg;
    rig_t r;
    float x = 0.0f, y = 0.0f, th = 0.0f;
    int32_t prev[2] = {0, 0};
    int i;
    ffr_config_default(&cfg);
    cfg.route[0].op = FFR_OP_FOLLOW;
    cfg.route[0].side = FFR_SIDE_LEFT;
    cfg.route[0].event = FFR_EV_GAP_R;
    cfg.route[0].arg = n;
    cfg.route[1].op = FFR_OP_END;
    cfg.route_len = 2;
    rig_init(&r, &cfg);
    r.out.state = FFR_ST_IDLE;
    for (i = 0; i < 3000 && r.out.state != FFR_ST_FAILED; ++i) {
        const float mm_per_tick = 2.0f * FFR_PI * cfg.wheel_radius_mm / cfg.encoder_ticks_per_rev;
        float dl, dr, ds, dth;
        int k;
        for (k = 0; k < FFR_IR_COUNT; ++k) {
            r.in.ir_mv[k] = ffr_ir_valid(&cfg, seg_beam_mm(&cfg, x, y, th, k))
                                ? rig_mv_for_mm(&cfg, seg_beam_mm(&cfg, x, y, th, k))
                                : 0u;
        }
        r.in.start = i > 0;
        rig_tick(&r);
        dl = (float)(r.in.enc[0] - prev[0]) * mm_per_tick;
        dr = (float)(r.in.enc[1] - prev[1]) * mm_per_tick;
        prev[0] = r.in.enc[0];
        prev[1] = r.in.enc[1];
        ds = 0.5f * (dl + dr);
        dth = (dr - dl) / cfg.track_width_mm;
        x += ds * ffr_cosf(th + 0.5f * dth);
        y += ds * ffr_sinf(th + 0.5f * dth);
        th += dth;
    }
    /* the END after it: the route ran out with no flame */
    CHECK(r.out.state == FFR_ST_FAILED && r.out.fail_code == FFR_FAIL_NO_FLAME);
    CHECK(ffr_absf(y) < 60.0f);
    return x;
}

TEST(gaps_follow_stops_in_the_middle_of_the_nth_opening)
{
    /* the door's middle is 690, the hallway's 1170 */
    CHECK_NEAR(follow_to_gap(1), 690.0, 40.0);
    CHECK_NEAR(follow_to_gap(0), 690.0, 40.0);
    CHECK_NEAR(follow_to_gap(2), 1170.0, 40.0);
}

TEST(open_a_far_edge_seen_before_the_assumed_middle_puts_the_middle_between_the_edges)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    ffr_config_default(&cfg);
    ffr_openings_reset(&op);
    op.opened[FFR_SIDE_LEFT] = 1;
    op.open_at_mm[FFR_SIDE_LEFT] = 1000.0f;
    /* no far edge yet: half a hallway past the wall's end, as before */
    CHECK_NEAR(ffr_open_middle_mm(&op, &cfg, FFR_SIDE_LEFT), 1000.0f + cfg.hallway_half_mm, 0.01);
    /* a far edge before the wall's end is an earlier opening's: not this one */
    op.gap_end_mm[FFR_SIDE_LEFT] = 700.0f;
    CHECK_NEAR(ffr_open_middle_mm(&op, &cfg, FFR_SIDE_LEFT), 1000.0f + cfg.hallway_half_mm, 0.01);
    /* a 36 cm door: its middle between the two edges, short of the assumed one */
    op.gap_end_mm[FFR_SIDE_LEFT] = 1360.0f;
    CHECK_NEAR(ffr_open_middle_mm(&op, &cfg, FFR_SIDE_LEFT), 1180.0, 0.01);
    /* a wide door's far edge never sends the robot past the assumed middle */
    op.gap_end_mm[FFR_SIDE_LEFT] = 1560.0f;
    CHECK_NEAR(ffr_open_middle_mm(&op, &cfg, FFR_SIDE_LEFT), 1000.0f + cfg.hallway_half_mm, 0.01);
    /* the other side is its own */
    CHECK_NEAR(ffr_open_middle_mm(&op, &cfg, FFR_SIDE_RIGHT), cfg.hallway_half_mm, 0.01);
}

SUITE(openings,
      TEST_REF(open_from_the_start_is_no_opening),
      TEST_REF(a_wall_then_open_is_an_opening_and_stays_one),
      TEST_REF(a_dropout_counts_half),
      TEST_REF(a_hit_jumping_out_is_past_the_wall_end_a_drift_is_followed),
      TEST_REF(a_wall_across_behind_receding_is_no_wall_seen),
      TEST_REF(from_a_hallway_start_a_front_hit_beyond_the_rear_rangers_wall_is_no_wall_end),
      TEST_REF(gaps_a_door_then_a_hallway_are_two_openings_each_put_by_its_far_edge),
      TEST_REF(gaps_a_step_that_starts_in_an_opening_counts_it_from_its_far_edge),
      TEST_REF(gaps_a_yawed_robot_puts_the_far_edge_along_the_corridor),
      TEST_REF(gaps_the_far_edge_is_refined_from_nearer_hits_on_its_face),
      TEST_REF(gaps_a_spike_is_no_wall_and_a_dropout_no_opening),
      TEST_REF(gaps_follow_stops_in_the_middle_of_the_nth_opening),
      TEST_REF(open_a_far_edge_seen_before_the_assumed_middle_puts_the_middle_between_the_edges));
