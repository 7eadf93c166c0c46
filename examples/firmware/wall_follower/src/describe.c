/*
 * describe.c - what the contract asks a firmware to say about itself: its
 * configuration's defaults and layout (the config descriptor table), the
 * fixed I/O layout, its state and failure names, its name, version and the
 * hash over all of it.
 */
#include <stddef.h>

#include "ffr_contract_hash.h"
#include "wall_follower.h"

void ffr_config_default(ffr_config_t *c)
{
    static const float ir_x[FFR_IR_COUNT] = {100.0f, 80.0f, 80.0f, -80.0f, -80.0f};
    static const float ir_y[FFR_IR_COUNT] = {0.0f, 70.0f, -70.0f, 70.0f, -70.0f};
    static const float ir_a[FFR_IR_COUNT] = {0.0f, 45.0f, -45.0f, 135.0f, -135.0f};
    uint8_t *p = (uint8_t *)c;
    uint32_t i;
    for (i = 0; i < (uint32_t)sizeof(*c); i++) {
        p[i] = 0u;
    }
    /* the robot: ffr overwrites these with the team's calibration */
    c->wheel_radius_mm = 28.0f;
    c->track_width_mm = 170.0f;
    c->encoder_ticks_per_rev = 360.0f;
    c->body_front_mm = 120.0f;
    c->body_half_width_mm = 100.0f;
    for (i = 0; i < FFR_IR_COUNT; i++) {
        c->ir_x_mm[i] = ir_x[i];
        c->ir_y_mm[i] = ir_y[i];
        c->ir_angle_deg[i] = ir_a[i];
    }
    c->line_sensor_x_mm = 110.0f;
    c->ir_k_mv_mm = 332000.0f;
    c->ir_offset_mv = 15.0f;
    c->ir_d0_mm = 40.0f;

    /* this firmware's own tuning */
    c->ir_max_mm = 800.0f;
    c->cruise_mm_s = 250.0f;
    c->approach_mm_s = 150.0f;
    c->turn_deg_s = 150.0f;
    c->scan_deg_s = 120.0f;
    c->accel_mm_s2 = 1200.0f;
    c->pwm_per_mm_s = 2.04f;
    c->pwm_offset = 98.0f;
    c->pwm_kp = 0.5f;
    c->wall_mm = 190.0f;
    c->wall_kp = 1.2f;
    c->angle_kp = 3.5f;
    c->heading_kp = 4.0f;
    c->heading_learn = 0.02f;
    c->max_yaw_deg_s = 120.0f;
    c->front_mm = 120.0f;
    c->open_mm = 400.0f;
    c->corner_mm = 0.0f;
    c->arc_max_deg = 300.0f;
    c->start_turn_deg = 180.0f;
    c->entry_mm = 250.0f;
    c->line_holdoff_mm = 100.0f;
    c->flame_detect = 250.0f;
    c->flame_near = 3000.0f;
    c->flame_out = 120.0f;
    c->out_fraction = 0.1f;
    c->flame_steer_deg_s = 90.0f;
    c->approach_stop_mm = 120.0f;
    c->guard_mm = 150.0f;
    c->guard_kp = 1.5f;
    c->home_zone_mm = 450.0f;
    c->away_mm = 1000.0f;
    c->out_confirm_ms = 500u;
    c->fan_max_ms = 10000u;
    c->mission_max_ms = 290000u;
    c->scan_attempts = 3u;
}

/* The configuration's rows, once: the compiler checks each against its
 * member (type, signedness, array length), and the same list makes the
 * table ffr reads to set, list and check any field by name. Keep it in the
 * order of struct ffr_config. */
#define WF_CONFIG_ROWS(S, A) \
    S(wheel_radius_mm, F32) S(track_width_mm, F32) S(encoder_ticks_per_rev, F32) \
    S(body_front_mm, F32) S(body_half_width_mm, F32) A(ir_x_mm, F32, FFR_IR_COUNT) \
    A(ir_y_mm, F32, FFR_IR_COUNT) A(ir_angle_deg, F32, FFR_IR_COUNT) S(line_sensor_x_mm, F32) \
    S(ir_k_mv_mm, F32) S(ir_offset_mv, F32) S(ir_d0_mm, F32) S(ir_max_mm, F32) S(cruise_mm_s, F32) \
    S(approach_mm_s, F32) S(turn_deg_s, F32) S(scan_deg_s, F32) S(accel_mm_s2, F32) \
    S(pwm_per_mm_s, F32) S(pwm_offset, F32) S(pwm_kp, F32) S(wall_mm, F32) S(wall_kp, F32) \
    S(angle_kp, F32) S(heading_kp, F32) S(heading_learn, F32) S(max_yaw_deg_s, F32) S(front_mm, F32) S(open_mm, F32) \
    S(corner_mm, F32) S(arc_max_deg, F32) S(start_turn_deg, F32) S(entry_mm, F32) \
    S(line_holdoff_mm, F32) S(flame_detect, F32) S(flame_near, F32) S(flame_out, F32) S(out_fraction, F32) \
    S(flame_steer_deg_s, F32) S(approach_stop_mm, F32) S(guard_mm, F32) S(guard_kp, F32) \
    S(home_zone_mm, F32) S(away_mm, F32) S(out_confirm_ms, U32) S(fan_max_ms, U32) \
    S(mission_max_ms, U32) S(scan_attempts, U8) A(reserved, U8, 3)

#define CHECK(m, code) FFR_CHECK_ROW(ffr_config_t, m, code);
#define CHECK_A(m, code, n) FFR_CHECK_ARRAY(ffr_config_t, m, code, n);
WF_CONFIG_ROWS(CHECK, CHECK_A)
FFR_STATIC_ASSERT(config_fits, sizeof(struct ffr_config) <= FFR_CONFIG_MAX);
FFR_STATIC_ASSERT(state_fits, sizeof(struct ffr_state) <= FFR_STATE_MAX);

#define ROW(m, code) FFR_ROW(FFR_S_CONFIG, ffr_config_t, m, code),
#define ROW_A(m, code, n) FFR_ROW_ARRAY(FFR_S_CONFIG, ffr_config_t, m, code, n),

/* The contract's I/O rows, then this firmware's configuration. */
static const ffr_field_t k_layout[] = {FFR_IO_ROWS, WF_CONFIG_ROWS(ROW, ROW_A)};

const ffr_field_t *ffr_layout(uint32_t *count)
{
    if (count != 0) {
        *count = (uint32_t)(sizeof(k_layout) / sizeof(k_layout[0]));
    }
    return k_layout;
}

uint32_t ffr_version(void)
{
    return (FFR_CONTRACT_MAJOR << 16) | FFR_CONTRACT_MINOR;
}

uint32_t ffr_sizeof(uint32_t struct_id)
{
    switch (struct_id) {
    case FFR_S_INPUTS:
        return (uint32_t)sizeof(ffr_inputs_t);
    case FFR_S_OUTPUTS:
        return (uint32_t)sizeof(ffr_outputs_t);
    case FFR_S_CONFIG:
        return (uint32_t)sizeof(struct ffr_config);
    case FFR_S_STATE:
        return (uint32_t)sizeof(struct ffr_state);
    default:
        return 0u;
    }
}

const char *ffr_firmware_name(void)
{
    return WF_NAME;
}

static const char *const k_fail_names[WF_FAIL_COUNT] = {
    "", "no flame found", "fans did not put the flame out", "flame lost", "timeout",
};

const char *const *ffr_names(uint32_t kind, uint32_t *count)
{
    if (kind == FFR_NAMES_STATE) {
        if (count != 0) {
            *count = WF_STATE_COUNT;
        }
        return wf_state_names();
    }
    if (kind == FFR_NAMES_FAIL) {
        if (count != 0) {
            *count = WF_FAIL_COUNT;
        }
        return k_fail_names;
    }
    if (count != 0) {
        *count = 0u;
    }
    return 0;
}

/* The contract's recipe (ffr_contract_hash.h): the harness computes the same
 * from what the library describes and compares a board's with it. */
uint32_t ffr_layout_hash(void)
{
    return ffr_contract_hash();
}
