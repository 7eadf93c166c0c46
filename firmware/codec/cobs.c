/*
 * COBS (Consistent Overhead Byte Stuffing, Cheshire & Baker 1999): the
 * encoded block has no zero byte, so 0x00 can delimit serial frames and a
 * receiver resynchronises at the next zero after any line noise. Each run of
 * up to 254 non-zero bytes is preceded by a code byte = run length + 1.
 */
#include "ffr_codec.h"

size_t ffr_cobs_encode(const uint8_t *in, size_t len, uint8_t *out, size_t cap)
{
    size_t code_at = 0; /* where the current run's code byte goes */
    size_t o = 1;       /* next byte to write; code_at < o <= cap   */
    uint8_t code = 1;
    size_t i;
    if (cap < 1u || (len > 0u && in == NULL)) {
        return 0;
    }
    for (i = 0; i < len; ++i) {
        if (in[i] == 0u) {
            out[code_at] = code;
            if (o >= cap) {
                return 0;
            }
            code_at = o++;
            code = 1;
            continue;
        }
        if (o >= cap) {
            return 0;
        }
        out[o++] = in[i];
        ++code;
        if (code == 0xFFu) { /* a full run of 254: close it; no zero follows it */
            out[code_at] = code;
            code = 1;
            if (i + 1u == len) {
                return o;
            }
            if (o >= cap) {
                return 0;
            }
            code_at = o++;
        }
    }
    out[code_at] = code;
    return o;
}

int ffr_cobs_decode(const uint8_t *in, size_t len, uint8_t *out, size_t cap, size_t *out_len)
{
    size_t i = 0;
    size_t o = 0;
    *out_len = 0;
    if (len == 0u) {
        return FFR_E_SHORT;
    }
    while (i < len) {
        uint8_t code = in[i];
        size_t run;
        size_t k;
        if (code == 0u) {
            return FFR_E_COBS;
        }
        run = (size_t)code - 1u;
        if (i + 1u + run > len) {
            return FFR_E_COBS; /* the run claims bytes past the end */
        }
        if (o + run > cap) {
            return FFR_E_LONG;
        }
        for (k = 0; k < run; ++k) {
            uint8_t c = in[i + 1u + k];
            if (c == 0u) {
                return FFR_E_COBS;
            }
            out[o++] = c;
        }
        i += 1u + run;
        /* a short run stands for "run, then a zero" unless the block ends */
        if (code != 0xFFu && i < len) {
            if (o >= cap) {
                return FFR_E_LONG;
            }
            out[o++] = 0u;
        }
    }
    *out_len = o;
    return FFR_OK;
}
