/*
 * ffr_codec.h - the wire codec of the firmware link (docs/protocol.md).
 *
 * Pure buffer in, buffer out: no I/O, no heap, no globals, C99. Every board
 * (the host board program, the CAN board, a Cortex-M board) uses this one
 * codec; hil_bridge/codec.py is its Python twin, checked against it by shared
 * test vectors and round trips in both directions.
 *
 * Layers, bottom up:
 *   CRC-16/IBM-3740 (a.k.a. CCITT-FALSE)       ffr_crc16
 *   struct <-> wire bytes (layout order, LE)  ffr_wire_encode / ffr_wire_decode
 *   message = type byte + fixed-size body     ffr_msg_encode / ffr_msg_decode
 *   serial frame = COBS(msg + CRC) + 0x00     ffr_frame_encode / ffr_frame_decode / ffr_deframer_push
 *   CAN frames = (msg body + CRC) in 8 or 64 byte segments, id = type<<7 | segment
 */
#ifndef FFR_CODEC_H
#define FFR_CODEC_H

#include <stddef.h>
#include <stdint.h>

#include "ffr_contract.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FFR_PROTO_VERSION 1u

/* Message types. On CAN the type is the top bits of the identifier, so a
 * lower type wins arbitration: errors first, then the lockstep frames. */
typedef enum {
    FFR_MSG_ERROR = 1,   /* board -> host: something went wrong          */
    FFR_MSG_OUTPUTS = 2, /* board -> host: ffr_outputs_t of one tick     */
    FFR_MSG_INPUTS = 3,  /* host -> board: ffr_inputs_t of one tick      */
    FFR_MSG_INFO = 4,    /* board -> host: handshake answer              */
    FFR_MSG_HELLO = 5,   /* host -> board: handshake                     */
    FFR_MSG_READY = 6,   /* board -> host: reset done                    */
    FFR_MSG_RESET = 7    /* host -> board: the firmware's config, restart */
} ffr_msg_type_t;

/* Error codes in FFR_MSG_ERROR. */
typedef enum {
    FFR_ERR_NONE = 0,
    FFR_ERR_CRC = 1,      /* frame failed its CRC                        */
    FFR_ERR_FRAMING = 2,  /* COBS invalid, frame too long or too short   */
    FFR_ERR_LENGTH = 3,   /* body length wrong for the message type      */
    FFR_ERR_TYPE = 4,     /* unknown or unexpected message type          */
    FFR_ERR_NOT_READY = 5,/* inputs before a reset                       */
    FFR_ERR_SEQUENCE = 6, /* inputs neither the last nor the next seq    */
    FFR_ERR_PROTO = 7,    /* protocol version not supported              */
    FFR_ERR_WATCHDOG = 8, /* inputs stopped: motors and fans stopped     */
    FFR_ERR_SEGMENT = 9   /* CAN segment out of order or unknown id      */
} ffr_err_code_t;

/* Decoder status (0 = ok). The same names exist in hil_bridge/codec.py. */
typedef enum {
    FFR_OK = 0,
    FFR_E_SHORT = -1,   /* too few bytes                                  */
    FFR_E_LONG = -2,    /* too many bytes / buffer too small              */
    FFR_E_COBS = -3,    /* not valid COBS                                 */
    FFR_E_CRC = -4,     /* CRC mismatch                                   */
    FFR_E_TYPE = -5,    /* unknown message type                           */
    FFR_E_LENGTH = -6,  /* body length wrong for the type                 */
    FFR_E_SEGMENT = -7  /* CAN: unknown id, segment out of order, bad DLC */
} ffr_status_t;

typedef struct {
    uint16_t proto;       /* FFR_PROTO_VERSION                              */
    uint16_t watchdog_ms; /* link watchdog the board should use (0: its own) */
} ffr_hello_t;

typedef struct {
    uint16_t proto;
    uint16_t watchdog_ms;  /* the watchdog in force                         */
    uint32_t fw_version;   /* ffr_version()                                 */
    uint32_t layout_hash;  /* ffr_layout_hash()                             */
    uint16_t inputs_size;  /* wire sizes of the three structs               */
    uint16_t outputs_size;
    uint16_t config_size;
    uint16_t reserved;
} ffr_info_t;

typedef struct {
    uint16_t config_crc;   /* CRC-16 of the configuration bytes received    */
    uint16_t reserved;
} ffr_ready_t;

typedef struct {
    uint8_t code;          /* ffr_err_code_t                                */
    uint8_t detail;        /* code-specific (e.g. the offending type)       */
    uint16_t reserved;
    uint32_t seq;          /* the sequence number concerned (or last seen)  */
} ffr_error_t;

typedef struct {
    uint8_t type; /* ffr_msg_type_t */
    union {
        ffr_hello_t hello;
        ffr_info_t info;
        ffr_ready_t ready;
        ffr_error_t error;
        ffr_inputs_t inputs;
        ffr_outputs_t outputs;
        /* the firmware's own ffr_config_t (any contract firmware's: at most
         * FFR_CONFIG_MAX bytes), 8-aligned; FFR_MSG_CONFIG(m) is it, typed */
        uint64_t config[FFR_CONFIG_MAX / 8u];
    } u;
} ffr_msg_t;
#define FFR_MSG_CONFIG(m) ((ffr_config_t *)(void *)(m)->u.config)

/* Wire body sizes (fixed per type). */
#define FFR_HELLO_SIZE 4u
#define FFR_INFO_SIZE 20u
#define FFR_READY_SIZE 4u
#define FFR_ERROR_SIZE 8u
/* Upper bounds: a message is at most the type byte and a config of the
 * contract's largest (FFR_CONFIG_MAX: any firmware's RESET fits); a serial
 * frame adds the CRC, COBS overhead (one byte per 254) and the delimiter. */
#define FFR_MSG_MAX (1u + FFR_CONFIG_MAX)
#define FFR_FRAME_MAX (FFR_MSG_MAX + 2u + (FFR_MSG_MAX + 2u) / 254u + 2u)

/* CRC-16/IBM-3740: poly 0x1021, init 0xFFFF, no reflection, xorout 0; check("123456789") = 0x29B1. */
uint16_t ffr_crc16(const uint8_t *data, size_t len);
uint16_t ffr_crc16_update(uint16_t crc, const uint8_t *data, size_t len);

/* Struct <-> wire: every field of struct_id (FFR_S_*) in layout-table order,
 * little-endian, no padding. Returns the bytes written/read, 0 on error. */
size_t ffr_wire_size(uint32_t struct_id);
size_t ffr_wire_encode(uint32_t struct_id, const void *s, uint8_t *buf, size_t cap);
size_t ffr_wire_decode(uint32_t struct_id, const uint8_t *buf, size_t len, void *s);

/* Body size of a message type, 0 for an unknown type. */
size_t ffr_msg_body_size(uint8_t type);
/* Message -> bytes (type + body). Returns the length, 0 on error. */
size_t ffr_msg_encode(const ffr_msg_t *m, uint8_t *buf, size_t cap);
/* Bytes -> message. FFR_OK or FFR_E_SHORT/TYPE/LENGTH. */
int ffr_msg_decode(const uint8_t *buf, size_t len, ffr_msg_t *m);

/* COBS (Cheshire & Baker): no zero byte in the output. Return the length, 0 on error. */
size_t ffr_cobs_encode(const uint8_t *in, size_t len, uint8_t *out, size_t cap);
int ffr_cobs_decode(const uint8_t *in, size_t len, uint8_t *out, size_t cap, size_t *out_len);

/* Serial frame: COBS(msg || crc16 big-endian) || 0x00. Returns the length, 0 on error. */
size_t ffr_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap);
/* One frame without its delimiter -> msg bytes (msg needs room for msg + 2 CRC bytes,
 * FFR_MSG_MAX + 2 for any frame). FFR_OK or FFR_E_*. */
int ffr_frame_decode(const uint8_t *frame, size_t len, uint8_t *msg, size_t cap, size_t *msg_len);

/* Byte-at-a-time receiver (a UART interrupt's view of the stream). */
typedef struct {
    uint8_t buf[FFR_FRAME_MAX];
    uint16_t len;
    uint8_t overflow; /* a frame longer than FFR_FRAME_MAX is being dropped */
    uint8_t reserved;
} ffr_deframer_t;

void ffr_deframer_init(ffr_deframer_t *d);
/* Push one byte. Returns 1 when a delimiter ends a non-empty frame (then
 * frame and len give it, without the delimiter, valid until the next push),
 * FFR_E_LONG when an over-long frame ended, 0 otherwise. */
int ffr_deframer_push(ffr_deframer_t *d, uint8_t byte, const uint8_t **frame, size_t *len);

/* CAN: identifier of a segment; FD frames set FFR_CAN_FD_BIT so that one DBC
 * describes both kinds without a clash. 11-bit standard identifiers. */
#define FFR_CAN_FD_BIT 0x400u
#define FFR_CAN_SEG_BITS 7u
#define FFR_CAN_SEG_MAX 128u
uint32_t ffr_can_id(uint8_t type, uint32_t segment, int fd);
/* Number of CAN frames for a message of this type (classic: 8 bytes, FD: 64). */
uint32_t ffr_can_frame_count(uint8_t type, int fd);
/* Frame `index` of msg (type + body): its id, data (up to 64 bytes, FD
 * frames padded with zeros to a valid FD length) and length. Returns 1 if the
 * frame exists, 0 past the last one, FFR_E_* on a bad message. */
int ffr_can_frame(const uint8_t *msg, size_t len, int fd, uint32_t index, uint32_t *id, uint8_t data[64],
                  uint8_t *dlen);

typedef struct {
    uint8_t buf[FFR_MSG_MAX + 2u + 64u]; /* type + body + crc (+ FD padding) */
    uint16_t have;                       /* bytes collected                  */
    uint8_t type;                        /* 0 = idle                         */
    uint8_t next;                        /* next segment expected            */
} ffr_can_rx_t;

void ffr_can_rx_init(ffr_can_rx_t *r);
size_t ffr_can_rx_sizeof(void); /* for hosts that allocate it from outside C */
/* Push one received CAN frame. Returns 1 when a message is complete and its
 * CRC holds (msg/msg_len = type + body), 0 when more segments are needed,
 * FFR_E_SEGMENT/LENGTH/CRC on a bad frame (the partial message is dropped).
 * Later segments of a dropped message are ignored (0), so one loss gives one
 * error report, not one per remaining segment. */
int ffr_can_rx_push(ffr_can_rx_t *r, uint32_t id, const uint8_t *data, uint8_t dlen, uint8_t *msg, size_t cap,
                    size_t *msg_len);

#ifdef __cplusplus
}
#endif
#endif /* FFR_CODEC_H */
