/*
 * libFuzzer target: everything a board does with bytes it did not choose.
 * The input is split in two: the first half is a serial byte stream (the
 * deframer, COBS, CRC, message decoding, then the board link answering with
 * the real firmware), the second a sequence of CAN frames (id, length, data)
 * for the reassembler. Every decoded message must encode back to the same
 * bytes. ASan and UBSan watch for the rest.
 *
 *   make fuzz FUZZ_SECONDS=60
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ffr.h"
#include "ffr_codec.h"
#include "ffr_link.h"

static ffr_board_link_t g_link;
static ffr_deframer_t g_rx;
static ffr_can_rx_t g_can;
static ffr_msg_t g_msg;
static uint8_t g_buf[FFR_MSG_MAX + 2u], g_again[FFR_MSG_MAX], g_reply[FFR_MSG_MAX];

static void check_roundtrip(const uint8_t *msg, size_t len)
{
    if (ffr_msg_decode(msg, len, &g_msg) == FFR_OK) {
        size_t n = ffr_msg_encode(&g_msg, g_again, sizeof(g_again));
        if (n != len || memcmp(g_again, msg, len) != 0) {
            abort(); /* a message that does not survive decode + encode */
        }
    }
}

static void serve(const uint8_t *msg, size_t len, uint32_t now)
{
    check_roundtrip(msg, len);
    if (len > 0u && msg[0] == FFR_MSG_RESET) {
        return; /* a fuzzed configuration is the firmware's business, not the decoder's */
    }
    (void)ffr_board_link_on_msg(&g_link, msg, len, now, g_reply, sizeof(g_reply));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t half = size / 2u, i;
    uint32_t now = 0;
    ffr_board_link_init(&g_link, 100u, 0u);
    /* a board that has been reset with the default configuration */
    memset(&g_msg, 0, sizeof(g_msg));
    g_msg.type = FFR_MSG_RESET;
    ffr_config_default(FFR_MSG_CONFIG(&g_msg));
    i = ffr_msg_encode(&g_msg, g_buf, sizeof(g_buf));
    (void)ffr_board_link_on_msg(&g_link, g_buf, i, now, g_reply, sizeof(g_reply));
    ffr_deframer_init(&g_rx);
    ffr_can_rx_init(&g_can);

    for (i = 0; i < half; ++i) {
        const uint8_t *f = NULL;
        size_t flen = 0, mlen = 0;
        int got = ffr_deframer_push(&g_rx, data[i], &f, &flen);
        now += 3u;
        if (got < 0) {
            (void)ffr_board_link_on_bad_frame(&g_link, got, g_reply, sizeof(g_reply));
        } else if (got > 0) {
            int st = ffr_frame_decode(f, flen, g_buf, sizeof(g_buf), &mlen);
            if (st == FFR_OK) {
                serve(g_buf, mlen, now);
            } else {
                (void)ffr_board_link_on_bad_frame(&g_link, st, g_reply, sizeof(g_reply));
            }
        }
        (void)ffr_board_link_poll(&g_link, now, g_reply, sizeof(g_reply));
    }
    /* CAN: [id lo, id hi, dlen, data...] repeated */
    i = half;
    while (i + 3u <= size) {
        uint32_t id = (uint32_t)data[i] | ((uint32_t)data[i + 1u] << 8);
        uint8_t dlen = (uint8_t)(data[i + 2u] % 65u);
        size_t mlen = 0;
        int r;
        i += 3u;
        if (i + dlen > size) {
            break;
        }
        r = ffr_can_rx_push(&g_can, id, data + i, dlen, g_buf, sizeof(g_buf), &mlen);
        if (r == 1) {
            serve(g_buf, mlen, now);
        }
        i += dlen;
    }
    return 0;
}
