/*
 * The firmware describes itself (the contract, ffr_contract.h): its I/O and
 * configuration layout, so the harness can read and set the configuration by
 * name and the wire codec can pack it; the names of its states, failure codes
 * and route program's codes; its name; and a hash over all of it, which the
 * wire handshake compares. The tables are read-only data, not state.
 *
 * Each row below exists once, in an X-macro list, and is expanded twice: into
 * the table and into a compile-time check that the row's type code and count
 * match the struct member (FFR_CHECK_* in ffr_contract.h).
 */
#include <stddef.h>

#include "ffr_contract_hash.h"
#include "ffr_internal.h"

/* ffr_step_t: one route step (our sub-struct FFR_S_ROUTE_STEP). S = scalar row. */
#define STEP_ROWS(S) \
    S(op, U8) S(side, U8) S(event, U8) S(arg, U8) S(param, I16) S(reserved, I16)

/* ffr_config_t. S = scalar, A = array of n, X = array of n sub-structs. */
#define CONFIG_ROWS(S, A, X)                                                                          \
    S(wheel_radius_mm, F32) S(track_width_mm, F32) S(encoder_ticks_per_rev, F32) S(body_front_mm, F32) \
    S(body_half_width_mm, F32) A(ir_x_mm, F32, FFR_IR_COUNT) A(ir_y_mm, F32, FFR_IR_COUNT)             \
    A(ir_angle_deg, F32, FFR_IR_COUNT) S(line_sensor_x_mm, F32) S(ir_k_mv_mm, F32)                    \
    S(ir_offset_mv, F32) S(ir_d0_mm, F32) S(ir_min_mm, F32) S(ir_max_mm, F32) S(ir_min_mv, F32)        \
    S(ff_gain_permille_per_mm_s, F32) S(ff_offset_permille, F32) S(speed_kp, F32) S(speed_ki, F32)    \
    S(accel_mm_s2, F32) S(pwm_limit, I16) S(reserved0, I16) S(cruise_speed_mm_s, F32)                 \
    S(room_speed_mm_s, F32) S(approach_speed_mm_s, F32) S(turn_rate_deg_s, F32)                       \
    S(scan_rate_deg_s, F32) S(wall_target_mm, F32) S(wall_kp_deg_per_mm, F32) S(wall_max_deg, F32)    \
    S(heading_kp, F32) S(wall_align_gain, F32) S(front_stop_mm, F32) S(front_slow_mm, F32)           \
    S(open_mm, F32) S(open_confirm_mm, F32) S(wall_seen_mm, F32) S(hallway_half_mm, F32)              \
    S(turn_tol_deg, F32) S(line_holdoff_mm, F32) S(room_line_max_mm, F32) S(room_entry_mm, F32)       \
    S(room_exit_mm, F32) S(home_advance_mm, F32) S(flame_detect, F32) S(flame_out, F32)               \
    S(flame_steer_deg, F32) S(approach_stop_mm, F32) S(guard_side_mm, F32) S(guard_stop_mm, F32)      \
    S(fan_timeout_ms, U32) S(flame_out_confirm_ms, U32) S(verify_ms, U32) S(fan_attempts, U8)         \
    S(scan_dir, U8) S(route_len, U8) S(home_wall_side, U8)                                            \
    X(route, ffr_step_t, FFR_S_ROUTE_STEP, FFR_ROUTE_MAX) A(return_start, U8, FFR_ROOMS_MAX)         \
    S(start_area, U8) A(reserved1, U8, 3)

/* The compile-time checks: a wrong type code or count in a row above fails the build. */
#define STEP_CHECK(m, code) FFR_CHECK_ROW(ffr_step_t, m, code);
#define CFG_CHECK(m, code) FFR_CHECK_ROW(ffr_config_t, m, code);
#define CFG_CHECK_A(m, code, n) FFR_CHECK_ARRAY(ffr_config_t, m, code, n);
#define CFG_CHECK_X(m, S, sid, n) FFR_CHECK_STRUCTS(ffr_config_t, m, S, n);
STEP_ROWS(STEP_CHECK)
CONFIG_ROWS(CFG_CHECK, CFG_CHECK_A, CFG_CHECK_X)
FFR_STATIC_ASSERT(config_fits, sizeof(ffr_config_t) <= FFR_CONFIG_MAX);
FFR_STATIC_ASSERT(state_fits, sizeof(ffr_state_t) <= FFR_STATE_MAX);

#define STEP_ROW(m, code) FFR_ROW(FFR_S_ROUTE_STEP, ffr_step_t, m, code),
#define CFG_ROW(m, code) FFR_ROW(FFR_S_CONFIG, ffr_config_t, m, code),
#define CFG_ROW_A(m, code, n) FFR_ROW_ARRAY(FFR_S_CONFIG, ffr_config_t, m, code, n),
#define CFG_ROW_X(m, S, sid, n) FFR_ROW_STRUCTS(FFR_S_CONFIG, ffr_config_t, m, sid, n),

static const ffr_field_t k_layout[] = {
    FFR_IO_ROWS,
    STEP_ROWS(STEP_ROW)
    CONFIG_ROWS(CFG_ROW, CFG_ROW_A, CFG_ROW_X)
};

/* Names, index = code. */
static const char *const k_state_names[] = {
    "IDLE", "FOLLOW", "TURN", "FORWARD", "ENTER", "SCAN", "APPROACH", "EXTINGUISH",
    "VERIFY", "TO_DOOR", "EXIT", "HOMING", "DONE", "FAILED", "ORIENT",
};
static const char *const k_fail_names[] = {
    "", "no flame found", "fans did not put the flame out", "doorway line not found", "invalid route program",
    "flame lost",
};
static const char *const k_op_names[] = {"END", "FOLLOW", "TURN", "FORWARD", "ROOM", "HOME"};
static const char *const k_side_names[] = {"LEFT", "RIGHT", "NONE"};
static const char *const k_event_names[] = {"FRONT", "OPEN_L", "OPEN_R", "LINE", "GAP_L", "GAP_R"};

#define COUNT_OF(a) (sizeof(a) / sizeof((a)[0]))
FFR_STATIC_ASSERT(state_names, COUNT_OF(k_state_names) == FFR_ST_COUNT);
FFR_STATIC_ASSERT(fail_names, COUNT_OF(k_fail_names) == FFR_FAIL_LOST_FLAME + 1);
FFR_STATIC_ASSERT(op_names, COUNT_OF(k_op_names) == FFR_OP_HOME + 1);
FFR_STATIC_ASSERT(side_names, COUNT_OF(k_side_names) == FFR_SIDE_NONE + 1);
FFR_STATIC_ASSERT(event_names, COUNT_OF(k_event_names) == FFR_EV_GAP_R + 1);

uint32_t ffr_version(void) { return (FFR_CONTRACT_MAJOR << 16) | FFR_CONTRACT_MINOR; }

const char *ffr_firmware_name(void) { return FFR_FIRMWARE_NAME; }

uint32_t ffr_sizeof(uint32_t struct_id)
{
    switch (struct_id) {
    case FFR_S_INPUTS:
        return (uint32_t)sizeof(ffr_inputs_t);
    case FFR_S_OUTPUTS:
        return (uint32_t)sizeof(ffr_outputs_t);
    case FFR_S_CONFIG:
        return (uint32_t)sizeof(ffr_config_t);
    case FFR_S_ROUTE_STEP:
        return (uint32_t)sizeof(ffr_step_t);
    case FFR_S_STATE:
        return (uint32_t)sizeof(ffr_state_t);
    default:
        return 0u;
    }
}

const ffr_field_t *ffr_layout(uint32_t *count)
{
    if (count != NULL) {
        *count = (uint32_t)COUNT_OF(k_layout);
    }
    return k_layout;
}

const char *const *ffr_names(uint32_t kind, uint32_t *count)
{
    const char *const *t = NULL;
    uint32_t n = 0u;
    switch (kind) {
    case FFR_NAMES_STATE:
        t = k_state_names;
        n = (uint32_t)COUNT_OF(k_state_names);
        break;
    case FFR_NAMES_FAIL:
        t = k_fail_names;
        n = (uint32_t)COUNT_OF(k_fail_names);
        break;
    case FFR_NAMES_OPS:
        t = k_op_names;
        n = (uint32_t)COUNT_OF(k_op_names);
        break;
    case FFR_NAMES_SIDES:
        t = k_side_names;
        n = (uint32_t)COUNT_OF(k_side_names);
        break;
    case FFR_NAMES_EVENTS:
        t = k_event_names;
        n = (uint32_t)COUNT_OF(k_event_names);
        break;
    default:
        break;
    }
    if (count != NULL) {
        *count = n;
    }
    return t;
}

/* The contract's recipe (ffr_contract_hash.h, docs/contract.md). */
uint32_t ffr_layout_hash(void) { return ffr_contract_hash(); }
