/*
 * The behaviours added for robustness under sensor noise and part-to-part
 * spread: openings seen by the rear ranger, far hits ignored for the wall
 * line, heading feedback with one ranger, the door-wall guard, and a flame
 * seen through the door left alone.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

TEST(openings_by_the_rear_ranger)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* a step that starts at the wall's end: the front ranger is already past
     * it, only the rear one sees the wall for 100 mm */
    ffr_openings_reset(&op);
    ir[FFR_IR_RR] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 34);
    CHECK(op.seen[FFR_SIDE_RIGHT] && !ffr_opening(&op, FFR_SIDE_RIGHT));
    /* the front ranger reading open is not enough: the wall is still beside */
    CHECK(!op.front_saw[FFR_SIDE_RIGHT]);
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    rig_travel(&op, &cfg, ir, &d, 5);
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT)); /* 15 mm < confirm */
    rig_travel(&op, &cfg, ir, &d, 3);
    CHECK(ffr_opening(&op, FFR_SIDE_RIGHT));
    /* the wall ended at the rear ranger's last hit point, behind the origin */
    CHECK_NEAR(op.open_at_mm[FFR_SIDE_RIGHT], 99.0f - 80.0f - 226.0f * 0.70710678f, 0.5);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
}

/* A fresh step past a wall's end: the rear ranger on the wall beside (70 +
 * 160 mm to the side) for 34 steps, then the front ranger's hit `lat_mm` to
 * the side (pending: the route's step ends at this side's opening) */
static void past_a_wall_end(ffr_openings_t *op, const ffr_config_t *cfg, float ir[FFR_IR_COUNT], float *d,
                            float lat_mm)
{
    ffr_openings_reset(op);
    *d = 0.0f;
    rig_no_walls(cfg, ir);
    ir[FFR_IR_RR] = 226.0f;
    rig_travel_pend(op, cfg, ir, d, 34, FFR_SIDE_RIGHT);
    ir[FFR_IR_RF] = (lat_mm - 70.0f) / 0.70710678f;
}

/* A step that starts at the wall's end (the corridor's north end, the west
 * hallway's opening 23 cm ahead): the rear ranger stays on the wall until the
 * robot is ~20 cm into the opening, and by then the front ranger sees the
 * opening's far side. That is no reason to drop the opening. */
TEST(an_opening_seen_past_its_wall_end_survives_its_far_side)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f, last;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    ffr_openings_reset(&op);
    ir[FFR_IR_RR] = 226.0f; /* the wall beside, 70 + 160 mm to the side */
    rig_travel_pend(&op, &cfg, ir, &d, 34, FFR_SIDE_RIGHT);
    CHECK(op.seen[FFR_SIDE_RIGHT] && !ffr_opening(&op, FFR_SIDE_RIGHT));
    /* the front ranger hits the opening's far side, 300 mm to the side */
    ir[FFR_IR_RF] = (300.0f - 70.0f) / 0.70710678f;
    rig_travel_pend(&op, &cfg, ir, &d, 20, FFR_SIDE_RIGHT);
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT)); /* the rear ranger still on the wall */
    last = d - 3.0f;
    /* the rear ranger leaves the wall: open, at its last hit */
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    rig_travel_pend(&op, &cfg, ir, &d, 8, FFR_SIDE_RIGHT);
    CHECK(ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK_NEAR(op.open_at_mm[FFR_SIDE_RIGHT], last - 80.0f - 226.0f * 0.70710678f, 0.5);
    /* the same, its hits going off the wall alongside (a far wall behind) */
    past_a_wall_end(&op, &cfg, ir, &d, 300.0f);
    rig_travel_pend(&op, &cfg, ir, &d, 5, FFR_SIDE_RIGHT);
    last = d - 3.0f;
    ir[FFR_IR_RR] = 226.0f + 100.0f;
    rig_travel_pend(&op, &cfg, ir, &d, 1, FFR_SIDE_RIGHT);
    CHECK(ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK_NEAR(op.open_at_mm[FFR_SIDE_RIGHT], last - 80.0f - 226.0f * 0.70710678f, 0.5);
    /* the front ranger's next hit in line with the rear's wall (within
     * 60 mm of its distance to the side): the wall goes on, no end */
    past_a_wall_end(&op, &cfg, ir, &d, 240.0f);
    rig_travel_pend(&op, &cfg, ir, &d, 20, FFR_SIDE_RIGHT);
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    rig_travel_pend(&op, &cfg, ir, &d, 8, FFR_SIDE_RIGHT);
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK(op.front_saw[FFR_SIDE_RIGHT] == 1u);
    /* not in a step ending at this side's opening (the explorer's legs):
     * the far side seen first is the plain rule's wall, no opening */
    ffr_openings_reset(&op);
    d = 0.0f;
    rig_no_walls(&cfg, ir);
    ir[FFR_IR_RR] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 34);
    ir[FFR_IR_RF] = (300.0f - 70.0f) / 0.70710678f;
    rig_travel(&op, &cfg, ir, &d, 20);
    ir[FFR_IR_RR] = FFR_IR_NONE(&cfg);
    rig_travel(&op, &cfg, ir, &d, 8);
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
}

TEST(far_hits_are_not_the_wall)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_ir_geom_t g;
    ffr_wall_t w;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* the rear ranger sees the wall beside (230 mm), the front one looks into
     * an opening and hits a wall across it, 420 mm to the side */
    ir[FFR_IR_RR] = (230.0f - 70.0f) / 0.70710678f;
    ir[FFR_IR_RF] = (420.0f - 70.0f) / 0.70710678f;
    w = ffr_wall_estimate(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_SIDE_RIGHT);
    CHECK(w.valid && !w.angle_valid);
    CHECK_NEAR(w.dist_mm, 230.0, 0.5);
}

TEST(one_ranger_keeps_heading_feedback)
{
    ffr_config_t cfg;
    ffr_state_t st;
    int i;
    ffr_config_default(&cfg);
    ffr_init(&st, &cfg);
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        st.ir_mm[i] = FFR_IR_NONE(&cfg);
    }
    /* only the right-rear ranger sees the wall, at the target distance; the
     * robot points 10 degrees left of the corridor: steer back right */
    st.ir_mm[FFR_IR_RR] = (cfg.wall_target_mm - 70.0f) / 0.70710678f;
    ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm); /* as ffr_step does with new readings */
    st.route.heading_ref_rad = 0.0f;
    st.odo.heading_rad = 10.0f * FFR_DEG;
    ffr_drive_corridor(&st, FFR_SIDE_RIGHT, 300.0f);
    CHECK(st.cmd_w_rad_s < -0.3f);
    /* on the corridor heading: straight on */
    st.odo.heading_rad = 0.0f;
    ffr_drive_corridor(&st, FFR_SIDE_RIGHT, 300.0f);
    CHECK_NEAR(st.cmd_w_rad_s, 0.0, 1e-3);
}

/* ROOM(1) then END; enter east across the doorway line, scan with the flame
 * strongest at `flame_deg`, approach. */
static void enter_and_scan(rig_t *r, ffr_config_t *cfg, float flame_deg, float peak)
{
    int i;
    ffr_config_default(cfg);
    rig_room_route(cfg, 1);
    rig_init(r, cfg);
    r->in.start = 1;
    rig_line(r, 21, 4);
    CHECK(rig_run_until_state(r, FFR_ST_SCAN, 400));
    for (i = 0; i < 600 && r->out.state == FFR_ST_SCAN; ++i) {
        float deg = r->st.odo.heading_rad / FFR_DEG - flame_deg;
        float s = deg > -20.0f && deg < 20.0f ? peak * (1.0f - deg * deg / 400.0f) : 20.0f;
        r->in.flame[0] = r->in.flame[1] = (uint16_t)(s > 20.0f ? s : 20.0f);
        rig_tick(r);
    }
    r->in.flame[0] = r->in.flame[1] = (uint16_t)peak;
    CHECK(rig_run_until_state(r, FFR_ST_APPROACH, 400));
}

/* Tick through the approach with a flame at bearing `flame_deg` (odometry
 * frame; far enough that only the heading matters): the two sensors share
 * `peak` by how far the flame is off the heading, as the real ones do.
 * Returns the flame's bearing off the heading at the end, degrees. */
static float approach_flame(rig_t *r, float flame_deg, float peak, int max_ticks)
{
    float off = 0.0f;
    int i;
    for (i = 0; i < max_ticks && r->out.state == FFR_ST_APPROACH; ++i) {
        float left;
        off = flame_deg - r->st.odo.heading_rad / FFR_DEG;
        left = peak * ffr_clampf(0.5f + off / 40.0f, 0.0f, 1.0f);
        r->in.flame[0] = (uint16_t)left;
        r->in.flame[1] = (uint16_t)(peak - left);
        rig_tick(r);
    }
    return off;
}

TEST(door_wall_guard_stops_by_the_jamb)
{
    ffr_config_t cfg;
    rig_t r;
    float x0, y0, off;
    /* the flame back toward the door wall, 120 degrees left of the entry
     * heading: the approach runs toward the wall the door is in */
    enter_and_scan(&r, &cfg, 120.0f, 900.0f);
    x0 = r.st.odo.x_mm;
    y0 = r.st.odo.y_mm;
    off = approach_flame(&r, r.st.odo.heading_rad / FFR_DEG, 900.0f, 600);
    /* stopped with no line and no ranger seeing anything: the guard, with the
     * flame near, so the fans go on */
    CHECK(r.out.state == FFR_ST_EXTINGUISH);
    {
        float moved = ffr_sqrtf((r.st.odo.x_mm - x0) * (r.st.odo.x_mm - x0) + (r.st.odo.y_mm - y0) * (r.st.odo.y_mm - y0));
        CHECK(moved > 20.0f && moved < 300.0f);
    }
    /* on the way the robot turned toward running along the wall, but no
     * farther than keeps the flame where the fans reach (30 degrees) */
    CHECK(ffr_absf(off) > 3.0f && ffr_absf(off) < 25.0f);
}

TEST(flame_beyond_the_door_is_left_alone)
{
    ffr_config_t cfg;
    rig_t r;
    /* a weak flame back toward the door wall: the guard stops the approach
     * at the wall with the flame still far, so it is not in this room */
    enter_and_scan(&r, &cfg, 125.0f, 300.0f);
    approach_flame(&r, r.st.odo.heading_rad / FFR_DEG, 300.0f, 600);
    CHECK(r.out.state == FFR_ST_TO_DOOR);
    CHECK(r.out.fan == 0 && (r.out.flags & FFR_FLAG_EXTINGUISHED) == 0);
    CHECK(r.st.room.flame_found == 0);

    /* approaching, the line sensor meets the doorway line it came in by (a
     * flame seen through the door): no fans, back out and search on */
    enter_and_scan(&r, &cfg, 120.0f, 900.0f);
    rig_tick(&r);
    r.st.odo.x_mm = r.st.room.line_x_mm - cfg.line_sensor_x_mm * ffr_cosf(r.st.odo.heading_rad);
    r.st.odo.y_mm = r.st.room.line_y_mm - cfg.line_sensor_x_mm * ffr_sinf(r.st.odo.heading_rad);
    rig_line(&r, 0, 3);
    CHECK(r.out.state == FFR_ST_TO_DOOR);
    CHECK(r.out.fan == 0 && r.st.room.flame_found == 0);
    /* the same line deep in the room is the candle circle: fans on */
    enter_and_scan(&r, &cfg, 60.0f, 900.0f);
    rig_line(&r, 20, 3);
    CHECK(r.out.state == FFR_ST_EXTINGUISH);
}

/* Flames differ in size: an approach stopped beside a wall by the flame's
 * strength alone (FLAME_REACH) steps closer when the fans do not put it out
 * (below), then, the steps made, goes on toward it; one stopped by the
 * candle circle's line does not. */
static int run_while(rig_t *r, uint8_t state, int max_ticks)
{
    int i;
    for (i = 0; i < max_ticks && r->out.state == state; ++i) {
        rig_tick(r);
    }
    return i;
}

TEST(a_flame_not_out_from_where_its_strength_said_is_approached_closer)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    uint16_t peaks[3] = {1200, 1500, 2000}; /* sums 2400..4000: all past FLAME_REACH x flame_detect */
    int k;
    for (k = 0; k < 3; ++k) {
        float s0;
        int s;
        enter_and_scan(&r, &cfg, 0.0f, (float)peaks[k]);
        /* a wall near the left front corner, not touching: the guard's "near" */
        r.in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(&cfg, 120.0f);
        (void)run_while(&r, FFR_ST_APPROACH, 50);
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
        /* the flame stays lit: the steps closer (5), each after a dwell */
        for (s = 0; s < 5; ++s) {
            (void)run_while(&r, FFR_ST_EXTINGUISH, (int)(cfg.fan_timeout_ms / 10u) + 10);
            CHECK(r.out.state == FFR_ST_APPROACH);
            (void)run_while(&r, FFR_ST_APPROACH, 400);
            CHECK(r.out.state == FFR_ST_EXTINGUISH);
        }
        /* then, after one attempt's fan time, on toward it */
        (void)run_while(&r, FFR_ST_EXTINGUISH, (int)(cfg.fan_timeout_ms / 10u) + 10);
        CHECK(r.out.state == FFR_ST_APPROACH);
        CHECK(r.out.fan == 0);
        s0 = r.st.odo.dist_mm;
        for (i = 0; i < 30; ++i) {
            rig_tick(&r);
        }
        CHECK(r.out.state == FFR_ST_APPROACH);
        CHECK(r.st.odo.dist_mm > s0 + 5.0f); /* it drives on */
        /* the candle circle stops it: fans again */
        rig_line(&r, 0, 3);
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
        /* stopped by the line: a second timeout keeps the fans at it */
        for (i = 0; i < (int)(cfg.fan_timeout_ms / 10u) + 10; ++i) {
            rig_tick(&r);
        }
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
    }
}

/* A big flame reads near by its strength from beyond the fans' reach: the
 * approach stopped beside a wall by that strength alone blows for a dwell
 * (5/8 of fan_timeout_ms), then, the flame still lit, steps 40 mm closer at
 * the creep's speed with the fans on (no break), and blows again; 5 steps at
 * most, none of them a fan attempt. Over the flame's strengths and dwells
 * ended with the flame lit, put out (its wick's glow falling), or going out
 * during a step. */
/* a flame of `peak` found and approached until its strength stopped the
 * robot, a wall 120 mm off its left front corner */
static void stopped_beside_a_wall(rig_t *r, ffr_config_t *cfg, float peak)
{
    enter_and_scan(r, cfg, 0.0f, peak);
    r->in.ir_mv[FFR_IR_LF] = rig_mv_for_mm(cfg, 120.0f);
    (void)run_while(r, FFR_ST_APPROACH, 50);
}

/* the flame reading falls by `rate` a tick (down to 20 counts) while the
 * firmware stays in `state`, at most `ticks` ticks */
static void fade(rig_t *r, float *glow, float rate, int ticks, uint8_t state)
{
    int i;
    for (i = 0; i < ticks && r->out.state == state; ++i) {
        *glow *= rate;
        r->in.flame[0] = r->in.flame[1] = (uint16_t)(*glow > 20.0f ? *glow : 20.0f);
        rig_tick(r);
    }
}

TEST(a_flame_not_out_after_the_dwell_is_stepped_toward)
{
    static const uint16_t peaks[] = {1200, 1600, 2000, 2400};
    unsigned k;
    for (k = 0; k < 4; ++k) {
        ffr_config_t cfg;
        rig_t r;
        int s, n;
        float d0, v_max = 0.0f;
        int fan_off = 0;
        uint32_t t0;
        stopped_beside_a_wall(&r, &cfg, (float)peaks[k]);
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
        for (s = 0; s < 5; ++s) {
            t0 = r.st.t_ms;
            (void)run_while(&r, FFR_ST_EXTINGUISH, (int)(cfg.fan_timeout_ms / 10u) + 10);
            /* the dwell, not the whole fan time */
            CHECK(r.out.state == FFR_ST_APPROACH && r.out.fan == 1);
            CHECK(r.st.t_ms - t0 >= 5000u - 20u && r.st.t_ms - t0 <= 5000u + 20u);
            CHECK(r.st.room.attempts == 0u);
            d0 = r.st.odo.dist_mm;
            for (n = 0; n < 400 && r.out.state == FFR_ST_APPROACH; ++n) {
                rig_tick(&r);
                v_max = r.st.cmd_v_mm_s > v_max ? r.st.cmd_v_mm_s : v_max;
                fan_off |= r.out.fan == 0;
            }
            CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
            CHECK(r.st.odo.dist_mm - d0 >= 40.0f && r.st.odo.dist_mm - d0 < 40.0f + 10.0f);
            CHECK(v_max > 0.0f && v_max <= 60.0f + 0.5f);
            CHECK(!fan_off);
        }
        /* the steps made: the whole fan time, then a fan attempt counted */
        t0 = r.st.t_ms;
        (void)run_while(&r, FFR_ST_EXTINGUISH, (int)(cfg.fan_timeout_ms / 10u) + 10);
        CHECK(r.out.state == FFR_ST_APPROACH && r.st.t_ms - t0 >= cfg.fan_timeout_ms);
        CHECK(r.st.room.attempts == 1u);
    }
    for (k = 0; k < 4; ++k) {
        /* put out by the first dwell: the glow falls (tau 0.5 s) from 3 s on,
         * no step; the fans' phase confirms it out and verifies */
        ffr_config_t cfg;
        rig_t r;
        float glow = (float)peaks[k];
        stopped_beside_a_wall(&r, &cfg, (float)peaks[k]);
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
        (void)run_while(&r, FFR_ST_EXTINGUISH, 300);
        fade(&r, &glow, 0.98f, 600, FFR_ST_EXTINGUISH); /* 10 ms of a 0.5 s time constant */
        CHECK(r.out.state == FFR_ST_VERIFY);
    }
    for (k = 0; k < 4; ++k) {
        /* put out during the first step: it stops and the fans' phase
         * confirms it out (no backing out as from a far flame) */
        ffr_config_t cfg;
        rig_t r;
        float glow = (float)peaks[k];
        stopped_beside_a_wall(&r, &cfg, (float)peaks[k]);
        (void)run_while(&r, FFR_ST_EXTINGUISH, (int)(cfg.fan_timeout_ms / 10u) + 10);
        CHECK(r.out.state == FFR_ST_APPROACH);
        fade(&r, &glow, 0.95f, 400, FFR_ST_APPROACH); /* below FLAME_NEAR at the step's end: not a far flame */
        CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
        fade(&r, &glow, 0.98f, 300, FFR_ST_EXTINGUISH);
        CHECK(r.out.state == FFR_ST_VERIFY);
    }
}

/* Leaving a room on odometry's heading, a front corner near a wall beside
 * it steers away; nothing near, no steering. Over the guard's whole band. */
TEST(leaving_a_room_steers_a_front_corner_off_a_wall)
{
    static ffr_state_t st;
    int i, side;
    ffr_config_default(&st.cfg);
    ffr_ir_geom_init(&st.ir_geom, &st.cfg);
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        st.ir_mm[i] = FFR_IR_NONE(&st.cfg);
    }
    ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm);
    CHECK(ffr_leave_guard(&st) == 0.0f);
    for (side = 0; side < 2; ++side) {
        int k = side == 0 ? FFR_IR_LF : FFR_IR_RF;
        float prev = 0.0f;
        /* a wall parallel to the heading, from 40 mm off the body's side in
         * to touching: the corner ranger reads it along its 45 degree beam */
        for (i = 0; i <= 40; ++i) {
            float gap = 80.0f - 2.0f * (float)i; /* wall to the body's side, mm */
            float lat = st.cfg.body_half_width_mm + gap - 70.0f; /* from the ranger */
            float w;
            st.ir_mm[FFR_IR_LF] = st.ir_mm[FFR_IR_RF] = FFR_IR_NONE(&st.cfg);
            st.ir_mm[k] = lat / 0.70710678f;
            ffr_ir_geom_update(&st.ir_geom, &st.cfg, st.ir_mm);
            w = ffr_leave_guard(&st);
            if (!ffr_ir_valid(&st.cfg, st.ir_mm[k]) || st.ir_mm[k] < st.cfg.ir_min_mm) {
                continue;
            }
            if (gap >= st.cfg.guard_side_mm || st.ir_geom.hit_x_mm[k] - st.cfg.body_front_mm >= st.cfg.guard_side_mm) {
                CHECK(w == 0.0f);
            } else if (side == 0) {
                CHECK(w < 0.0f && w <= prev); /* wall on the left: right, harder nearer */
            } else {
                CHECK(w > 0.0f && w >= prev);
            }
            prev = w;
        }
    }
}

/* The white walls mirror the flame: a weak peak seen facing a near wall
 * does not end the scan early; the flame farther round is found and approached.
 * A weak peak with no wall ahead still ends it early (as before). */
TEST(a_flame_reflection_in_a_near_wall_does_not_end_the_scan)
{
    ffr_config_t cfg;
    rig_t r;
    int wall, i;
    for (wall = 0; wall < 2; ++wall) {
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 1);
        rig_init(&r, &cfg);
        r.in.start = 1;
        rig_line(&r, 21, 4);
        CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 400));
        for (i = 0; i < 900 && r.out.state == FFR_ST_SCAN; ++i) {
            float h = r.st.odo.heading_rad / FFR_DEG;
            float dw = h - 60.0f, df = h - 130.0f;
            float s = 40.0f;
            if (dw > -20.0f && dw < 20.0f) {
                s = 40.0f + 75.0f * (1.0f - dw * dw / 400.0f); /* sum up to 1.3 x flame_detect */
            }
            if (df > -20.0f && df < 20.0f) {
                s = 40.0f + 860.0f * (1.0f - df * df / 400.0f);
            }
            r.in.flame[0] = r.in.flame[1] = (uint16_t)s;
            r.in.ir_mv[FFR_IR_CF] = (wall && dw > -30.0f && dw < 30.0f)
                                        ? rig_mv_for_mm(&cfg, 250.0f - cfg.ir_x_mm[FFR_IR_CF])
                                        : 0u;
            rig_tick(&r);
        }
        r.in.ir_mv[FFR_IR_CF] = 0u;
        CHECK(rig_run_until_state(&r, FFR_ST_APPROACH, 400));
        if (wall) {
            CHECK_NEAR(r.st.room.best_heading_rad / FFR_DEG, 130.0, 6.0);
        } else {
            CHECK_NEAR(r.st.room.best_heading_rad / FFR_DEG, 60.0, 6.0);
        }
    }
}

TEST(flame_dark_level_is_learned)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);
    /* ambient light: each sensor 30 counts above its 40-count dark level, noisy */
    for (i = 0; i < 400; ++i) {
        r.in.flame[0] = (uint16_t)(70 + (i % 7) - 3);
        r.in.flame[1] = (uint16_t)(70 + (i % 5) - 2);
        rig_tick(&r);
    }
    CHECK(r.st.flame_dark > 132.0f && r.st.flame_dark <= 140.0f); /* low by at most the noise */
    /* a flame coming into view does not raise it */
    for (i = 0; i < 200; ++i) {
        r.in.flame[0] = r.in.flame[1] = 900;
        rig_tick(&r);
    }
    CHECK(r.st.flame_dark > 132.0f && r.st.flame_dark <= 140.0f); /* low by at most the noise */
}

/* Tick while the firmware is in `state`, the flame at `flame_deg` as in
 * approach_flame; returns the ticks run. */
static int hold_flame(rig_t *r, uint8_t state, float flame_deg, float peak, int max_ticks)
{
    int i;
    for (i = 0; i < max_ticks && r->out.state == state; ++i) {
        float off = flame_deg - r->st.odo.heading_rad / FFR_DEG;
        float left = peak * ffr_clampf(0.5f + off / 40.0f, 0.0f, 1.0f);
        r->in.flame[0] = (uint16_t)left;
        r->in.flame[1] = (uint16_t)(peak - left);
        rig_tick(r);
    }
    return i;
}

/* An approach stopped by the wall guard alone (the door's wall) whose fans
 * do not put the flame out creeps on, slowly and at most 80 mm (CREEP_MM),
 * then the fans again; the tries stay bounded by fan_attempts. Over the
 * flame's bearings toward the door wall and its strengths. */
TEST(a_flame_not_out_beside_the_wall_guard_is_crept_toward)
{
    static const float bearings[] = {110.0f, 120.0f, 130.0f};
    static const float peaks[] = {700.0f, 900.0f, 1100.0f}; /* x 2 below FLAME_REACH */
    unsigned b, p;
    for (b = 0; b < 3; ++b) {
        for (p = 0; p < 3; ++p) {
            ffr_config_t cfg;
            rig_t r;
            float d0, v_max = 0.0f;
            int i, tries = 1;
            enter_and_scan(&r, &cfg, bearings[b], peaks[p]);
            approach_flame(&r, r.st.odo.heading_rad / FFR_DEG, peaks[p], 600);
            CHECK(r.out.state == FFR_ST_EXTINGUISH); /* stopped by the door wall's guard */
            /* the flame stays lit for one attempt's fan time: on toward it */
            hold_flame(&r, FFR_ST_EXTINGUISH, bearings[b], peaks[p], (int)(cfg.fan_timeout_ms / 10u) + 10);
            CHECK(r.out.state == FFR_ST_APPROACH && r.out.fan == 0);
            d0 = r.st.odo.dist_mm;
            for (i = 0; i < 400 && r.out.state == FFR_ST_APPROACH; ++i) {
                hold_flame(&r, FFR_ST_APPROACH, bearings[b], peaks[p], 1);
                if (r.st.cmd_v_mm_s > v_max) {
                    v_max = r.st.cmd_v_mm_s;
                }
            }
            /* a creep: it drove on, slowly, no farther than its bound */
            hold_flame(&r, FFR_ST_EXTINGUISH, bearings[b], peaks[p], 1);
            CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
            CHECK(r.st.odo.dist_mm - d0 > 40.0f && r.st.odo.dist_mm - d0 < 80.0f + 15.0f);
            CHECK(v_max > 0.0f && v_max <= 60.0f + 0.5f && v_max < cfg.approach_speed_mm_s);
            /* never lit out: bounded tries, then "not out" */
            while (r.out.state != FFR_ST_FAILED && tries < 10) {
                int n = hold_flame(&r, r.out.state, bearings[b], peaks[p], (int)(cfg.fan_timeout_ms / 10u) + 400);
                CHECK(n > 0);
                if (r.out.state == FFR_ST_EXTINGUISH || r.out.state == FFR_ST_FAILED) {
                    tries++;
                }
            }
            CHECK(r.out.state == FFR_ST_FAILED && r.out.fail_code == FFR_FAIL_NOT_OUT);
            CHECK(r.out.fan == 0);
        }
    }
}

/* A creep that brings the nose to the doorway it came in by stops there and
 * the fans go on: the flame was seen near and tried, it is in this room (an
 * approach, not a creep, reaching the doorway backs out). Over flames far
 * back toward the door wall. */
TEST(a_creep_to_the_doorway_keeps_the_fans_on)
{
    static const float bearings[] = {130.0f, 135.0f, 140.0f};
    unsigned b;
    for (b = 0; b < 3; ++b) {
        ffr_config_t cfg;
        rig_t r;
        int i, at_door = 0, backed_out = 0;
        enter_and_scan(&r, &cfg, bearings[b], 1000.0f);
        approach_flame(&r, r.st.odo.heading_rad / FFR_DEG, 1000.0f, 600);
        CHECK(r.out.state == FFR_ST_EXTINGUISH);
        for (i = 0; i < 4000 && r.out.state != FFR_ST_FAILED; ++i) {
            ffr_door_frame_t df;
            uint8_t was = r.out.state;
            hold_flame(&r, r.out.state, bearings[b], 1000.0f, 1);
            df = ffr_door_frame(&r.st);
            if (was == FFR_ST_APPROACH && ffr_nose_in_doorway(&r.st, &df)) {
                at_door = 1; /* the creep got there */
            }
            if (r.out.state == FFR_ST_TO_DOOR) {
                backed_out = 1;
            }
        }
        CHECK(at_door);
        CHECK(!backed_out);
        CHECK(r.out.state == FFR_ST_FAILED && r.out.fail_code == FFR_FAIL_NOT_OUT);
    }
}

SUITE(robustness,
      TEST_REF(leaving_a_room_steers_a_front_corner_off_a_wall),
      TEST_REF(a_flame_reflection_in_a_near_wall_does_not_end_the_scan),
      TEST_REF(a_flame_not_out_from_where_its_strength_said_is_approached_closer),
      TEST_REF(a_flame_not_out_after_the_dwell_is_stepped_toward),
      TEST_REF(flame_dark_level_is_learned),
      TEST_REF(openings_by_the_rear_ranger),
      TEST_REF(an_opening_seen_past_its_wall_end_survives_its_far_side),
      TEST_REF(far_hits_are_not_the_wall),
      TEST_REF(one_ranger_keeps_heading_feedback),
      TEST_REF(door_wall_guard_stops_by_the_jamb),
      TEST_REF(flame_beyond_the_door_is_left_alone),
      TEST_REF(a_flame_not_out_beside_the_wall_guard_is_crept_toward),
      TEST_REF(a_creep_to_the_doorway_keeps_the_fans_on));
