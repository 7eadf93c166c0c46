/*
 * The firmware as a board on QEMU's microbit (nRF51822, Cortex-M0, soft
 * float): frames arrive on UART0, the shared board link
 * (firmware/link/board_link.c: handshake, reset, lockstep, watchdog) answers
 * them with the real firmware, the answer goes back on UART0. Between frames
 * the CPU sleeps.
 *
 * The profile of ffr_step goes out by semihosting (the nRF51 has one UART):
 * TIMER0, free-running at 16 MHz, captured around every step. Under QEMU
 * with -icount shift=0 each instruction is 1 ns of virtual time, so one count
 * is 62.5 instructions (on the real chip one count is one CPU cycle).
 * The watchdog's milliseconds come from TIMER1's interrupt, in virtual time
 * too: sleeping advances it with the host clock.
 */
#include "board.h"
#include "ffr_codec.h"
#include "ffr_link.h"

#define PROFILE_EVERY 250u
/* 1: log the profile by semihosting (QEMU -semihosting, or a probe serving it:
 * without one, the bkpt would fault). The image for a bare micro:bit is built
 * with 0 (make build/arm/microbit-hw.elf). */
#ifndef BOARD_PROFILE_LOG
#define BOARD_PROFILE_LOG 1
#endif

typedef struct {
    ffr_board_link_t link;
    ffr_deframer_t rx;
    uint8_t msg[FFR_MSG_MAX + 2u];
    uint8_t reply[FFR_MSG_MAX];
    uint8_t frame[FFR_FRAME_MAX];
} board_t;

static board_t g_board; /* the board's RAM */

/* TIMER0: a free-running 32-bit up-counter at 16 MHz, read by capturing it
 * into CC[0]; used only to profile ffr_step. */
#define TIMER0_START (*(volatile uint32_t *)0x40008000u)
#define TIMER0_CAPTURE0 (*(volatile uint32_t *)0x40008040u)
#define TIMER0_MODE (*(volatile uint32_t *)0x40008504u)
#define TIMER0_BITMODE (*(volatile uint32_t *)0x40008508u)
#define TIMER0_PRESCALER (*(volatile uint32_t *)0x40008510u)
#define TIMER0_CC0 (*(volatile uint32_t *)0x40008540u)

static void profile_clock_init(void)
{
    TIMER0_MODE = 0u;      /* timer */
    TIMER0_BITMODE = 3u;   /* 32 bits */
    TIMER0_PRESCALER = 0u; /* 16 MHz */
    TIMER0_START = 1u;
}

static uint32_t profile_clock(void)
{
    TIMER0_CAPTURE0 = 1u;
    return TIMER0_CC0;
}

static void send(board_t *b, size_t len)
{
    size_t n;
    if (len == 0u) {
        return;
    }
    n = ffr_frame_encode(b->reply, len, b->frame, sizeof(b->frame));
    uart_write(b->frame, (uint32_t)n);
}

static char *put_u32(char *p, uint32_t v)
{
    char tmp[12];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0) {
        *p++ = tmp[--n];
    }
    return p;
}

static void report_profile(const ffr_board_link_t *l)
{
    char line[96];
    char *p = line;
    const char *k1 = "ffr-profile steps=", *k2 = " sum=", *k3 = " max=", *k4 = " overruns=";
    while (*k1 != '\0') {
        *p++ = *k1++;
    }
    p = put_u32(p, l->prof_steps);
    while (*k2 != '\0') {
        *p++ = *k2++;
    }
    p = put_u32(p, l->prof_sum);
    while (*k3 != '\0') {
        *p++ = *k3++;
    }
    p = put_u32(p, l->prof_max);
    while (*k4 != '\0') {
        *p++ = *k4++;
    }
    p = put_u32(p, uart_rx_overruns());
    *p++ = '\n';
    *p = '\0';
    board_log_puts(line);
}

int main(void)
{
    board_t *b = &g_board;
    uint32_t reported = 0u;
    uart_init();
    board_clock_init();
    ffr_board_link_init(&b->link, FFR_WATCHDOG_DEFAULT_MS, board_millis());
    profile_clock_init();
    b->link.step_clock = profile_clock;
    ffr_deframer_init(&b->rx);
    /* the link's UART now listens: a host may wait for this line before its first frame
     * (some UARTs drop what arrives before they are enabled) */
    board_log_puts("ffr-board ready\n");
    for (;;) {
        int c;
        size_t rlen;
        while ((c = uart_getc()) >= 0) {
            const uint8_t *f = 0;
            size_t flen = 0, mlen = 0;
            int got = ffr_deframer_push(&b->rx, (uint8_t)c, &f, &flen);
            if (got == 0) {
                continue;
            }
            if (got < 0) {
                rlen = ffr_board_link_on_bad_frame(&b->link, got, b->reply, sizeof(b->reply));
            } else {
                int st = ffr_frame_decode(f, flen, b->msg, sizeof(b->msg), &mlen);
                rlen = st != FFR_OK ? ffr_board_link_on_bad_frame(&b->link, st, b->reply, sizeof(b->reply))
                                    : ffr_board_link_on_msg(&b->link, b->msg, mlen, board_millis(), b->reply,
                                                            sizeof(b->reply));
            }
            send(b, rlen);
        }
        send(b, ffr_board_link_poll(&b->link, board_millis(), b->reply, sizeof(b->reply)));
        if (BOARD_PROFILE_LOG && b->link.prof_steps - reported >= PROFILE_EVERY) {
            reported = b->link.prof_steps;
            report_profile(&b->link);
        }
        board_idle();
    }
}
