/*
 * ffr_link.h - the board side of the firmware link (docs/protocol.md):
 * handshake, reset with configuration, lockstep steps answered once per
 * sequence number (a repeated request gets the same answer again, the
 * firmware is not stepped twice), error reports, and the link watchdog.
 *
 * It carries any firmware that meets the contract (ffr_contract.h): the
 * firmware's state and configuration live in buffers of FFR_STATE_MAX and
 * FFR_CONFIG_MAX bytes; a firmware whose state is larger is refused at RESET.
 *
 * Portable like the firmware: no I/O, no heap, no globals. A board's
 * transport (UART, CAN, a pty on the host) feeds it decoded messages and the
 * board clock, and sends what it returns; every board shares this code.
 */
#ifndef FFR_LINK_H
#define FFR_LINK_H

#include "ffr_codec.h"
#include "ffr_contract.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FFR_WATCHDOG_DEFAULT_MS 500u

typedef struct {
    uint64_t fw[FFR_STATE_MAX / 8u]; /* the firmware's ffr_state_t (any contract firmware's), 8-aligned */
    ffr_msg_t msg;            /* scratch for decoding and replies (a config is big: not on the stack) */
    ffr_outputs_t last_out;   /* the answer to the last sequence number, for repeats */
    uint32_t last_rx_ms;      /* board clock at the last valid inputs  */
    uint32_t watchdog_ms;     /* 0 = off                               */
    uint32_t rx_msgs;         /* counters                              */
    uint32_t tx_msgs;
    uint32_t rx_errors;
    uint32_t repeats;         /* inputs answered again from last_out  */
    uint32_t watchdog_trips;
    int16_t pwm[2];           /* what the board drives its motors with */
    uint8_t fan;              /* and its fans                          */
    uint8_t configured;       /* a reset has been received             */
    uint8_t have_out;         /* last_out is valid; the watchdog is armed */
    uint8_t tripped;          /* the watchdog stopped the actuators    */
    uint8_t reserved[2];
    /* Optional profile of ffr_step: a board that has a free-running up-counter
     * (24 bits are enough) sets step_clock; the link reads it around every step. */
    uint32_t (*step_clock)(void);
    uint32_t prof_steps;
    uint32_t prof_sum;        /* counts, all steps */
    uint32_t prof_max;        /* counts, the slowest step */
} ffr_board_link_t;

void ffr_board_link_init(ffr_board_link_t *b, uint32_t watchdog_ms, uint32_t now_ms);
/* A received message (type + body, its CRC already checked). The reply (type
 * + body) goes to `reply`; returns its length, 0 when there is none. */
size_t ffr_board_link_on_msg(ffr_board_link_t *b, const uint8_t *msg, size_t len, uint32_t now_ms, uint8_t *reply,
                             size_t cap);
/* A frame that failed to decode (its FFR_E_* status): the error report to send. */
size_t ffr_board_link_on_bad_frame(ffr_board_link_t *b, int status, uint8_t *reply, size_t cap);
/* Call often: the link watchdog. When inputs have been silent for longer
 * than watchdog_ms, motors and fans stop and an error report is returned
 * (once); the next valid inputs re-arm it. */
size_t ffr_board_link_poll(ffr_board_link_t *b, uint32_t now_ms, uint8_t *reply, size_t cap);
/* The actuator commands in force (what a board writes to its PWM and fan pins). */
void ffr_board_link_actuators(const ffr_board_link_t *b, int16_t pwm[2], uint8_t *fan);
/* sizeof(ffr_board_link_t), for hosts that allocate it from outside C (ctypes). */
size_t ffr_board_link_sizeof(void);

#ifdef __cplusplus
}
#endif
#endif /* FFR_LINK_H */
