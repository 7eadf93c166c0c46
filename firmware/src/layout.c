/*
 * The firmware describes its own I/O and configuration layout so the host
 * (ctypes) and the wire codec can check, at load time, that they agree with
 * this build field by field. The table is read-only data, not state.
 */
#include <stddef.h>

#include "ffr_internal.h"

#define FLD(sid, type_, member, t, n) {#member, (uint16_t)(sid), (uint16_t)(t), (uint16_t)offsetof(type_, member), (uint16_t)(n)}
#define IN(m, t, n) FLD(FFR_S_INPUTS, ffr_inputs_t, m, t, n)
#define OUT(m, t, n) FLD(FFR_S_OUTPUTS, ffr_outputs_t, m, t, n)
#define CFG(m, t, n) FLD(FFR_S_CONFIG, ffr_config_t, m, t, n)
#define STP(m, t, n) FLD(FFR_S_STEP, ffr_step_t, m, t, n)

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

    STP(op, FFR_T_U8, 1),
    STP(side, FFR_T_U8, 1),
    STP(event, FFR_T_U8, 1),
    STP(arg, FFR_T_U8, 1),
    STP(param, FFR_T_I16, 1),
    STP(reserved, FFR_T_I16, 1),

    CFG(wheel_radius_mm, FFR_T_F32, 1),
    CFG(track_width_mm, FFR_T_F32, 1),
    CFG(encoder_ticks_per_rev, FFR_T_F32, 1),
    CFG(body_front_mm, FFR_T_F32, 1),
    CFG(body_half_width_mm, FFR_T_F32, 1),
    CFG(ir_x_mm, FFR_T_F32, FFR_IR_COUNT),
    CFG(ir_y_mm, FFR_T_F32, FFR_IR_COUNT),
    CFG(ir_angle_deg, FFR_T_F32, FFR_IR_COUNT),
    CFG(line_sensor_x_mm, FFR_T_F32, 1),
    CFG(ir_k_mv_mm, FFR_T_F32, 1),
    CFG(ir_offset_mv, FFR_T_F32, 1),
    CFG(ir_d0_mm, FFR_T_F32, 1),
    CFG(ir_min_mm, FFR_T_F32, 1),
    CFG(ir_max_mm, FFR_T_F32, 1),
    CFG(ir_min_mv, FFR_T_F32, 1),
    CFG(ff_gain_permille_per_mm_s, FFR_T_F32, 1),
    CFG(ff_offset_permille, FFR_T_F32, 1),
    CFG(speed_kp, FFR_T_F32, 1),
    CFG(speed_ki, FFR_T_F32, 1),
    CFG(accel_mm_s2, FFR_T_F32, 1),
    CFG(pwm_limit, FFR_T_I16, 1),
    CFG(reserved0, FFR_T_I16, 1),
    CFG(cruise_speed_mm_s, FFR_T_F32, 1),
    CFG(room_speed_mm_s, FFR_T_F32, 1),
    CFG(approach_speed_mm_s, FFR_T_F32, 1),
    CFG(turn_rate_deg_s, FFR_T_F32, 1),
    CFG(scan_rate_deg_s, FFR_T_F32, 1),
    CFG(wall_target_mm, FFR_T_F32, 1),
    CFG(wall_kp_deg_per_mm, FFR_T_F32, 1),
    CFG(wall_max_deg, FFR_T_F32, 1),
    CFG(heading_kp, FFR_T_F32, 1),
    CFG(wall_align_gain, FFR_T_F32, 1),
    CFG(front_stop_mm, FFR_T_F32, 1),
    CFG(front_slow_mm, FFR_T_F32, 1),
    CFG(open_mm, FFR_T_F32, 1),
    CFG(open_confirm_mm, FFR_T_F32, 1),
    CFG(wall_seen_mm, FFR_T_F32, 1),
    CFG(hallway_half_mm, FFR_T_F32, 1),
    CFG(turn_tol_deg, FFR_T_F32, 1),
    CFG(line_holdoff_mm, FFR_T_F32, 1),
    CFG(room_line_max_mm, FFR_T_F32, 1),
    CFG(room_entry_mm, FFR_T_F32, 1),
    CFG(room_exit_mm, FFR_T_F32, 1),
    CFG(home_advance_mm, FFR_T_F32, 1),
    CFG(flame_detect, FFR_T_F32, 1),
    CFG(flame_out, FFR_T_F32, 1),
    CFG(flame_steer_deg, FFR_T_F32, 1),
    CFG(approach_stop_mm, FFR_T_F32, 1),
    CFG(guard_side_mm, FFR_T_F32, 1),
    CFG(guard_stop_mm, FFR_T_F32, 1),
    CFG(fan_timeout_ms, FFR_T_U32, 1),
    CFG(flame_out_confirm_ms, FFR_T_U32, 1),
    CFG(verify_ms, FFR_T_U32, 1),
    CFG(fan_attempts, FFR_T_U8, 1),
    CFG(scan_dir, FFR_T_U8, 1),
    CFG(route_len, FFR_T_U8, 1),
    CFG(home_wall_side, FFR_T_U8, 1),
    CFG(route, 0, FFR_ROUTE_MAX), /* type 0: an array of ffr_step_t */
    CFG(return_start, FFR_T_U8, FFR_ROOMS_MAX),
};

uint32_t ffr_version(void) { return (FFR_VERSION_MAJOR << 16) | FFR_VERSION_MINOR; }

uint32_t ffr_sizeof(uint32_t struct_id)
{
    switch (struct_id) {
    case FFR_S_INPUTS:
        return (uint32_t)sizeof(ffr_inputs_t);
    case FFR_S_OUTPUTS:
        return (uint32_t)sizeof(ffr_outputs_t);
    case FFR_S_CONFIG:
        return (uint32_t)sizeof(ffr_config_t);
    case FFR_S_STEP:
        return (uint32_t)sizeof(ffr_step_t);
    case 99u:
        return (uint32_t)sizeof(ffr_state_t);
    default:
        return 0u;
    }
}

const ffr_field_t *ffr_layout(uint32_t *count)
{
    if (count != NULL) {
        *count = (uint32_t)(sizeof(k_layout) / sizeof(k_layout[0]));
    }
    return k_layout;
}

static uint32_t fnv(uint32_t h, uint32_t v, int bytes)
{
    int i;
    for (i = 0; i < bytes; ++i) {
        h ^= (v >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

uint32_t ffr_layout_hash(void)
{
    uint32_t h = 2166136261u;
    uint32_t n;
    uint32_t i;
    const ffr_field_t *f = ffr_layout(&n);
    for (i = 0; i < n; ++i) {
        const char *c;
        for (c = f[i].name; *c != '\0'; ++c) {
            h = fnv(h, (uint32_t)(uint8_t)*c, 1);
        }
        h = fnv(h, f[i].struct_id, 2);
        h = fnv(h, f[i].type, 2);
        h = fnv(h, f[i].offset, 2);
        h = fnv(h, f[i].count, 2);
    }
    for (i = 0; i < 4u; ++i) {
        h = fnv(h, ffr_sizeof(i), 4);
    }
    return h;
}
