/* The board's main loop, shared by every microcontroller board: frames in on
 * the link UART (or a frame transport) -> deframer -> shared board link (firmware/link/board_link.c:
 * handshake, reset, lockstep, watchdog) -> frame back; sleep between frames.
 * A board supplies its start-up, UART, millisecond clock and idle (board.h)
 * and these hooks. */
#ifndef FFR_BOARD_LOOP_H
#define FFR_BOARD_LOOP_H
#include <stdint.h>

typedef struct {
    /* a free-running counter read around every ffr_step (the profile) */
    uint32_t (*step_clock)(void);
    /* where the "ffr-board ready" line and the profile go; 0: nowhere (a bare
     * board without a log channel) */
    void (*log_puts)(const char *s);
    /* a second transport that moves whole frames (QEMU's Ethernet on the mps2-an386), 0: none.
     * frame_recv: the next datagram's payload (one serial frame with its delimiter; anything
     * after the delimiter, e.g. padding, is ignored) into buf, its length, 0 when none waits;
     * frame_send: one serial frame out as one datagram. An answer goes back on the transport
     * its request came in on. */
    uint32_t (*frame_recv)(uint8_t *buf, uint32_t cap);
    void (*frame_send)(const uint8_t *frame, uint32_t n);
} board_loop_hooks_t;

/* Never returns. Call once the UART, the millisecond clock and the step clock run. */
void board_loop_run(const board_loop_hooks_t *hooks);
#endif
