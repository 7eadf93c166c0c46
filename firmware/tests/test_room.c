/*
 * The room task's failures, through the whole firmware with plain inputs
 * (the rig): the doorway line never met (in or out), a flame the fans do not
 * put out, and a flame that, approached, vanishes without being put out.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

/* dark flame sensors (the rig's default) */
#define DARK 20u
/* a flame straight ahead at the approach's start: near (>= 4 x flame_detect
 * in sum over the dark level, flame_detect 170 by default) */
#define NEAR_EACH 900u

/* A one-room route, started, through the doorway line and into the scan. */
static int into_the_scan(rig_t *r, const ffr_config_t *cfg)
{
    rig_init(r, cfg);
    r->in.start = 1;
    rig_tick(r);
    rig_line(r, 20, 4);
    return rig_run_until_state(r, FFR_ST_SCAN, 400);
}

/* The scan meets a flame at 80 degrees (peak_each counts on each sensor),
 * turns back to it and starts the approach with it ahead. */
static int into_the_approach(rig_t *r, const ffr_config_t *cfg, uint16_t peak_each)
{
    int i;
    if (!into_the_scan(r, cfg)) {
        return 0;
    }
    for (i = 0; i < 600 && r->out.state == FFR_ST_SCAN; ++i) {
        float deg = r->st.odo.heading_rad / FFR_DEG;
        float s = (float)DARK;
        if (deg > 60.0f && deg < 100.0f) {
            s = (float)peak_each - ((float)peak_each - (float)DARK) * (deg - 80.0f) * (deg - 80.0f) / 400.0f;
        }
        r->in.flame[0] = r->in.flame[1] = (uint16_t)(s < (float)DARK ? (float)DARK : s);
        rig_tick(r);
    }
    r->in.flame[0] = r->in.flame[1] = peak_each;
    return rig_run_until_state(r, FFR_ST_APPROACH, 400);
}

/* ... and the approach stopped at the candle circle: fans on. */
static int into_the_fans(rig_t *r, const ffr_config_t *cfg)
{
    int i;
    if (!into_the_approach(r, cfg, NEAR_EACH)) {
        return 0;
    }
    for (i = 0; i < 20; ++i) {
        rig_tick(r);
    }
    rig_line(r, 0, 3);
    rig_tick(r);
    return r->out.state == FFR_ST_EXTINGUISH && r->out.fan == 1;
}

/* ROOM 1, ROOM 2, END: room 1 is not the route's last room */
static void two_room_route(ffr_config_t *cfg)
{
    rig_room_route(cfg, 0);
    cfg->route[1].op = FFR_OP_ROOM;
    cfg->route[1].arg = 2;
    cfg->route[2].op = FFR_OP_END;
    cfg->route_len = 3;
}

/* tick with dark flame sensors until the state is no longer `state` */
static int run_while(rig_t *r, uint8_t state, int max_ticks)
{
    int i;
    for (i = 0; i < max_ticks && r->out.state == state; ++i) {
        rig_tick(r);
    }
    return r->out.state != state;
}

/* A one-room route (its room the last): the first scan finds no flame, the
 * robot drives DEEPER and its second scan begins */
static int into_the_second_scan(rig_t *r, const ffr_config_t *cfg)
{
    return into_the_scan(r, cfg) && run_while(r, FFR_ST_SCAN, 2000) && rig_run_until_state(r, FFR_ST_SCAN, 1000);
}

TEST(no_doorway_line_on_the_way_in_fails_no_line)
{
    /* over the class of limits: each fails once it has driven that far */
    static const float limits[] = {150.0f, 450.0f, 900.0f};
    unsigned k;
    for (k = 0; k < sizeof(limits) / sizeof(limits[0]); ++k) {
        ffr_config_t cfg;
        rig_t r;
        float at;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        cfg.room_line_max_mm = limits[k];
        rig_init(&r, &cfg);
        r.in.start = 1;
        CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 3000));
        CHECK(r.out.fail_code == FFR_FAIL_NO_LINE);
        CHECK((r.out.flags & FFR_FLAG_IN_ROOM) == 0);
        at = r.st.odo.dist_mm;
        CHECK(at > limits[k] && at < limits[k] + 20.0f);
        CHECK(r.out.pwm[0] == 0 && r.out.pwm[1] == 0);
    }
}

TEST(no_doorway_line_on_the_way_out_fails_no_line)
{
    ffr_config_t cfg;
    rig_t r;
    float out_from;
    ffr_config_default(&cfg);
    two_room_route(&cfg); /* not the last room: no second scan */
    CHECK(into_the_scan(&r, &cfg));
    /* a full turn, no flame: it turns to the door and drives out ... */
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 2000));
    CHECK(rig_run_until_driving(&r, 400));
    out_from = r.st.room.phase_start_mm;
    /* ... and never meets the line: it fails beyond the way in and the slack */
    CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 3000));
    CHECK(r.out.fail_code == FFR_FAIL_NO_LINE);
    CHECK(r.st.odo.dist_mm - out_from > cfg.room_line_max_mm + cfg.room_entry_mm);
    CHECK((r.out.flags & FFR_FLAG_IN_ROOM) != 0);
    CHECK(r.out.rooms_searched == 0);
}

TEST(a_flame_the_fans_never_put_out_fails_not_out)
{
    /* each number of attempts: the fans run that many times their timeout */
    uint8_t attempts;
    for (attempts = 1; attempts <= 3; ++attempts) {
        ffr_config_t cfg;
        rig_t r;
        uint32_t fans_from, ticks;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        cfg.fan_attempts = attempts;
        cfg.fan_timeout_ms = 1000u;
        CHECK(into_the_fans(&r, &cfg));
        fans_from = r.st.t_ms;
        CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 2000));
        CHECK(r.out.fail_code == FFR_FAIL_NOT_OUT);
        CHECK(r.out.fan == 0);
        CHECK((r.out.flags & FFR_FLAG_EXTINGUISHED) == 0);
        ticks = r.st.t_ms - fans_from;
        CHECK(ticks >= (uint32_t)attempts * cfg.fan_timeout_ms - 20u
              && ticks <= (uint32_t)attempts * cfg.fan_timeout_ms + 40u);
    }
}

TEST(a_flame_that_keeps_coming_back_fails_not_out)
{
    /* out, then burning again while it is watched: the fans again, and after
     * fan_attempts of that, failed */
    ffr_config_t cfg;
    rig_t r;
    int round, seen_verify = 0;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_fans(&r, &cfg));
    for (round = 0; round < 10 && r.out.state != FFR_ST_FAILED; ++round) {
        r.in.flame[0] = r.in.flame[1] = DARK;
        if (rig_run_until_state(&r, FFR_ST_VERIFY, 200)) {
            seen_verify++;
        }
        r.in.flame[0] = r.in.flame[1] = NEAR_EACH;
        rig_run_until_state(&r, FFR_ST_EXTINGUISH, 5);
        rig_run_until_state(&r, FFR_ST_FAILED, 1);
    }
    CHECK(seen_verify == (int)cfg.fan_attempts);
    CHECK(r.out.state == FFR_ST_FAILED);
    CHECK(r.out.fail_code == FFR_FAIL_NOT_OUT);
    CHECK((r.out.flags & FFR_FLAG_EXTINGUISHED) == 0);
}

TEST(an_approached_flame_lost_and_not_found_again_fails_lost_flame)
{
    /* at the default scan rate and faster ones (a turn in 2.4 s to 0.4 s):
     * never sooner than FFR_FLAME_LOST_MS after the loss, and soon after */
    static const float rates[] = {150.0f, 400.0f, 900.0f};
    unsigned k;
    for (k = 0; k < sizeof(rates) / sizeof(rates[0]); ++k) {
        ffr_config_t cfg;
        rig_t r;
        uint32_t lost_at;
        float turn_ms;
        int i;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        cfg.scan_rate_deg_s = rates[k];
        CHECK(into_the_approach(&r, &cfg, NEAR_EACH));
        for (i = 0; i < 10; ++i) {
            rig_tick(&r);
        }
        CHECK(r.out.state == FFR_ST_APPROACH);
        /* gone, not put out */
        r.in.flame[0] = r.in.flame[1] = DARK;
        rig_tick(&r);
        CHECK(r.out.state == FFR_ST_SCAN);
        lost_at = r.st.t_ms;
        CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 2000));
        CHECK(r.out.fail_code == FFR_FAIL_LOST_FLAME);
        CHECK((r.out.flags & FFR_FLAG_EXTINGUISHED) == 0);
        CHECK(r.out.fan == 0 && r.out.pwm[0] == 0 && r.out.pwm[1] == 0);
        /* the stated time at least, and a full turn of the re-scan at least
         * (by odometry); not much longer than the longer of the two */
        turn_ms = 360.0f / rates[k] * 1000.0f;
        CHECK(r.st.t_ms - lost_at >= FFR_FLAME_LOST_MS);
        CHECK(ffr_absf(r.st.odo.heading_rad - r.st.room.start_heading_rad) >= 2.0f * FFR_PI);
        CHECK((float)(r.st.t_ms - lost_at)
              <= (turn_ms > (float)FFR_FLAME_LOST_MS ? 1.2f * turn_ms : (float)FFR_FLAME_LOST_MS) + 300.0f);
    }
}

TEST(a_flame_lost_and_found_again_is_approached_again)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_approach(&r, &cfg, NEAR_EACH));
    r.in.flame[0] = r.in.flame[1] = DARK;
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_SCAN);
    CHECK(r.st.room.lost_since_ms != 0u);
    /* it burns again within the re-scan's turn: seen, faced, approached */
    for (i = 0; i < 30; ++i) {
        rig_tick(&r);
    }
    r.in.flame[0] = r.in.flame[1] = NEAR_EACH;
    rig_tick(&r);
    r.in.flame[0] = r.in.flame[1] = DARK + 40u;
    CHECK(rig_run_until_state(&r, FFR_ST_APPROACH, 600));
    CHECK(r.st.room.lost_since_ms == 0u);
    CHECK((r.out.flags & FFR_FLAG_FAILED) == 0);
}

TEST(a_far_flame_lost_is_searched_for_elsewhere)
{
    /* a flame only ever seen weak (never near) and lost: no "flame lost"; a
     * full re-scan without it leaves the room, as for a room without one */
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    two_room_route(&cfg);
    CHECK(into_the_approach(&r, &cfg, 300u));
    for (i = 0; i < 5; ++i) {
        rig_tick(&r);
    }
    CHECK(r.out.state == FFR_ST_APPROACH);
    CHECK(r.st.room.flame_near == 0);
    r.in.flame[0] = r.in.flame[1] = DARK;
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_SCAN);
    CHECK(r.st.room.lost_since_ms == 0u);
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 2000));
    CHECK((r.out.flags & FFR_FLAG_FAILED) == 0);
}

TEST(leaving_hands_the_heading_out_to_the_route)
{
    /* room.c returns the heading out; route.c takes it as its reference,
     * and counts the room once the robot is out */
    ffr_config_t cfg;
    rig_t r;
    float in_heading;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_scan(&r, &cfg));
    in_heading = r.st.room.entry_heading_rad;
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 2000));
    CHECK(rig_run_until_driving(&r, 400));
    CHECK(r.st.route.heading_ref_rad == r.st.room.exit_heading_rad);
    CHECK_NEAR(ffr_wrap_pi(r.st.route.heading_ref_rad - in_heading - FFR_PI), 0.0, 1e-4);
    CHECK(r.out.rooms_searched == 0);
    rig_line(&r, 0, 3);
    CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 400)); /* the one-room route ends: no flame */
    CHECK(r.out.fail_code == FFR_FAIL_NO_FLAME);
    CHECK(r.out.rooms_searched == 1);
}

/* ---- a candle beside the door (issue 13, doorcandle; room_entry.c) ---- */

/* the approach with the flame near and the front ranger reading `mm` ahead */
static void front_reads(rig_t *r, const ffr_config_t *cfg, float mm)
{
    r->in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(cfg, mm);
}

TEST(a_candle_base_at_reach_ahead_stops_the_approach)
{
    /* inside the candle circle no line edge comes: the front ranger at the
     * bottom of its span (nearer than ir_min_mm), with the flame near, stops
     * the robot and the fans go on; with the flame far it drives on */
    static const float below[] = {40.0f, 70.0f, 95.0f, 100.0f};
    unsigned k;
    for (k = 0; k < sizeof(below) / sizeof(below[0]); ++k) {
        int near;
        for (near = 0; near <= 1; ++near) {
            ffr_config_t cfg;
            rig_t r;
            ffr_config_default(&cfg);
            rig_room_route(&cfg, 0);
            CHECK(into_the_approach(&r, &cfg, near ? NEAR_EACH : 300u));
            front_reads(&r, &cfg, below[k]);
            rig_tick(&r);
            rig_tick(&r);
            if (near) {
                CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
                CHECK(r.st.cmd_v_mm_s == 0.0f && r.st.cmd_w_rad_s == 0.0f); /* stopped */
            } else {
                CHECK(r.out.state == FFR_ST_APPROACH && r.out.fan == 0);
            }
        }
    }
}

TEST(a_front_ranger_folding_back_stops_the_approach)
{
    /* the reading near (up to 200 mm), then growing again by 30 mm or more
     * while the robot drives on toward it: folded back below ~8 cm, the base
     * at reach. A growth far off, or too small, drives on. */
    static const float from[] = {120.0f, 150.0f, 190.0f, 400.0f, 150.0f};
    static const float grow[] = {40.0f, 60.0f, 35.0f, 80.0f, 20.0f};
    static const int stops[] = {1, 1, 1, 0, 0};
    unsigned k;
    for (k = 0; k < sizeof(from) / sizeof(from[0]); ++k) {
        ffr_config_t cfg;
        rig_t r;
        int i;
        float at;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        CHECK(into_the_approach(&r, &cfg, NEAR_EACH));
        front_reads(&r, &cfg, from[k]);
        for (i = 0; i < 5; ++i) {
            rig_tick(&r);
        }
        CHECK(r.out.state == FFR_ST_APPROACH);
        front_reads(&r, &cfg, from[k] + grow[k]);
        at = r.st.odo.dist_mm;
        for (i = 0; i < 100 && r.out.state == FFR_ST_APPROACH; ++i) {
            rig_tick(&r);
        }
        if (stops[k]) {
            CHECK(r.out.state == FFR_ST_EXTINGUISH);
            CHECK(r.st.odo.dist_mm - at < 40.0f); /* within a few cm */
        } else {
            CHECK(r.out.state == FFR_ST_APPROACH);
        }
    }
}

TEST(a_scan_begun_just_past_a_near_flame_turns_on_to_it)
{
    /* the scan turns left; at its start a flame reads on the right sensor
     * only and fades as the turn goes on. After an entry that passed the
     * flame near (its peak 10 x flame_detect) that is no peak passed, the
     * scan turns on: strong at the start (4.5 x) or at the edge of the
     * sensors' view (2 x). After a peak of 5 x, only if the start has
     * fallen below 0.6 of it (2 x; at 4.5 x the flame is still ahead). No
     * such entry (none, or a peak of 3 x): the early stop as before. */
    static const uint16_t right[] = {700u, 700u, 275u, 700u, 275u, 275u};
    static const float entry_x[] = {10.0f, 0.0f, 10.0f, 5.0f, 5.0f, 3.0f};
    static const int turns_on[] = {1, 0, 1, 0, 1, 0};
    unsigned k;
    for (k = 0; k < sizeof(right) / sizeof(right[0]); ++k) {
        ffr_config_t cfg;
        rig_t r;
        int i;
        float start;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        CHECK(into_the_scan(&r, &cfg));
        r.st.room.entry_peak = entry_x[k] * cfg.flame_detect;
        start = r.st.odo.heading_rad;
        for (i = 0; i < 400 && r.out.state == FFR_ST_SCAN; ++i) {
            float turned = (r.st.odo.heading_rad - start) / FFR_DEG;
            float f = (float)right[k] - ((float)right[k] - (float)DARK) * turned / 30.0f;
            r.in.flame[0] = DARK;
            r.in.flame[1] = (uint16_t)(f < (float)DARK ? (float)DARK : f);
            rig_tick(&r);
            if (turned > 90.0f) {
                break;
            }
        }
        if (turns_on[k]) {
            CHECK(r.out.state == FFR_ST_SCAN);
            CHECK((r.st.odo.heading_rad - start) / FFR_DEG > 90.0f);
        } else {
            CHECK(r.out.state != FFR_ST_SCAN || (r.st.odo.heading_rad - start) / FFR_DEG < 90.0f);
            CHECK(r.st.room.flame_found != 0);
        }
    }
}

TEST(the_side_of_a_flame_and_a_flame_passed_by)
{
    ffr_config_t cfg;
    float peak = 0.0f, d = 170.0f;
    int i;
    ffr_config_default(&cfg);
    /* trailing: on the side the scan turns away from, near enough */
    CHECK(ffr_scan_starts_trailing(&cfg, 1.0f, 50.0f, 600.0f, 650.0f) == 1);
    CHECK(ffr_scan_starts_trailing(&cfg, -1.0f, 50.0f, 600.0f, 650.0f) == 0);
    CHECK(ffr_scan_starts_trailing(&cfg, -1.0f, 600.0f, 50.0f, 650.0f) == 1);
    CHECK(ffr_scan_starts_trailing(&cfg, 1.0f, 330.0f, 320.0f, 650.0f) == 0); /* ahead */
    CHECK(ffr_scan_starts_trailing(&cfg, 1.0f, 20.0f, 180.0f, 200.0f) == 1);  /* 1.2 x */
    CHECK(ffr_scan_starts_trailing(&cfg, 1.0f, 20.0f, 140.0f, 160.0f) == 0);  /* below 1 x */
    /* passed by: within reach (8 x), then below 0.6 of the peak; not before
     * (a flicker of 30 % is no passing) */
    for (i = 0; i < 20; ++i) {
        CHECK(ffr_entry_passing_flame(&cfg, &peak, d * (1.0f + 0.5f * (float)i), cfg.room_entry_mm) == 0);
    }
    CHECK(peak > 8.0f * d);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 0.7f * peak, cfg.room_entry_mm) == 0);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 0.55f * peak, cfg.room_entry_mm) == 1);
    peak = 0.0f;
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 7.5f * d, cfg.room_entry_mm) == 0);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 0.5f * d, cfg.room_entry_mm) == 0); /* a flame passed farther off: on */
}

TEST(a_flame_passed_before_the_body_clears_the_door_does_not_end_the_entry)
{
    /* the scan's turn in place needs the axle 100 mm past the doorway line
     * (the line sensor met it 110 mm ahead of the axle): a near flame
     * passed sooner leaves the entry driving on, and the same fall once the
     * axle is that far in ends it */
    ffr_config_t cfg;
    float peak = 0.0f, d, in;
    ffr_config_default(&cfg);
    d = cfg.flame_detect;
    in = cfg.line_sensor_x_mm + 100.0f; /* the axle 100 mm past the line */
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 10.0f * d, 100.0f) == 0);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 4.0f * d, 170.0f) == 0);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 4.0f * d, in - 1.0f) == 0);
    CHECK(ffr_entry_passing_flame(&cfg, &peak, 4.0f * d, in) == 1);
    CHECK(peak == 10.0f * d); /* the peak kept while the body was in the door */
}

TEST(the_line_sensor_past_the_doorway_line_on_the_way_out)
{
    /* the doorway line met at (500, 0) going +x; facing out (-x) from
     * origins along the way: the sensor (110 mm ahead) is past the line by
     * 500 - x + 110 */
    ffr_config_t cfg;
    ffr_state_t st;
    int k;
    ffr_config_default(&cfg);
    ffr_init(&st, &cfg);
    st.room.line_x_mm = 500.0f;
    st.room.line_y_mm = 0.0f;
    st.room.exit_heading_rad = FFR_PI;
    for (k = 0; k < 10; ++k) {
        float x = 450.0f + 40.0f * (float)k;
        st.odo.x_mm = x;
        st.odo.y_mm = 30.0f;
        st.odo.heading_rad = FFR_PI;
        CHECK_NEAR(ffr_leave_past_line_mm(&st), 500.0f - x + cfg.line_sensor_x_mm, 0.05);
    }
}


TEST(the_approach_slows_for_its_own_front_stop)
{
    /* something ahead (a candle's base, a wall): the approach goes at its
     * speed while braking at the stopping law would still stop it by
     * approach_stop_mm (the reading's age counted), slower nearer; with the
     * front at the route's old ramp (front_slow_mm to front_stop_mm) it no
     * longer crawls */
    static const float front[] = {700.0f, 450.0f, 350.0f, 300.0f, 260.0f, 230.0f, 210.0f};
    unsigned k;
    float prev = 1.0e9f;
    for (k = 0; k < sizeof(front) / sizeof(front[0]); ++k) {
        ffr_config_t cfg;
        rig_t r;
        int i;
        float want;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        CHECK(into_the_approach(&r, &cfg, NEAR_EACH));
        front_reads(&r, &cfg, front[k] - cfg.ir_x_mm[FFR_IR_CF]);
        for (i = 0; i < 3; ++i) {
            rig_tick(&r);
        }
        CHECK(r.out.state == FFR_ST_APPROACH);
        want = ffr_stopping_speed(ffr_front_now(&cfg, &r.st.odo, r.st.ir_mm) - cfg.approach_stop_mm,
                                  cfg.approach_speed_mm_s);
        CHECK_NEAR(r.st.cmd_v_mm_s, want, 1e-3);
        CHECK(r.st.cmd_v_mm_s <= cfg.approach_speed_mm_s && r.st.cmd_v_mm_s <= prev + 1e-3f);
        if (front[k] >= cfg.approach_stop_mm + 0.5f * cfg.approach_speed_mm_s
                             + 0.001f * FFR_IR_AGE_MS * cfg.approach_speed_mm_s) {
            CHECK(r.st.cmd_v_mm_s == cfg.approach_speed_mm_s); /* full speed */
        }
        prev = r.st.cmd_v_mm_s;
    }
}

/* The scan's heading (degrees) when it decides, for a flame at 80 degrees whose
 * sum peaks at 2 x peak_each and whose balance swings from the left sensor
 * (leading: the scan turns left) to the right across +-20 degrees. */
static float scan_decides_at(uint16_t peak_each)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    if (!into_the_scan(&r, &cfg)) {
        return -1.0f;
    }
    for (i = 0; i < 600 && r.out.state == FFR_ST_SCAN; ++i) {
        float deg = r.st.odo.heading_rad / FFR_DEG;
        float sum = 2.0f * (float)DARK, b;
        if (deg > 60.0f && deg < 100.0f) {
            sum = 2.0f * ((float)peak_each - ((float)peak_each - (float)DARK) * (deg - 80.0f) * (deg - 80.0f) / 400.0f);
        }
        b = ffr_clampf((80.0f - deg) / 20.0f, -1.0f, 1.0f);
        r.in.flame[0] = (uint16_t)(0.5f * sum * (1.0f + b) < (float)DARK ? (float)DARK : 0.5f * sum * (1.0f + b));
        r.in.flame[1] = (uint16_t)(0.5f * sum * (1.0f - b) < (float)DARK ? (float)DARK : 0.5f * sum * (1.0f - b));
        rig_tick(&r);
        if (r.st.cmd_w_rad_s <= 0.0f) {
            return deg; /* stopped: the scan has decided */
        }
    }
    return 1.0e3f;
}

TEST(a_strong_flame_crossing_to_the_trailing_side_ends_the_scan)
{
    /* strong (>= 4 x flame_detect): the scan ends once the balance has gone
     * from the leading side past the flame's heading to the trailing side
     * (~5 degrees past it), well before the sum falls to 0.6 of its peak
     * (12.6 degrees past); weak, the peak rule alone, as before */
    float strong = scan_decides_at(NEAR_EACH);
    float weak = scan_decides_at(300u);
    CHECK(strong > 80.0f && strong < 88.0f);
    CHECK(weak > 92.0f && weak < 100.0f);
}

TEST(the_fans_go_on_once_the_flame_is_within_their_reach)
{
    /* the approach: fans off with the flame near but not yet within the fans'
     * reach by its strength (below 14 x flame_detect), on from there without a
     * break into the fans' phase at the candle circle; a flame going out under
     * them is the fans' phase's (confirmed out, then watched), not a new scan */
    int out;
    for (out = 0; out <= 1; ++out) {
        ffr_config_t cfg;
        rig_t r;
        int i;
        ffr_config_default(&cfg);
        rig_room_route(&cfg, 0);
        CHECK(into_the_approach(&r, &cfg, NEAR_EACH));
        for (i = 0; i < 5; ++i) {
            rig_tick(&r);
            CHECK(r.out.state == FFR_ST_APPROACH && r.out.fan == 0);
        }
        r.in.flame[0] = r.in.flame[1] = 1300u; /* 2,600 counts over dark: > 14 x 170 */
        rig_tick(&r);
        CHECK(r.out.state == FFR_ST_APPROACH && r.out.fan == 1);
        CHECK(r.st.cmd_v_mm_s > 0.0f); /* still driving on */
        for (i = 0; i < 5; ++i) {
            rig_tick(&r);
            CHECK(r.out.fan == 1);
        }
        if (out) {
            r.in.flame[0] = r.in.flame[1] = DARK;
            rig_tick(&r);
            CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
            CHECK(rig_run_until_state(&r, FFR_ST_VERIFY, 200));
        } else {
            rig_line(&r, 0, 3);
            CHECK(r.out.state == FFR_ST_EXTINGUISH && r.out.fan == 1);
            for (i = 0; i < 10; ++i) {
                rig_tick(&r);
                CHECK(r.out.fan == 1);
            }
        }
    }
}

/* ---- the route's last room (furniture may hide its candle) ---- */

TEST(the_last_room_is_the_route_step_with_no_room_after_it_before_the_end)
{
    /* the default route visits rooms 1-4 (steps 4, 12, 18, 22), then END:
     * room 4 alone is the last; not on a way home, nor for the explorer */
    ffr_state_t st;
    uint8_t pc;
    ffr_config_default(&st.cfg);
    st.returning = 0u;
    for (pc = 0u; pc < st.cfg.route_len; ++pc) {
        st.route.pc = pc;
        CHECK(ffr_route_last_room(&st) == (pc == 22u));
    }
    CHECK(st.cfg.route[22].op == FFR_OP_ROOM && st.cfg.route[22].arg == 4u && st.cfg.route[23].op == FFR_OP_END);
    st.route.pc = 22u;
    st.returning = 1u;
    CHECK(ffr_route_last_room(&st) == 0);
    st.returning = 0u;
    st.cfg.start_area = FFR_START_HALLWAY;
    CHECK(ffr_route_last_room(&st) == 0);
    st.cfg.start_area = FFR_START_HOME;
    st.cfg.route_len = 23u; /* no END: no room is known to be the last */
    CHECK(ffr_route_last_room(&st) == 0);
}

TEST(a_room_before_the_last_scanned_without_a_flame_is_left)
{
    /* no flame seen driving in nor from the scan point: out at once, one scan */
    ffr_config_t cfg;
    rig_t r;
    ffr_config_default(&cfg);
    two_room_route(&cfg);
    CHECK(into_the_scan(&r, &cfg));
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.out.state == FFR_ST_EXIT);
    CHECK(r.st.room.scans == 1u);
}

TEST(the_last_room_scanned_without_a_flame_is_scanned_deeper_in_then_aside)
{
    /* The route's rooms before it held no flame: the candle is in this one,
     * hidden (furniture). A second scan DEEPER along the entry line, then a
     * third off it (45 degrees: the rig's rangers see nothing, every way is
     * open), kept as the trail's first point; none finds it: back to the
     * second point, out along the entry line, and the route ends */
    ffr_config_t cfg;
    rig_t r;
    int i;
    float h0, x1, y1, x2, y2, x3, y3, c, s, along, across;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_scan(&r, &cfg));
    h0 = r.st.room.entry_heading_rad;
    x1 = r.st.odo.x_mm;
    y1 = r.st.odo.y_mm;
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.out.state == FFR_ST_ENTER); /* DEEPER */
    CHECK(r.st.room.scans == 2u);
    CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 1000));
    x2 = r.st.odo.x_mm;
    y2 = r.st.odo.y_mm;
    c = ffr_cosf(h0);
    s = ffr_sinf(h0);
    along = (x2 - x1) * c + (y2 - y1) * s;
    CHECK(along > 350.0f && along < 410.0f); /* DEEPER_MM on the entry line */
    CHECK(ffr_absf(-(x2 - x1) * s + (y2 - y1) * c) < 40.0f); /* (the drive settling after the turn) */
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.out.state == FFR_ST_ENTER); /* the aside */
    CHECK(r.st.room.scans == 3u);
    for (i = 0; i < 8; ++i) {
        rig_tick(&r); /* the four headings, each clear: two half corridors a heading, one a tick */
    }
    CHECK(r.st.room.obst.aside_next == 8u);
    CHECK_NEAR(ffr_wrap_pi(r.st.room.best_heading_rad - h0), 45.0f * FFR_DEG, 1e-4);
    CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 1000));
    x3 = r.st.odo.x_mm;
    y3 = r.st.odo.y_mm;
    along = (x3 - x2) * c + (y3 - y2) * s;
    across = -(x3 - x2) * s + (y3 - y2) * c;
    CHECK(ffr_sqrtf(along * along + across * across) > 350.0f);
    CHECK(across > 0.6f * along && across < 1.4f * along); /* 45 degrees to the left */
    CHECK(r.st.room.obst.n_via == 1u);
    CHECK(ffr_absf((float)r.st.room.obst.via_x_mm[0] - x3) < 1.0f && ffr_absf((float)r.st.room.obst.via_y_mm[0] - y3) < 1.0f);
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.out.state == FFR_ST_TO_DOOR); /* back to the second point */
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 2000));
    CHECK(ffr_absf(r.st.odo.x_mm - x2) < 20.0f && ffr_absf(r.st.odo.y_mm - y2) < 20.0f);
    CHECK((r.out.flags & FFR_FLAG_FAILED) == 0);
    CHECK(rig_run_until_driving(&r, 400));
    rig_line(&r, 0, 3);
    CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 1000));
    CHECK(r.out.fail_code == FFR_FAIL_NO_FLAME);
}

TEST(the_last_room_with_no_way_aside_is_left_after_the_second_scan)
{
    /* something the rangers saw 200 mm off the second point along each of
     * the four aside headings: no third point, out from the second */
    ffr_config_t cfg;
    rig_t r;
    int k;
    float h0, x, y;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_second_scan(&r, &cfg));
    h0 = r.st.room.entry_heading_rad;
    for (k = -2; k <= 2; ++k) {
        float dir = h0 + (float)k * 45.0f * FFR_DEG;
        if (k != 0) {
            ffr_obst_mark(&r.st.room.obst, r.st.odo.x_mm + 200.0f * ffr_cosf(dir), r.st.odo.y_mm + 200.0f * ffr_sinf(dir));
        }
    }
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.out.state == FFR_ST_ENTER); /* looking along the four, a near half a tick, stopped */
    x = r.st.odo.x_mm;
    y = r.st.odo.y_mm;
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 10));
    CHECK(r.st.room.obst.aside_next == 8u);
    CHECK(r.st.room.obst.n_via == 0u);
    CHECK(ffr_absf(r.st.odo.x_mm - x) < 5.0f && ffr_absf(r.st.odo.y_mm - y) < 5.0f);
}

TEST(a_flame_seen_from_the_aside_point_is_approached)
{
    /* the third scan finds the flame: the approach starts there, the point
     * kept to back out through */
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    CHECK(into_the_second_scan(&r, &cfg));
    CHECK(run_while(&r, FFR_ST_SCAN, 2000));
    CHECK(r.st.room.scans == 3u);
    CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 1000));
    for (i = 0; i < 600 && r.out.state == FFR_ST_SCAN; ++i) {
        r.in.flame[0] = r.in.flame[1] = NEAR_EACH;
        rig_tick(&r);
    }
    CHECK(rig_run_until_state(&r, FFR_ST_APPROACH, 400));
    CHECK(r.st.room.obst.n_via == 1u);
    CHECK((r.out.flags & FFR_FLAG_FAILED) == 0);
}

/* A TURN step into the door, then the room. The line comes under the line
 * sensor `on_at` ticks into the turn and leaves it `off_after` ticks after
 * the entry begins (-1: before it begins, the line passed by as it turned). */
static void turn_onto_the_line(rig_t *r, ffr_config_t *cfg, int on_at, int off_after)
{
    int i;
    ffr_config_default(cfg);
    cfg->home_wall_side = FFR_HOME_AS_PLACED;
    cfg->route[0].op = FFR_OP_TURN;
    cfg->route[0].side = FFR_SIDE_NONE;
    cfg->route[0].param = -90;
    cfg->route[1].op = FFR_OP_ROOM;
    cfg->route[1].arg = 1;
    cfg->route[2].op = FFR_OP_END;
    cfg->route_len = 3;
    rig_init(r, cfg);
    r->in.start = 1;
    rig_tick(r);
    for (i = 0; i < 400 && r->out.state == FFR_ST_TURN; ++i) {
        r->in.line = i >= on_at && (off_after >= 0 || i < on_at + 6) ? 1u : 0u;
        rig_tick(r);
    }
    for (i = 0; i < off_after; ++i) {
        rig_tick(r);
    }
    r->in.line = 0;
}

TEST(a_line_under_the_sensor_as_the_entry_begins_is_the_doorway_line)
{
    /* a turn into the door ending late brings the sensor onto the line as
     * it turns: its edge came in the turn, none comes in the entry. Over
     * when in the turn it came and how long it stays under the sensor */
    static const int on_at[] = {2, 10, 25};
    static const int stays[] = {1, 3, 8};
    unsigned a, b;
    for (a = 0; a < sizeof(on_at) / sizeof(on_at[0]); ++a) {
        for (b = 0; b < sizeof(stays) / sizeof(stays[0]); ++b) {
            ffr_config_t cfg;
            rig_t r;
            turn_onto_the_line(&r, &cfg, on_at[a], stays[b]);
            CHECK(r.st.lines.count == 1u); /* one line, counted in the turn */
            CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 800));
            CHECK((r.out.flags & FFR_FLAG_IN_ROOM) != 0);
            CHECK((r.out.flags & FFR_FLAG_FAILED) == 0);
        }
    }
}

TEST(a_line_passed_while_turning_is_not_the_doorway_line)
{
    /* under the sensor for a few ticks of the turn and gone before the
     * entry begins: the entry still looks for its line, and fails without */
    ffr_config_t cfg;
    rig_t r;
    turn_onto_the_line(&r, &cfg, 2, -1);
    CHECK(r.st.lines.count == 1u);
    CHECK(r.st.lines.level == 0u);
    CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 3000));
    CHECK(r.out.fail_code == FFR_FAIL_NO_LINE);
    CHECK((r.out.flags & FFR_FLAG_IN_ROOM) == 0);
}

SUITE(room,
      TEST_REF(no_doorway_line_on_the_way_in_fails_no_line),
      TEST_REF(no_doorway_line_on_the_way_out_fails_no_line),
      TEST_REF(a_line_under_the_sensor_as_the_entry_begins_is_the_doorway_line),
      TEST_REF(a_line_passed_while_turning_is_not_the_doorway_line),
      TEST_REF(a_flame_the_fans_never_put_out_fails_not_out),
      TEST_REF(a_flame_that_keeps_coming_back_fails_not_out),
      TEST_REF(an_approached_flame_lost_and_not_found_again_fails_lost_flame),
      TEST_REF(a_flame_lost_and_found_again_is_approached_again),
      TEST_REF(a_far_flame_lost_is_searched_for_elsewhere),
      TEST_REF(leaving_hands_the_heading_out_to_the_route),
      TEST_REF(a_candle_base_at_reach_ahead_stops_the_approach),
      TEST_REF(a_front_ranger_folding_back_stops_the_approach),
      TEST_REF(a_scan_begun_just_past_a_near_flame_turns_on_to_it),
      TEST_REF(the_side_of_a_flame_and_a_flame_passed_by),
      TEST_REF(a_flame_passed_before_the_body_clears_the_door_does_not_end_the_entry),
      TEST_REF(the_line_sensor_past_the_doorway_line_on_the_way_out),
      TEST_REF(the_approach_slows_for_its_own_front_stop),
      TEST_REF(a_strong_flame_crossing_to_the_trailing_side_ends_the_scan),
      TEST_REF(the_fans_go_on_once_the_flame_is_within_their_reach),
      TEST_REF(the_last_room_is_the_route_step_with_no_room_after_it_before_the_end),
      TEST_REF(a_room_before_the_last_scanned_without_a_flame_is_left),
      TEST_REF(the_last_room_scanned_without_a_flame_is_scanned_deeper_in_then_aside),
      TEST_REF(the_last_room_with_no_way_aside_is_left_after_the_second_scan),
      TEST_REF(a_flame_seen_from_the_aside_point_is_approached));
