/*
 * ffr_contract.h - the firmware contract, version 2 (docs/contract.md).
 *
 * What every firmware that runs in the ffr harness provides, whoever wrote it:
 * the fixed, versioned I/O of one tick (ffr_inputs_t in, ffr_outputs_t out,
 * hardware units), a self-description of its own configuration (a layout
 * table the harness reads to set any field by name), name tables for its
 * states and failure codes, and nine functions. The firmware's configuration
 * and state are its own: here they are incomplete types, each firmware
 * completes `struct ffr_config` and `struct ffr_state` in its own header.
 *
 * Portable C99: no platform headers, no heap, no globals.
 */
#ifndef FFR_CONTRACT_H
#define FFR_CONTRACT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FFR_CONTRACT_MAJOR 2u /* an incompatible change of this header */
#define FFR_CONTRACT_MINOR 0u /* a compatible addition */

/* Limits a board is built for: it holds the configuration and the state in
 * static buffers of these sizes (aligned to 8); the wire's RESET message
 * carries up to FFR_CONFIG_MAX configuration bytes. */
#define FFR_CONFIG_MAX 1024u
#ifndef FFR_STATE_MAX
#define FFR_STATE_MAX 2048u /* chosen: ours is under 2 KB (docs/contract.md); a board may build with -DFFR_STATE_MAX=... */
#endif

/* ------------------------------------------------------------------ */
/* One tick of inputs and outputs (hardware units). Fixed by the contract. */
/* ------------------------------------------------------------------ */

/* IR rangers, in the order of ffr_inputs_t.ir_mv: centre front, left front,
 * right front, left rear, right rear. */
enum { FFR_IR_CF = 0, FFR_IR_LF = 1, FFR_IR_RF = 2, FFR_IR_LR = 3, FFR_IR_RR = 4, FFR_IR_COUNT = 5 };

typedef struct {
    uint32_t t_ms;               /* tick time                                  */
    uint32_t seq;                /* sequence number, echoed in the outputs     */
    int32_t enc[2];              /* cumulative encoder counts, left, right     */
    uint16_t ir_mv[FFR_IR_COUNT];/* GP2D12 outputs, mV                         */
    uint16_t flame[2];           /* flame sensors, ADC counts, left, right     */
    uint8_t line;                /* 1 = white under the line sensor            */
    uint8_t start;               /* 1 = go                                     */
} ffr_inputs_t;

/* ffr_outputs_t.flags. The harness ends a mission on DONE or FAILED. */
#define FFR_FLAG_FLAME_SEEN 0x01u
#define FFR_FLAG_EXTINGUISHED 0x02u
#define FFR_FLAG_IN_ROOM 0x04u
#define FFR_FLAG_DONE 0x08u
#define FFR_FLAG_FAILED 0x10u

typedef struct {
    uint32_t seq;                /* = inputs.seq                               */
    int16_t pwm[2];              /* per mille, left, right                     */
    uint8_t fan;                 /* 1 = fans on                                */
    uint8_t state;               /* index into ffr_names(FFR_NAMES_STATE)      */
    uint8_t room;                /* room being searched (0 = none)             */
    uint8_t rooms_searched;
    uint8_t line_count;          /* white lines crossed                        */
    uint8_t flags;               /* FFR_FLAG_*                                 */
    uint8_t step;                /* route program counter                      */
    uint8_t fail_code;           /* why FAILED (0 = none): ffr_names(FFR_NAMES_FAIL) */
    int16_t odo_x_mm;            /* odometry estimate, start frame             */
    int16_t odo_y_mm;
    int16_t odo_heading_cdeg;
    int16_t reserved;
} ffr_outputs_t;
/* Fields a firmware does not use (room, rooms_searched, line_count, step,
 * odo_*, reserved) it leaves 0. */

/* ------------------------------------------------------------------ */
/* The firmware's own types: completed in the firmware's header.        */
/* ------------------------------------------------------------------ */
typedef struct ffr_config ffr_config_t;
typedef struct ffr_state ffr_state_t;

/* ------------------------------------------------------------------ */
/* Layout self-description                                              */
/* ------------------------------------------------------------------ */

/* Element types of a layout row. A row of type FFR_T_STRUCT_OF(sid) is an
 * array of a firmware-own sub-struct: the low byte of `type` is FFR_T_STRUCT
 * (0), the high byte the sub-struct's id (16..255), whose fields are rows of
 * the same table under that struct id; ffr_sizeof(sid) is its size (the
 * array's stride). */
typedef enum {
    FFR_T_STRUCT = 0,
    FFR_T_U8 = 1,
    FFR_T_I16 = 2,
    FFR_T_U16 = 3,
    FFR_T_I32 = 4,
    FFR_T_U32 = 5,
    FFR_T_F32 = 6
} ffr_type_t;
#define FFR_T_STRUCT_OF(sid) ((uint16_t)((uint16_t)FFR_T_STRUCT | (uint16_t)((uint16_t)(sid) << 8)))
#define FFR_T_BASE(type) ((uint16_t)((type) & 0xFFu))
#define FFR_T_SUBSTRUCT(type) ((uint16_t)((type) >> 8))

/* Struct ids: the fixed I/O, the firmware's configuration, the size of its
 * state (ffr_sizeof only), and its own sub-structs from FFR_S_OWN up. */
enum { FFR_S_INPUTS = 0, FFR_S_OUTPUTS = 1, FFR_S_CONFIG = 2, FFR_S_OWN = 16, FFR_S_STATE = 99 };

typedef struct {
    const char *name;
    uint16_t struct_id; /* FFR_S_*          */
    uint16_t type;      /* ffr_type_t, or FFR_T_STRUCT_OF(sub-struct id) */
    uint16_t offset;
    uint16_t count;     /* array length (1 for scalars) */
} ffr_field_t;

/* Name tables: index = outputs.state, outputs.fail_code. A firmware may add
 * its own kinds from FFR_NAMES_OWN up. */
enum { FFR_NAMES_STATE = 0, FFR_NAMES_FAIL = 1, FFR_NAMES_OWN = 16 };

/* ------------------------------------------------------------------ */
/* What every firmware exports                                          */
/* ------------------------------------------------------------------ */
void ffr_config_default(ffr_config_t *cfg);
void ffr_init(ffr_state_t *st, const ffr_config_t *cfg);
void ffr_step(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out);
uint32_t ffr_version(void);                     /* FFR_CONTRACT_MAJOR << 16 | FFR_CONTRACT_MINOR */
uint32_t ffr_sizeof(uint32_t struct_id);        /* inputs, outputs, config, own sub-structs, 99 = state; 0 unknown */
const ffr_field_t *ffr_layout(uint32_t *count); /* inputs + outputs (fixed) and the config (own) */
const char *const *ffr_names(uint32_t kind, uint32_t *count); /* NULL and 0 for an unknown kind */
const char *ffr_firmware_name(void);            /* e.g. "ffr-reference 1.1" */
uint32_t ffr_layout_hash(void);                 /* FNV-1a over layout, names, firmware name (docs/contract.md) */

/* ------------------------------------------------------------------ */
/* Helpers for writing a layout table that the compiler checks          */
/* ------------------------------------------------------------------ */

/* The C type of each element type, by its short name (U8, I16, ... F32). */
typedef uint8_t ffr_ctype_U8;
typedef int16_t ffr_ctype_I16;
typedef uint16_t ffr_ctype_U16;
typedef int32_t ffr_ctype_I32;
typedef uint32_t ffr_ctype_U32;
typedef float ffr_ctype_F32;

/* Table rows: a scalar, an array of n, an array of n sub-structs. */
#define FFR_ROW(sid, T, m, code) \
    {#m, (uint16_t)(sid), (uint16_t)FFR_T_##code, (uint16_t)offsetof(T, m), 1u}
#define FFR_ROW_ARRAY(sid, T, m, code, n) \
    {#m, (uint16_t)(sid), (uint16_t)FFR_T_##code, (uint16_t)offsetof(T, m), (uint16_t)(n)}
#define FFR_ROW_STRUCTS(sid, T, m, sub_sid, n) \
    {#m, (uint16_t)(sid), FFR_T_STRUCT_OF(sub_sid), (uint16_t)offsetof(T, m), (uint16_t)(n)}

/*
 * Compile-time checks of a row against the member (file scope, one per row).
 * Each assigns the member's address to a pointer of the row's C type inside
 * sizeof (never evaluated): C99 makes an assignment between incompatible
 * pointer types a constraint violation, so a wrong element type (F32 for an
 * int16_t, U8 for a uint32_t), a wrong signedness (U16 for an int16_t,
 * -Wpointer-sign under -Wall/-pedantic), a scalar row for an array, or a
 * wrong array length is refused by the compiler. T must be a typedef name.
 */
#define FFR_CHECK_ROW(T, m, code) \
    typedef char ffr_check_##T##_##m[sizeof(*(ffr_ctype_##code **)0 = &((T *)0)->m)]
#define FFR_CHECK_ARRAY(T, m, code, n) \
    typedef char ffr_check_##T##_##m[sizeof(*(ffr_ctype_##code(**)[n])0 = &((T *)0)->m)]
#define FFR_CHECK_STRUCTS(T, m, S, n) \
    typedef char ffr_check_##T##_##m[sizeof(*(S(**)[n])0 = &((T *)0)->m)]
/* A condition that must hold at compile time (C99: a negative array size). */
#define FFR_STATIC_ASSERT(name, cond) typedef char ffr_static_assert_##name[(cond) ? 1 : -1]

/* The fixed I/O rows, the same in every firmware's table (put them first). */
#define FFR_IO_ROWS                                                         \
    FFR_ROW(FFR_S_INPUTS, ffr_inputs_t, t_ms, U32),                         \
    FFR_ROW(FFR_S_INPUTS, ffr_inputs_t, seq, U32),                          \
    FFR_ROW_ARRAY(FFR_S_INPUTS, ffr_inputs_t, enc, I32, 2),                 \
    FFR_ROW_ARRAY(FFR_S_INPUTS, ffr_inputs_t, ir_mv, U16, FFR_IR_COUNT),    \
    FFR_ROW_ARRAY(FFR_S_INPUTS, ffr_inputs_t, flame, U16, 2),               \
    FFR_ROW(FFR_S_INPUTS, ffr_inputs_t, line, U8),                          \
    FFR_ROW(FFR_S_INPUTS, ffr_inputs_t, start, U8),                         \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, seq, U32),                        \
    FFR_ROW_ARRAY(FFR_S_OUTPUTS, ffr_outputs_t, pwm, I16, 2),               \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, fan, U8),                         \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, state, U8),                       \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, room, U8),                        \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, rooms_searched, U8),              \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, line_count, U8),                  \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, flags, U8),                       \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, step, U8),                        \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, fail_code, U8),                   \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, odo_x_mm, I16),                   \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, odo_y_mm, I16),                   \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, odo_heading_cdeg, I16),           \
    FFR_ROW(FFR_S_OUTPUTS, ffr_outputs_t, reserved, I16)

/* The I/O structs' sizes (32 and 24 bytes) and the I/O rows, checked once here. */
FFR_STATIC_ASSERT(inputs_size, sizeof(ffr_inputs_t) == 32u);
FFR_STATIC_ASSERT(outputs_size, sizeof(ffr_outputs_t) == 24u);
FFR_CHECK_ROW(ffr_inputs_t, t_ms, U32);
FFR_CHECK_ROW(ffr_inputs_t, seq, U32);
FFR_CHECK_ARRAY(ffr_inputs_t, enc, I32, 2);
FFR_CHECK_ARRAY(ffr_inputs_t, ir_mv, U16, FFR_IR_COUNT);
FFR_CHECK_ARRAY(ffr_inputs_t, flame, U16, 2);
FFR_CHECK_ROW(ffr_inputs_t, line, U8);
FFR_CHECK_ROW(ffr_inputs_t, start, U8);
FFR_CHECK_ROW(ffr_outputs_t, seq, U32);
FFR_CHECK_ARRAY(ffr_outputs_t, pwm, I16, 2);
FFR_CHECK_ROW(ffr_outputs_t, fan, U8);
FFR_CHECK_ROW(ffr_outputs_t, state, U8);
FFR_CHECK_ROW(ffr_outputs_t, room, U8);
FFR_CHECK_ROW(ffr_outputs_t, rooms_searched, U8);
FFR_CHECK_ROW(ffr_outputs_t, line_count, U8);
FFR_CHECK_ROW(ffr_outputs_t, flags, U8);
FFR_CHECK_ROW(ffr_outputs_t, step, U8);
FFR_CHECK_ROW(ffr_outputs_t, fail_code, U8);
FFR_CHECK_ROW(ffr_outputs_t, odo_x_mm, I16);
FFR_CHECK_ROW(ffr_outputs_t, odo_y_mm, I16);
FFR_CHECK_ROW(ffr_outputs_t, odo_heading_cdeg, I16);
FFR_CHECK_ROW(ffr_outputs_t, reserved, I16);

#ifdef __cplusplus
}
#endif
#endif /* FFR_CONTRACT_H */
