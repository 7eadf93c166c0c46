/* The board's main loop (board_loop.h), the same on every microcontroller. */
#include "board_loop.h"

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

static void send(board_t *b, size_t len)
{
    size_t n;
    if (len == 0u) {
        return;
    }
    n = ffr_frame_encode(b->reply, len, b->frame, sizeof(b->frame));
    uart_write(b->frame, (uint32_t)n);
}

static char *put_str(char *p, const char *s)
{
    while (*s != '\0') {
        *p++ = *s++;
    }
    return p;
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

/* "ffr-profile steps=N sum=S max=M overruns=O": what hil_bridge/qemu_board.py reads */
static void report_profile(const ffr_board_link_t *l, void (*log_puts)(const char *s))
{
    char line[96];
    char *p = put_str(line, "ffr-profile steps=");
    p = put_u32(p, l->prof_steps);
    p = put_str(p, " sum=");
    p = put_u32(p, l->prof_sum);
    p = put_str(p, " max=");
    p = put_u32(p, l->prof_max);
    p = put_str(p, " overruns=");
    p = put_u32(p, uart_rx_overruns());
    *p++ = '\n';
    *p = '\0';
    log_puts(line);
}

void board_loop_run(const board_loop_hooks_t *hooks)
{
    board_t *b = &g_board;
    uint32_t reported = 0u;
    ffr_board_link_init(&b->link, FFR_WATCHDOG_DEFAULT_MS, board_millis());
    b->link.step_clock = hooks->step_clock;
    ffr_deframer_init(&b->rx);
    /* the link's UART now listens: a host may wait for this line before its first frame
     * (some UARTs drop what arrives before they are enabled) */
    if (hooks->log_puts != 0) {
        hooks->log_puts("ffr-board ready\n");
    }
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
        if (hooks->log_puts != 0 && b->link.prof_steps - reported >= PROFILE_EVERY) {
            reported = b->link.prof_steps;
            report_profile(&b->link, hooks->log_puts);
        }
        board_idle();
    }
}
