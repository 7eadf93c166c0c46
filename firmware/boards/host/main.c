/*
 * ffr-host-board: the firmware as a board on the end of a wire, for tests
 * and demos without hardware. It plays the microcontroller: receive a frame,
 * let the shared board link (handshake, reset, lockstep, watchdog) answer it
 * with the real firmware, send the answer back.
 *
 *   ffr-host-board [--pty | --tcp PORT | --stdio] [--watchdog-ms N]
 *                  [--step-delay-us N] [--stdin-lifeline] [--connect-timeout-ms N]
 *
 * --stdin-lifeline: exit when standard input closes, i.e. when the process
 * that launched us has gone, so a board never outlives its harness.
 * --connect-timeout-ms: exit if nobody has sent a byte by then. Default 10 s,
 * none with --stdin-lifeline: the launcher is alive, and it may first spend
 * many seconds compiling its plant on a cold cache (seen on a fresh CI clone).
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ffr_codec.h"
#include "ffr_link.h"
#include "transport.h"

typedef struct {
    ffr_board_link_t link;
    ffr_deframer_t rx;
    uint8_t msg[FFR_MSG_MAX + 2u];
    uint8_t reply[FFR_MSG_MAX];
    uint8_t frame[FFR_FRAME_MAX];
    uint8_t chunk[512];
} board_t;

static uint32_t now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint32_t)((uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u);
}

static int send_msg(transport_t *t, board_t *b, size_t len)
{
    size_t n;
    if (len == 0u) {
        return 0;
    }
    n = ffr_frame_encode(b->reply, len, b->frame, sizeof(b->frame));
    return n == 0u ? -1 : transport_write(t, b->frame, n);
}

static long arg_long(const char *name, const char *v, long lo, long hi)
{
    char *end = NULL;
    long x = v != NULL ? strtol(v, &end, 10) : 0;
    if (v == NULL || *v == '\0' || *end != '\0' || x < lo || x > hi) {
        fprintf(stderr, "ffr-host-board: %s = '%s': expected an integer in %ld..%ld\n", name, v ? v : "", lo, hi);
        exit(2);
    }
    return x;
}

static int stdin_closed(void)
{
    struct pollfd p;
    char c;
    p.fd = STDIN_FILENO;
    p.events = POLLIN;
    p.revents = 0;
    if (poll(&p, 1, 0) <= 0) {
        return 0;
    }
    return read(STDIN_FILENO, &c, 1) <= 0;
}

int main(int argc, char **argv)
{
    static board_t b; /* the board's RAM: one instance, like an MCU's */
    transport_t t;
    transport_kind_t kind = TRANSPORT_PTY;
    long port = 0, watchdog = FFR_WATCHDOG_DEFAULT_MS, delay_us = 0, connect_ms = 10000;
    int lifeline = 0, i, rc = 0, connect_given = 0;
    uint32_t started;
    int connected = 0;

    for (i = 1; i < argc; ++i) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--pty") == 0) {
            kind = TRANSPORT_PTY;
        } else if (strcmp(a, "--stdio") == 0) {
            kind = TRANSPORT_STDIO;
        } else if (strcmp(a, "--tcp") == 0) {
            kind = TRANSPORT_TCP;
            port = arg_long(a, v, 0, 65535);
            ++i;
        } else if (strcmp(a, "--watchdog-ms") == 0) {
            watchdog = arg_long(a, v, 0, 65535);
            ++i;
        } else if (strcmp(a, "--step-delay-us") == 0) {
            delay_us = arg_long(a, v, 0, 1000000);
            ++i;
        } else if (strcmp(a, "--connect-timeout-ms") == 0) {
            connect_ms = arg_long(a, v, 1, 3600000);
            connect_given = 1;
            ++i;
        } else if (strcmp(a, "--stdin-lifeline") == 0) {
            lifeline = 1;
        } else {
            fprintf(stderr, "ffr-host-board: unknown option '%s'\n", a);
            return 2;
        }
    }
    if (lifeline && kind == TRANSPORT_STDIO) {
        fprintf(stderr, "ffr-host-board: --stdin-lifeline needs --pty or --tcp\n");
        return 2;
    }
    signal(SIGPIPE, SIG_IGN);
    ffr_board_link_init(&b.link, (uint32_t)watchdog, now_ms());
    ffr_deframer_init(&b.rx);
    if (transport_open(&t, kind, (int)port) != 0) {
        return 1;
    }
    started = now_ms();
    for (;;) {
        long n = transport_read(&t, b.chunk, sizeof(b.chunk), 5);
        long k;
        if (n < 0) {
            fprintf(stderr, "ffr-host-board: the host closed the line\n");
            break;
        }
        if (n > 0) {
            connected = 1;
        } else if (!connected && (!lifeline || connect_given) &&
                   (uint32_t)(now_ms() - started) > (uint32_t)connect_ms) {
            fprintf(stderr, "ffr-host-board: nobody connected within %ld ms\n", connect_ms);
            rc = 1;
            break;
        }
        if (lifeline && stdin_closed()) {
            fprintf(stderr, "ffr-host-board: launcher gone (stdin closed)\n");
            break;
        }
        for (k = 0; k < n; ++k) {
            const uint8_t *f = NULL;
            size_t flen = 0, mlen = 0, rlen;
            int got = ffr_deframer_push(&b.rx, b.chunk[k], &f, &flen);
            if (got == 0) {
                continue;
            }
            if (got < 0) {
                rlen = ffr_board_link_on_bad_frame(&b.link, got, b.reply, sizeof(b.reply));
            } else {
                int st = ffr_frame_decode(f, flen, b.msg, sizeof(b.msg), &mlen);
                if (st != FFR_OK) {
                    rlen = ffr_board_link_on_bad_frame(&b.link, st, b.reply, sizeof(b.reply));
                } else {
                    rlen = ffr_board_link_on_msg(&b.link, b.msg, mlen, now_ms(), b.reply, sizeof(b.reply));
                    if (delay_us > 0 && b.msg[0] == FFR_MSG_INPUTS) { /* a slow board */
                        struct timespec d;
                        d.tv_sec = delay_us / 1000000L;
                        d.tv_nsec = (delay_us % 1000000L) * 1000L;
                        nanosleep(&d, NULL);
                    }
                }
            }
            if (send_msg(&t, &b, rlen) != 0) {
                fprintf(stderr, "ffr-host-board: write failed: %s\n", strerror(errno));
                rc = 1;
                goto out;
            }
        }
        {
            size_t rlen = ffr_board_link_poll(&b.link, now_ms(), b.reply, sizeof(b.reply));
            if (rlen > 0u) {
                fprintf(stderr, "ffr-host-board: watchdog: no inputs for %lu ms after seq %lu: motors and fans "
                                "stopped\n",
                        (unsigned long)b.link.watchdog_ms, (unsigned long)b.link.last_out.seq);
                if (send_msg(&t, &b, rlen) != 0) {
                    break;
                }
            }
        }
    }
out:
    fprintf(stderr, "ffr-host-board: exit; received %lu, sent %lu, errors %lu, repeats %lu, watchdog trips %lu\n",
            (unsigned long)b.link.rx_msgs, (unsigned long)b.link.tx_msgs, (unsigned long)b.link.rx_errors,
            (unsigned long)b.link.repeats, (unsigned long)b.link.watchdog_trips);
    transport_close(&t);
    return rc;
}
