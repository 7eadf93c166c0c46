/*
 * The firmware as a board on QEMU's mps2-an386 (Cortex-M4): frames arrive on
 * UART0, the shared board link (firmware/link/board_link.c: handshake,
 * reset, lockstep, watchdog) answers them with the real firmware, the answer
 * goes back on UART0. Between frames the CPU sleeps.
 *
 * UART1 carries a profile of ffr_step: timer 0 counts read around every
 * step. Under QEMU with -icount shift=0 each instruction is 1 ns of virtual
 * time and the timer counts the 25 MHz clock, so one count is 40 instructions.
 * (The watchdog's milliseconds come from SysTick's interrupt, in virtual
 * time too: sleeping advances it with the host clock.)
 */
#include "board.h"
#include "ffr_codec.h"
#include "ffr_link.h"

#define PROFILE_EVERY 250u

typedef struct {
    ffr_board_link_t link;
    ffr_deframer_t rx;
    uint8_t msg[FFR_MSG_MAX + 2u];
    uint8_t reply[FFR_MSG_MAX];
    uint8_t frame[FFR_FRAME_MAX];
} board_t;

static board_t g_board; /* the board's RAM */

/* CMSDK APB timer 0: a free-running 32-bit down-counter on the 25 MHz clock,
 * used only to profile ffr_step (SysTick is the millisecond clock; its
 * reload every millisecond would race with the readings). */
#define TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)

static void profile_clock_init(void)
{
    TIMER0_RELOAD = 0xFFFFFFFFu;
    TIMER0_VALUE = 0xFFFFFFFFu;
    TIMER0_CTRL = 1u; /* enable, no interrupt */
}

static uint32_t profile_clock(void) { return 0xFFFFFFFFu - TIMER0_VALUE; }

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
    uart1_puts(line);
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
    uart1_puts("ffr-board ready\n");
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
        if (b->link.prof_steps - reported >= PROFILE_EVERY) {
            reported = b->link.prof_steps;
            report_profile(&b->link);
        }
        board_idle();
    }
}
