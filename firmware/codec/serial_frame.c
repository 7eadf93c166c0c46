/*
 * Serial framing: COBS(message || CRC-16 big-endian) || 0x00. The CRC goes
 * big-endian so that the CRC over message and CRC together is zero (the
 * residue of a non-reflected CRC with xorout 0), which is how it is checked.
 */
#include "ffr_codec.h"

size_t ffr_frame_encode(const uint8_t *msg, size_t len, uint8_t *out, size_t cap)
{
    /* COBS works on contiguous input: stage message + CRC in the output's
     * tail, which the encoder (never ahead of its input) overwrites safely. */
    uint16_t crc;
    size_t need = len + 2u + (len + 2u) / 254u + 2u;
    size_t at;
    size_t n;
    size_t i;
    if (msg == NULL || len == 0u || len > FFR_MSG_MAX || cap < need) {
        return 0u;
    }
    at = cap - (len + 2u);
    for (i = len; i > 0u; --i) { /* backwards: msg may overlap out */
        out[at + i - 1u] = msg[i - 1u];
    }
    crc = ffr_crc16(out + at, len);
    out[at + len] = (uint8_t)(crc >> 8);
    out[at + len + 1u] = (uint8_t)crc;
    n = ffr_cobs_encode(out + at, len + 2u, out, cap - 1u);
    if (n == 0u) {
        return 0u;
    }
    out[n] = 0u;
    return n + 1u;
}

int ffr_frame_decode(const uint8_t *frame, size_t len, uint8_t *msg, size_t cap, size_t *msg_len)
{
    size_t n = 0;
    int st;
    *msg_len = 0;
    if (len < 4u) { /* code byte + type + CRC at the least */
        return FFR_E_SHORT;
    }
    if (len > FFR_FRAME_MAX) {
        return FFR_E_LONG;
    }
    st = ffr_cobs_decode(frame, len, msg, cap, &n);
    if (st != FFR_OK) {
        return st;
    }
    if (n < 3u) {
        return FFR_E_SHORT;
    }
    if (ffr_crc16(msg, n) != 0u) {
        return FFR_E_CRC;
    }
    *msg_len = n - 2u;
    return FFR_OK;
}

void ffr_deframer_init(ffr_deframer_t *d)
{
    d->len = 0;
    d->overflow = 0;
    d->reserved = 0;
}

int ffr_deframer_push(ffr_deframer_t *d, uint8_t byte, const uint8_t **frame, size_t *len)
{
    if (byte == 0u) {
        size_t n = d->len;
        int over = d->overflow;
        d->len = 0;
        d->overflow = 0;
        if (over) {
            return FFR_E_LONG;
        }
        if (n == 0u) {
            return 0; /* back-to-back delimiters: idle line */
        }
        *frame = d->buf;
        *len = n;
        return 1;
    }
    if (d->len >= sizeof(d->buf)) {
        d->overflow = 1;
    } else {
        d->buf[d->len++] = byte;
    }
    return 0;
}
