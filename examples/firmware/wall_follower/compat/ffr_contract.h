/*
 * compat/ffr_contract.h - a provisional copy of the firmware contract,
 * version 2, written from its specification while ffr's own header
 * (firmware/include/ffr_contract.h) was being written. The Makefile puts
 * ffr's include directory first, so once ffr ships the header this copy is
 * never read; delete this directory then.
 */
#ifndef FFR_CONTRACT_H
#define FFR_CONTRACT_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FFR_CONTRACT_MAJOR 2u
#define FFR_CONTRACT_MINOR 0u

enum { FFR_IR_CF = 0, FFR_IR_LF = 1, FFR_IR_RF = 2, FFR_IR_LR = 3, FFR_IR_RR = 4, FFR_IR_COUNT = 5 };

typedef struct {
    uint32_t t_ms;
    uint32_t seq;
    int32_t enc[2];
    uint16_t ir_mv[FFR_IR_COUNT];
    uint16_t flame[2];
    uint8_t line;
    uint8_t start;
} ffr_inputs_t;

#define FFR_FLAG_FLAME_SEEN 0x01u
#define FFR_FLAG_EXTINGUISHED 0x02u
#define FFR_FLAG_IN_ROOM 0x04u
#define FFR_FLAG_DONE 0x08u
#define FFR_FLAG_FAILED 0x10u

typedef struct {
    uint32_t seq;
    int16_t pwm[2];
    uint8_t fan;
    uint8_t state;
    uint8_t room;
    uint8_t rooms_searched;
    uint8_t line_count;
    uint8_t flags;
    uint8_t step;
    uint8_t fail_code;
    int16_t odo_x_mm;
    int16_t odo_y_mm;
    int16_t odo_heading_cdeg;
    int16_t reserved;
} ffr_outputs_t;

typedef struct ffr_config ffr_config_t;
typedef struct ffr_state ffr_state_t;

typedef enum {
    FFR_T_STRUCT = 0, FFR_T_U8 = 1, FFR_T_I16 = 2, FFR_T_U16 = 3, FFR_T_I32 = 4, FFR_T_U32 = 5, FFR_T_F32 = 6
} ffr_type_t;
enum { FFR_S_INPUTS = 0, FFR_S_OUTPUTS = 1, FFR_S_CONFIG = 2, FFR_S_STATE = 99 };

typedef struct {
    const char *name;
    uint16_t struct_id;
    uint16_t type;
    uint16_t offset;
    uint16_t count;
} ffr_field_t;

enum { FFR_NAMES_STATE = 0, FFR_NAMES_FAIL = 1 };

#define FFR_CONFIG_MAX 1024u

void ffr_config_default(ffr_config_t *cfg);
void ffr_init(ffr_state_t *st, const ffr_config_t *cfg);
void ffr_step(ffr_state_t *st, const ffr_inputs_t *in, ffr_outputs_t *out);
uint32_t ffr_version(void);
uint32_t ffr_sizeof(uint32_t struct_id);
const ffr_field_t *ffr_layout(uint32_t *count);
const char *const *ffr_names(uint32_t kind, uint32_t *count);
const char *ffr_firmware_name(void);
uint32_t ffr_layout_hash(void);

#ifdef __cplusplus
}
#endif
#endif /* FFR_CONTRACT_H */
