/*
 * describe.c - what the contract asks a firmware to say about itself: its
 * configuration's defaults and layout (the config descriptor table), the
 * fixed I/O layout, its state and failure names, its name, version and the
 * hash over all of it.
 */
#include <stddef.h>

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
    c->max_yaw_deg_s = 120.0f;
    c->front_mm = 120.0f;
    c->open_mm = 400.0f;
    c->corner_mm = 0.0f;
    c->arc_max_deg = 300.0f;
    c->start_turn_deg = 180.0f;
    c->entry_mm = 120.0f;
    c->line_holdoff_mm = 100.0f;
    c->flame_detect = 250.0f;
    c->flame_near = 3000.0f;
    c->flame_out = 120.0f;
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

#define FLD(sid, type_, member, t, n) \
    {#member, (uint16_t)(sid), (uint16_t)(t), (uint16_t)offsetof(type_, member), (uint16_t)(n)}
#define IN(m, t, n) FLD(FFR_S_INPUTS, ffr_inputs_t, m, t, n)
#define OUT(m, t, n) FLD(FFR_S_OUTPUTS, ffr_outputs_t, m, t, n)
#define CFG(m, t, n) FLD(FFR_S_CONFIG, struct ffr_config, m, t, n)
#define F32(m) CFG(m, FFR_T_F32, 1)

/* The contract's I/O rows, then this firmware's configuration: the config
 * descriptor table ffr reads to set, list and check fields by name. */
static const ffr_field_t k_layout[] = {
    IN(t_ms, FFR_T_U32, 1),
    IN(seq, FFR_T_U32, 1),
    IN(enc, FFR_T_I32, 2),
    IN(ir_mv, FFR_T_U16, FFR_IR_COUNT),
    IN(flame, FFR_T_U16, 2),
    IN(line, FFR_T_U8, 1),
    IN(start, FFR_T_U8, 1),

    OUT(seq, FFR_T_U32, 1),
    OUT(pwm, FFR_T_I16, 2),
    OUT(fan, FFR_T_U8, 1),
    OUT(state, FFR_T_U8, 1),
    OUT(room, FFR_T_U8, 1),
    OUT(rooms_searched, FFR_T_U8, 1),
    OUT(line_count, FFR_T_U8, 1),
    OUT(flags, FFR_T_U8, 1),
    OUT(step, FFR_T_U8, 1),
    OUT(fail_code, FFR_T_U8, 1),
    OUT(odo_x_mm, FFR_T_I16, 1),
    OUT(odo_y_mm, FFR_T_I16, 1),
    OUT(odo_heading_cdeg, FFR_T_I16, 1),
    OUT(reserved, FFR_T_I16, 1),

    F32(wheel_radius_mm),
    F32(track_width_mm),
    F32(encoder_ticks_per_rev),
    F32(body_front_mm),
    F32(body_half_width_mm),
    CFG(ir_x_mm, FFR_T_F32, FFR_IR_COUNT),
    CFG(ir_y_mm, FFR_T_F32, FFR_IR_COUNT),
    CFG(ir_angle_deg, FFR_T_F32, FFR_IR_COUNT),
    F32(line_sensor_x_mm),
    F32(ir_k_mv_mm),
    F32(ir_offset_mv),
    F32(ir_d0_mm),
    F32(ir_max_mm),
    F32(cruise_mm_s),
    F32(approach_mm_s),
    F32(turn_deg_s),
    F32(scan_deg_s),
    F32(accel_mm_s2),
    F32(pwm_per_mm_s),
    F32(pwm_offset),
    F32(pwm_kp),
    F32(wall_mm),
    F32(wall_kp),
    F32(angle_kp),
    F32(heading_kp),
    F32(max_yaw_deg_s),
    F32(front_mm),
    F32(open_mm),
    F32(corner_mm),
    F32(arc_max_deg),
    F32(start_turn_deg),
    F32(entry_mm),
    F32(line_holdoff_mm),
    F32(flame_detect),
    F32(flame_near),
    F32(flame_out),
    F32(flame_steer_deg_s),
    F32(approach_stop_mm),
    F32(guard_mm),
    F32(guard_kp),
    F32(home_zone_mm),
    F32(away_mm),
    CFG(out_confirm_ms, FFR_T_U32, 1),
    CFG(fan_max_ms, FFR_T_U32, 1),
    CFG(mission_max_ms, FFR_T_U32, 1),
    CFG(scan_attempts, FFR_T_U8, 1),
    CFG(reserved, FFR_T_U8, 3),
};

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

static uint32_t fnv(uint32_t h, const void *data, uint32_t n)
{
    const uint8_t *b = (const uint8_t *)data;
    uint32_t i;
    for (i = 0; i < n; i++) {
        h ^= b[i];
        h *= 16777619u;
    }
    return h;
}

static uint32_t fnv_str(uint32_t h, const char *s)
{
    uint32_t n = 0;
    while (s[n] != '\0') {
        n++;
    }
    return fnv(h, s, n + 1u); /* with its terminator: "ab","c" differs from "a","bc" */
}

static uint32_t fnv_u16(uint32_t h, uint16_t v)
{
    uint8_t b[2];
    b[0] = (uint8_t)(v & 0xFFu);
    b[1] = (uint8_t)(v >> 8);
    return fnv(h, b, 2u);
}

uint32_t ffr_layout_hash(void)
{
    uint32_t h = 2166136261u;
    uint32_t n, i, kind;
    const ffr_field_t *f = ffr_layout(&n);
    for (i = 0; i < n; i++) {
        h = fnv_str(h, f[i].name);
        h = fnv_u16(h, f[i].struct_id);
        h = fnv_u16(h, f[i].type);
        h = fnv_u16(h, f[i].offset);
        h = fnv_u16(h, f[i].count);
    }
    for (kind = FFR_NAMES_STATE; kind <= FFR_NAMES_FAIL; kind++) {
        const char *const *names = ffr_names(kind, &n);
        for (i = 0; i < n; i++) {
            h = fnv_str(h, names[i]);
        }
    }
    return fnv_str(h, ffr_firmware_name());
}
