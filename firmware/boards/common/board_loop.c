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
    /* the frame going out; also a frame transport's datagram coming in, which is decoded into
     * msg before the reply is framed here */
    uint8_t frame[FFR_FRAME_MAX];
} board_t;

static board_t g_board; /* the board's RAM */

/* the reply (len bytes in b->reply, 0: none) as a frame, on the UART or the frame transport */
static void send(board_t *b, size_t len, void (*frame_send)(const uint8_t *frame, uint32_t n))
{
    size_t n;
    if (len == 0u) {
        return;
    }
    n = ffr_frame_encode(b->reply, len, b->frame, sizeof(b->frame));
    if (frame_send != 0) {
        frame_send(b->frame, (uint32_t)n);
    } else {
        uart_write(b->frame, (uint32_t)n);
    }
}

/* One received frame (got: 1, or the deframer's error) -> the reply's length */
static size_t on_frame(board_t *b, int got, const uint8_t *f, size_t flen)
{
    size_t mlen = 0;
    int st;
    if (got < 0) {
        return ffr_board_link_on_bad_frame(&b->link, got, b->reply, sizeof(b->reply));
    }
    st = ffr_frame_decode(f, flen, b->msg, sizeof(b->msg), &mlen);
    return st != FFR_OK ? ffr_board_link_on_bad_frame(&b->link, st, b->reply, sizeof(b->reply))
                        : ffr_board_link_on_msg(&b->link, b->msg, mlen, board_millis(), b->reply, sizeof(b->reply));
}

/* A datagram holds one whole frame: up to its delimiter (none: a damaged datagram) */
static size_t on_datagram(board_t *b, uint32_t n)
{
    uint32_t end = 0u;
    while (end < n && b->frame[end] != 0u) {
        ++end;
    }
    if (end == 0u || end == n) {
        return ffr_board_link_on_bad_frame(&b->link, end == 0u ? FFR_E_SHORT : FFR_E_COBS, b->reply,
                                           sizeof(b->reply));
    }
    return on_frame(b, 1, b->frame, end);
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
    void (*via)(const uint8_t *frame, uint32_t n) = 0; /* the last request's transport, 0: the UART */
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
        uint32_t n;
        while ((c = uart_getc()) >= 0) {
            const uint8_t *f = 0;
            size_t flen = 0;
            int got = ffr_deframer_push(&b->rx, (uint8_t)c, &f, &flen);
            if (got != 0) {
                via = 0;
                send(b, on_frame(b, got, f, flen), via);
            }
        }
        while (hooks->frame_recv != 0 && (n = hooks->frame_recv(b->frame, sizeof(b->frame))) > 0u) {
            via = hooks->frame_send;
            send(b, on_datagram(b, n), via);
        }
        /* the watchdog's report goes where the last request came from */
        send(b, ffr_board_link_poll(&b->link, board_millis(), b->reply, sizeof(b->reply)), via);
        if (hooks->log_puts != 0 && b->link.prof_steps - reported >= PROFILE_EVERY) {
            reported = b->link.prof_steps;
            report_profile(&b->link, hooks->log_puts);
        }
        board_idle();
    }
}
