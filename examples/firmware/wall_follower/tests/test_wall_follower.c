/*
 * test_wall_follower.c - the wall follower's own named unit tests (host only).
 *
 *   make test            build and run them all
 *   ./wf_tests NAME ...  run only the tests whose names contain NAME
 *
 * Each test prints "ok NAME" or "FAIL NAME: file:line: what"; the exit status
 * is the number of failed tests (0: all passed). A test that checks nothing
 * fails too.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "wall_follower.h"

static int g_checks;
static int g_failed;
static const char *g_name;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        g_checks++;                                                                  \
        if (!(cond)) {                                                               \
            printf("FAIL %s: %s:%d: %s\n", g_name, __FILE__, __LINE__, #cond);       \
            g_failed = 1;                                                            \
            return;                                                                  \
        }                                                                            \
    } while (0)
#define NEAR(a, b, tol) CHECK(fabs((double)(a) - (double)(b)) <= (double)(tol))

/* ---- helpers ------------------------------------------------------------ */

static void fresh(ffr_state_t *st)
{
    ffr_config_t cfg;
    ffr_config_default(&cfg);
    ffr_init(st, &cfg);
}

/* The GP2D12 output (mV) for a range along the beam, by the configured fit. */
static uint16_t mv_for(const ffr_config_t *c, float mm)
{
    return (uint16_t)(c->ir_k_mv_mm / (mm + c->ir_d0_mm) + c->ir_offset_mv + 0.5f);
}

/* Inputs with a straight wall on the left at `lat` mm from the origin,
 * parallel, nothing else in view. */
static void wall_left(const ffr_config_t *c, ffr_inputs_t *in, float lat)
{
    float r = (lat - c->ir_y_mm[FFR_IR_LF]) / (float)sin(45.0 * 3.14159265358979 / 180.0);
    memset(in, 0, sizeof(*in));
    in->ir_mv[FFR_IR_LF] = mv_for(c, r);
    in->ir_mv[FFR_IR_LR] = mv_for(c, r);
}

/* The sensors after steady inputs (the rangers' median filter has settled). */
static void sense(ffr_state_t *st, const ffr_inputs_t *in, wf_sense_t *s)
{
    int k;
    for (k = 0; k < WF_IR_WINDOW; k++) {
        wf_sense(st, in, s);
    }
}

/* Drive over a white line: WF_LINE_TICKS ticks of white (the last one is the
 * line's edge), moving forward; `out` is that tick's. Then as many of black. */
static void cross_line(ffr_state_t *st, ffr_inputs_t *in, ffr_outputs_t *out)
{
    ffr_outputs_t dark;
    int k;
    for (k = 0; k < 2 * WF_LINE_TICKS; k++) {
        in->line = k < WF_LINE_TICKS ? 1u : 0u;
        st->cmd_v = 200.0f;
        ffr_step(st, in, k < WF_LINE_TICKS ? out : &dark);
        if (out->state == WF_DONE || out->state == WF_FAILED || out->state == WF_HOME) {
            break;
        }
    }
    in->line = 0u;
}

/* ---- tests -------------------------------------------------------------- */

static void test_math_sqrt_sin_cos_atan2(void)
{
    int i;
    NEAR(wf_sqrt(2.0f), sqrt(2.0), 1e-6);
    NEAR(wf_sqrt(1.0e6f), 1000.0, 1e-3);
    CHECK(wf_sqrt(-1.0f) == 0.0f);
    for (i = -36; i <= 36; i++) {
        double a = i * 10.0 * 3.14159265358979 / 180.0;
        NEAR(wf_sin((float)a), sin(a), 2e-5);
        NEAR(wf_cos((float)a), cos(a), 2e-5);
        NEAR(wf_atan2((float)sin(a), (float)cos(a)), atan2(sin(a), cos(a)), 2e-3);
    }
}

static void test_ir_range_from_millivolts(void)
{
    ffr_config_t c;
    ffr_config_default(&c);
    NEAR(wf_ir_mm(&c, mv_for(&c, 300.0f)), 300.0, 2.0);
    NEAR(wf_ir_mm(&c, mv_for(&c, 120.0f)), 120.0, 1.0);
    CHECK(wf_ir_mm(&c, 0u) > c.ir_max_mm);          /* nothing seen */
    CHECK(wf_ir_mm(&c, mv_for(&c, 1500.0f)) > c.ir_max_mm); /* beyond the range */
}

static void test_layout_describes_the_config_and_fits_the_contract(void)
{
    uint32_t n, i, j, cfg_rows = 0, end = 0;
    const ffr_field_t *f = ffr_layout(&n);
    static const uint32_t size_of[7] = {0, 1, 2, 2, 4, 4, 4};
    CHECK(ffr_version() == ((2u << 16) | 0u));
    CHECK(ffr_sizeof(FFR_S_INPUTS) == 32u && ffr_sizeof(FFR_S_OUTPUTS) == 24u);
    CHECK(ffr_sizeof(FFR_S_CONFIG) == sizeof(struct ffr_config) && ffr_sizeof(FFR_S_CONFIG) <= FFR_CONFIG_MAX);
    CHECK(ffr_sizeof(FFR_S_STATE) == sizeof(struct ffr_state) && ffr_sizeof(77u) == 0u);
    for (i = 0; i < n; i++) {
        if (f[i].struct_id != FFR_S_CONFIG) {
            continue;
        }
        cfg_rows++;
        CHECK(f[i].type >= FFR_T_U8 && f[i].type <= FFR_T_F32);
        CHECK(f[i].offset >= end); /* in order, no overlap */
        end = f[i].offset + size_of[f[i].type] * f[i].count;
        for (j = i + 1; j < n; j++) {
            CHECK(f[j].struct_id != FFR_S_CONFIG || strcmp(f[i].name, f[j].name) != 0);
        }
    }
    CHECK(end == sizeof(struct ffr_config)); /* every byte described, padding none */
    CHECK(cfg_rows > 40u);
    CHECK(strcmp(ffr_firmware_name(), "wall_follower 0.1") == 0);
}

static void test_names_of_states_and_failures(void)
{
    uint32_t n, i;
    const char *const *s = ffr_names(FFR_NAMES_STATE, &n);
    CHECK(n == WF_STATE_COUNT);
    for (i = 0; i < n; i++) {
        CHECK(s[i] != 0 && s[i][0] != '\0');
    }
    CHECK(strcmp(s[WF_DONE], "DONE") == 0 && strcmp(s[WF_FAILED], "FAILED") == 0);
    s = ffr_names(FFR_NAMES_FAIL, &n);
    CHECK(n == WF_FAIL_COUNT && s[0][0] == '\0' && strcmp(s[WF_FAIL_NO_FLAME], "no flame found") == 0);
    CHECK(ffr_names(5u, &n) == 0 && n == 0u);
}

static void test_state_table_is_complete(void)
{
    const wf_state_row_t *t = wf_state_table();
    int s, e;
    for (s = 0; s < WF_STATE_COUNT; s++) {
        int transitions = 0;
        CHECK(t[s].tick != 0);
        for (e = 0; e < WF_EV_COUNT; e++) {
            uint8_t next = t[s].next[e];
            CHECK(next < WF_STATE_COUNT || next == WF_RESUME_PREV);
            CHECK(next != WF_IDLE || t[s].next[e] == 0u);
            transitions += next != 0u;
        }
        /* every state but the two ends leads somewhere, and can give up */
        if (s == WF_DONE || s == WF_FAILED) {
            CHECK(transitions == 0);
        } else {
            CHECK(transitions > 0 && t[s].next[WF_EV_FAIL] == WF_FAILED);
        }
    }
    CHECK(t[WF_FOLLOW].next[WF_EV_LINE] == WF_SCAN); /* only following, beside a wall, scans */
    CHECK(t[WF_ARC].next[WF_EV_LINE] == 0u && t[WF_CORNER].next[WF_EV_LINE] == 0u);
}

static void test_sense_a_parallel_left_wall(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    wf_sense_t s;
    fresh(&st);
    wall_left(&st.cfg, &in, 190.0f);
    sense(&st, &in, &s);
    CHECK(s.side_ok);
    NEAR(s.side_mm, 190.0, 3.0);
    NEAR(s.side_deg, 0.0, 1.0);
    /* the wall farther at the front than at the back: it turns away, angle > 0 */
    in.ir_mv[FFR_IR_LF] = mv_for(&st.cfg, 260.0f);
    sense(&st, &in, &s);
    CHECK(s.side_ok && s.side_deg > 5.0f);
    /* the right side (the way home) sees nothing there */
    st.side = -1.0f;
    sense(&st, &in, &s);
    CHECK(!s.side_ok && s.side_front_mm > st.cfg.open_mm);
}

static void test_a_lone_spike_is_not_a_wall_nor_a_blip_a_line(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    wf_sense_t s;
    int k, edges = 0;
    fresh(&st);
    wall_left(&st.cfg, &in, 190.0f);
    sense(&st, &in, &s);
    CHECK(s.ir_mm[FFR_IR_CF] > st.cfg.ir_max_mm);
    in.ir_mv[FFR_IR_CF] = 2400u; /* one measurement (4 ticks) says a wall touches the front */
    for (k = 0; k < 4; k++) {
        wf_sense(&st, &in, &s);
        CHECK(s.ir_mm[FFR_IR_CF] > st.cfg.ir_max_mm);
    }
    for (k = 0; k < WF_IR_WINDOW; k++) { /* it stays: it is there */
        wf_sense(&st, &in, &s);
    }
    CHECK(s.ir_mm[FFR_IR_CF] < 150.0f);
    for (k = 0; k < 40; k++) { /* white for one tick in every four: never a line */
        in.line = (k % 4 == 0) ? 1u : 0u;
        wf_sense(&st, &in, &s);
        edges += s.line_edge;
    }
    CHECK(edges == 0);
    in.line = 1u;
    for (k = 0; k < WF_LINE_TICKS; k++) {
        wf_sense(&st, &in, &s);
        edges += s.line_edge;
    }
    CHECK(edges == 1);
}

static void test_follow_steers_to_the_wall_distance(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    wf_sense_t s;
    const wf_state_row_t *row = &wf_state_table()[WF_FOLLOW];
    fresh(&st);
    wall_left(&st.cfg, &in, 260.0f); /* too far: turn left */
    sense(&st, &in, &s);
    CHECK(row->tick(&st, &s) == WF_EV_NONE && st.cmd_w > 0.0f && st.cmd_v > 0.0f);
    wall_left(&st.cfg, &in, 150.0f); /* too near: turn right */
    sense(&st, &in, &s);
    CHECK(row->tick(&st, &s) == WF_EV_NONE && st.cmd_w < 0.0f);
    in.ir_mv[FFR_IR_CF] = mv_for(&st.cfg, 100.0f); /* a wall ahead */
    sense(&st, &in, &s);
    CHECK(row->tick(&st, &s) == WF_EV_FRONT);
    memset(&in, 0, sizeof(in)); /* the wall ends */
    sense(&st, &in, &s);
    CHECK(row->tick(&st, &s) == WF_EV_OPEN);
}

static void test_waits_for_start_with_motors_off(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    int i;
    fresh(&st);
    memset(&in, 0, sizeof(in));
    for (i = 0; i < 50; i++) {
        in.t_ms = (uint32_t)i * 10u;
        in.seq = (uint32_t)i;
        ffr_step(&st, &in, &out);
        CHECK(out.state == WF_IDLE && out.pwm[0] == 0 && out.pwm[1] == 0 && out.seq == (uint32_t)i);
    }
    in.start = 1u;
    ffr_step(&st, &in, &out);
    CHECK(out.state == WF_START_TURN && out.pwm[0] < 0 && out.pwm[1] > 0); /* turning left */
}

static void test_doorway_lines_alternate_in_and_out(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    int k;
    fresh(&st);
    wf_enter(&st, WF_FOLLOW);
    st.x_mm = 2000.0f; /* far from home */
    st.max_away_mm = 2000.0f;
    st.cmd_v = 200.0f;
    wall_left(&st.cfg, &in, 190.0f);
    for (k = 0; k < 2; k++) {
        cross_line(&st, &in, &out);
        in.line = 0u;
        st.dist_mm += 500.0f;
        st.cmd_v = 200.0f;
        ffr_step(&st, &in, &out);
        if (k == 0) {
            CHECK((out.flags & FFR_FLAG_IN_ROOM) != 0u); /* in: a scan is due */
            CHECK(out.state == WF_SCAN);
            wf_enter(&st, WF_FOLLOW);
        } else {
            CHECK((out.flags & FFR_FLAG_IN_ROOM) == 0u); /* out: no scan */
            CHECK(out.state == WF_FOLLOW && st.scan_at_mm < 0.0f);
        }
    }
    CHECK(out.line_count == 2u);
}

static void test_back_home_without_a_flame_fails(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    fresh(&st);
    wf_enter(&st, WF_FOLLOW);
    st.max_away_mm = 3000.0f; /* was far away, now at the start again */
    st.cmd_v = 200.0f;
    wall_left(&st.cfg, &in, 190.0f);
    cross_line(&st, &in, &out);
    CHECK(out.state == WF_FAILED && (out.flags & FFR_FLAG_FAILED) && out.fail_code == WF_FAIL_NO_FLAME);
    CHECK(out.pwm[0] == 0 && out.pwm[1] == 0 && out.fan == 0u);
}

static void test_the_way_back_counts_the_way_in_s_doorways_to_home(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    int k;
    fresh(&st);
    st.x_mm = 3000.0f; /* odometry far from the start (it drifts): the count decides */
    st.max_away_mm = 3000.0f;
    st.flags = FFR_FLAG_EXTINGUISHED;
    st.doors_at_scan = 3u; /* in, out of one room, into the candle's */
    st.side = -1.0f;
    wf_enter(&st, WF_FOLLOW);
    memset(&in, 0, sizeof(in));
    for (k = 1; k <= 4; k++) {
        st.cmd_v = 200.0f;
        cross_line(&st, &in, &out);
        if (k < 4) {
            in.line = 0u;
            ffr_step(&st, &in, &out);
            st.dist_mm += 500.0f;
            CHECK(out.state != WF_HOME && st.doors_back == (uint8_t)k);
            wf_enter(&st, WF_FOLLOW);
        }
    }
    CHECK(out.state == WF_HOME); /* the line after the three doorways: home's ring */
}

static void test_fans_until_the_flame_stays_out_then_back_the_other_wall(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    int i;
    fresh(&st);
    st.t_ms = 1000u;
    st.resume_rad = 0.5f;
    wf_enter(&st, WF_EXTINGUISH);
    memset(&in, 0, sizeof(in));
    in.flame[0] = in.flame[1] = 2000u;
    for (i = 0; i < 100; i++) { /* burning: fans on, not moving */
        in.t_ms = 1000u + (uint32_t)i * 10u;
        ffr_step(&st, &in, &out);
        CHECK(out.state == WF_EXTINGUISH && out.fan == 1u);
    }
    in.flame[0] = in.flame[1] = 40u; /* out */
    for (i = 0; i < 100 && out.state == WF_EXTINGUISH; i++) {
        in.t_ms += 10u;
        ffr_step(&st, &in, &out);
    }
    CHECK(out.state == WF_GOTO && out.fan == 0u && (out.flags & FFR_FLAG_EXTINGUISHED));
    CHECK(in.t_ms - 1990u >= st.cfg.out_confirm_ms); /* only after it stayed out */
    CHECK(st.side < 0.0f); /* home along the right-hand wall: the way in, backwards */
    NEAR(st.resume_rad, 0.5 - 3.14159265, 1e-4);
}

static void test_flame_never_out_gives_up(void)
{
    ffr_state_t st;
    ffr_inputs_t in;
    ffr_outputs_t out;
    uint32_t t;
    fresh(&st);
    wf_enter(&st, WF_EXTINGUISH);
    memset(&in, 0, sizeof(in));
    in.flame[0] = in.flame[1] = 2000u;
    for (t = 0; t <= st.cfg.fan_max_ms + 20u; t += 10u) {
        in.t_ms = t;
        ffr_step(&st, &in, &out);
    }
    CHECK(out.state == WF_FAILED && out.fail_code == WF_FAIL_NOT_OUT);
}

static void test_scan_turns_once_and_finds_the_brightest_heading(void)
{
    ffr_state_t st;
    wf_sense_t s;
    const wf_state_row_t *row = &wf_state_table()[WF_SCAN];
    wf_event_t ev = WF_EV_NONE;
    int i;
    fresh(&st);
    wf_enter(&st, WF_SCAN);
    memset(&s, 0, sizeof(s));
    for (i = 0; i < 2000 && ev == WF_EV_NONE; i++) {
        /* pretend the robot turns as commanded; the flame is brightest at 90 degrees */
        st.heading_rad = wf_wrap(st.heading_rad + st.cmd_w * 0.01f);
        s.flame_sum = 1000.0f * (float)cos((double)st.heading_rad - 1.5707963);
        ev = row->tick(&st, &s);
    }
    CHECK(ev == WF_EV_FLAME);
    NEAR(st.target_rad, 2.0 * 3.14159265, 0.05); /* one full turn */
    NEAR(st.best_rad, 1.5707963, 0.05);
}

typedef struct {
    const char *name;
    void (*fn)(void);
} test_t;

#define T(f) {#f, f}
static const test_t k_tests[] = {
    T(test_math_sqrt_sin_cos_atan2),
    T(test_ir_range_from_millivolts),
    T(test_layout_describes_the_config_and_fits_the_contract),
    T(test_names_of_states_and_failures),
    T(test_state_table_is_complete),
    T(test_sense_a_parallel_left_wall),
    T(test_a_lone_spike_is_not_a_wall_nor_a_blip_a_line),
    T(test_follow_steers_to_the_wall_distance),
    T(test_waits_for_start_with_motors_off),
    T(test_doorway_lines_alternate_in_and_out),
    T(test_back_home_without_a_flame_fails),
    T(test_the_way_back_counts_the_way_in_s_doorways_to_home),
    T(test_fans_until_the_flame_stays_out_then_back_the_other_wall),
    T(test_flame_never_out_gives_up),
    T(test_scan_turns_once_and_finds_the_brightest_heading),
};

int main(int argc, char **argv)
{
    size_t i;
    int a, failed = 0, ran = 0;
    for (i = 0; i < sizeof(k_tests) / sizeof(k_tests[0]); i++) {
        int chosen = argc < 2;
        for (a = 1; a < argc; a++) {
            chosen |= strstr(k_tests[i].name, argv[a]) != 0;
        }
        if (!chosen) {
            continue;
        }
        g_name = k_tests[i].name;
        g_checks = 0;
        g_failed = 0;
        k_tests[i].fn();
        if (!g_failed && g_checks == 0) {
            printf("FAIL %s: checks nothing\n", g_name);
            g_failed = 1;
        }
        if (!g_failed) {
            printf("ok %s (%d checks)\n", g_name, g_checks);
        }
        failed += g_failed;
        ran++;
    }
    printf("%d tests, %d failed\n", ran, failed);
    return failed;
}
