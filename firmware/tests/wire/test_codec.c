#include <string.h>

#include "ffr.h"
#include "ffr_codec.h"
#include "unit.h"
#include "wire_tests.h"

static void test_crc(void)
{
    const uint8_t check[] = "123456789";
    uint8_t with_crc[11];
    uint16_t c = ffr_crc16(check, 9);
    CHECK(c == 0x29B1u);
    memcpy(with_crc, check, 9);
    with_crc[9] = (uint8_t)(c >> 8);
    with_crc[10] = (uint8_t)c;
    CHECK(ffr_crc16(with_crc, 11) == 0u); /* the residue the decoders check */
    CHECK(ffr_crc16(check, 0) == 0xFFFFu);
}

static void cobs_roundtrip(const uint8_t *in, size_t len)
{
    uint8_t enc[700], dec[700];
    size_t n = ffr_cobs_encode(in, len, enc, sizeof(enc)), m = 0, i;
    int zero = 0;
    CHECK(n >= len + 1u && n <= len + 1u + len / 254u + 1u);
    for (i = 0; i < n; ++i) {
        zero |= enc[i] == 0u;
    }
    CHECK(!zero);
    CHECK(ffr_cobs_decode(enc, n, dec, sizeof(dec), &m) == FFR_OK);
    CHECK(m == len && memcmp(in, dec, len) == 0);
}

static void test_cobs(void)
{
    static const uint8_t a[] = {0x00};
    static const uint8_t b[] = {0x11, 0x22, 0x00, 0x33};
    uint8_t enc[16], big[600], out[8];
    size_t i, n, m;
    CHECK(ffr_cobs_encode(a, 1, enc, sizeof(enc)) == 2u && enc[0] == 1u && enc[1] == 1u);
    n = ffr_cobs_encode(b, 4, enc, sizeof(enc));
    CHECK(n == 5u && enc[0] == 3u && enc[1] == 0x11u && enc[3] == 2u && enc[4] == 0x33u);
    for (i = 0; i < sizeof(big); ++i) {
        big[i] = (uint8_t)(i % 7u == 3u ? 0u : i + 1u);
    }
    cobs_roundtrip(big, sizeof(big));
    for (i = 0; i < sizeof(big); ++i) {
        big[i] = (uint8_t)(i % 255u + 1u); /* no zeros: full 254-byte runs */
    }
    cobs_roundtrip(big, 254);
    cobs_roundtrip(big, 255);
    cobs_roundtrip(big, 508);
    cobs_roundtrip(big, 0);
    CHECK(ffr_cobs_encode(big, 254, enc, sizeof(enc)) == 0u); /* too small: refused, not overrun */
    /* malformed: a run longer than the block, a zero inside */
    enc[0] = 5;
    enc[1] = 1;
    CHECK(ffr_cobs_decode(enc, 2, out, sizeof(out), &m) == FFR_E_COBS);
    enc[0] = 3;
    enc[1] = 0;
    enc[2] = 1;
    CHECK(ffr_cobs_decode(enc, 3, out, sizeof(out), &m) == FFR_E_COBS);
}

static void test_wire_struct(void)
{
    ffr_inputs_t in, back;
    ffr_config_t cfg, cfg2;
    uint8_t buf[sizeof(ffr_config_t)];
    memset(&in, 0, sizeof(in));
    in.t_ms = 0x01020304u;
    in.seq = 7u;
    in.enc[0] = -2;
    in.ir_mv[4] = 0xBEEFu;
    in.start = 1u;
    CHECK(ffr_wire_size(FFR_S_INPUTS) == 32u);
    CHECK(ffr_wire_size(FFR_S_OUTPUTS) == 24u);
    CHECK(ffr_wire_size(FFR_S_ROUTE_STEP) == 8u);
    CHECK(ffr_wire_size(FFR_S_CONFIG) <= sizeof(ffr_config_t));
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, sizeof(buf)) == 32u);
    CHECK(buf[0] == 0x04u && buf[3] == 0x01u && buf[4] == 7u); /* little-endian */
    CHECK(buf[8] == 0xFEu && buf[11] == 0xFFu);
    CHECK(buf[24] == 0xEFu && buf[25] == 0xBEu && buf[31] == 1u);
    memset(&back, 0xA5, sizeof(back));
    CHECK(ffr_wire_decode(FFR_S_INPUTS, buf, 32, &back) == 32u);
    CHECK(memcmp(&in, &back, sizeof(in)) == 0);
    CHECK(ffr_wire_decode(FFR_S_INPUTS, buf, 31, &back) == 0u);
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, 31) == 0u);

    ffr_config_default(&cfg);
    memset(&cfg2, 0, sizeof(cfg2));
    CHECK(ffr_wire_encode(FFR_S_CONFIG, &cfg, buf, sizeof(buf)) == ffr_wire_size(FFR_S_CONFIG));
    CHECK(ffr_wire_decode(FFR_S_CONFIG, buf, ffr_wire_size(FFR_S_CONFIG), &cfg2) == ffr_wire_size(FFR_S_CONFIG));
    CHECK(memcmp(&cfg, &cfg2, sizeof(cfg)) == 0);
    CHECK(cfg2.route_len == cfg.route_len && cfg2.route[3].param == cfg.route[3].param);
}

static void test_frames(void)
{
    ffr_msg_t m, d;
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX], out[FFR_MSG_MAX + 2u];
    size_t n, f, ol = 0, i;
    ffr_deframer_t df;
    const uint8_t *got = NULL;
    size_t glen = 0;
    int hits = 0;

    memset(&m, 0, sizeof(m));
    m.type = FFR_MSG_OUTPUTS;
    m.u.outputs.seq = 42u;
    m.u.outputs.pwm[0] = -300;
    m.u.outputs.fan = 1u;
    n = ffr_msg_encode(&m, msg, sizeof(msg));
    CHECK(n == 25u && msg[0] == FFR_MSG_OUTPUTS);
    f = ffr_frame_encode(msg, n, frame, sizeof(frame));
    CHECK(f > n + 2u && frame[f - 1u] == 0u);
    for (i = 0; i + 1u < f; ++i) {
        CHECK(frame[i] != 0u);
    }
    CHECK(ffr_frame_decode(frame, f - 1u, out, sizeof(out), &ol) == FFR_OK && ol == n && memcmp(out, msg, n) == 0);
    CHECK(ffr_msg_decode(out, ol, &d) == FFR_OK && d.u.outputs.seq == 42u && d.u.outputs.pwm[0] == -300);
    frame[3] ^= 0x10u;
    CHECK(ffr_frame_decode(frame, f - 1u, out, sizeof(out), &ol) == FFR_E_CRC);
    frame[3] ^= 0x10u;
    CHECK(ffr_msg_decode(out, 3, &d) == FFR_E_LENGTH);
    out[0] = 99u;
    CHECK(ffr_msg_decode(out, 25, &d) == FFR_E_TYPE);

    /* the deframer: noise, then the frame, then an idle delimiter */
    ffr_deframer_init(&df);
    CHECK(ffr_deframer_push(&df, 0x55u, &got, &glen) == 0);
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == 1 && glen == 1u); /* noise ends as a short frame */
    CHECK(ffr_frame_decode(got, glen, out, sizeof(out), &ol) == FFR_E_SHORT);
    for (i = 0; i < f; ++i) {
        int r = ffr_deframer_push(&df, frame[i], &got, &glen);
        if (r == 1) {
            hits++;
            CHECK(glen == f - 1u && memcmp(got, frame, glen) == 0);
        }
    }
    CHECK(hits == 1);
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == 0);
    for (i = 0; i < FFR_FRAME_MAX + 5u; ++i) {
        CHECK(ffr_deframer_push(&df, 0x01u, &got, &glen) == 0);
    }
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == FFR_E_LONG);
}

static void test_can(void)
{
    ffr_msg_t m;
    uint8_t msg[FFR_MSG_MAX], data[64], out[FFR_MSG_MAX];
    size_t n, ol = 0;
    uint32_t id, k;
    uint8_t dlen;
    ffr_can_rx_t rx;
    int r = 0, fd;
    memset(&m, 0, sizeof(m));
    m.type = FFR_MSG_INPUTS;
    m.u.inputs.seq = 9u;
    m.u.inputs.t_ms = 90u;
    n = ffr_msg_encode(&m, msg, sizeof(msg));
    CHECK(ffr_can_frame_count(FFR_MSG_INPUTS, 0) == 5u); /* 32 + CRC over 8-byte frames */
    CHECK(ffr_can_frame_count(FFR_MSG_INPUTS, 1) == 1u);
    CHECK(ffr_can_frame_count(FFR_MSG_OUTPUTS, 0) == 4u);
    CHECK(ffr_can_id(FFR_MSG_INPUTS, 2, 0) == 0x182u && ffr_can_id(FFR_MSG_INPUTS, 0, 1) == 0x580u);
    for (fd = 0; fd <= 1; ++fd) {
        ffr_can_rx_init(&rx);
        for (k = 0; ffr_can_frame(msg, n, fd, k, &id, data, &dlen) == 1; ++k) {
            CHECK(id == ffr_can_id(FFR_MSG_INPUTS, k, fd));
            r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
        }
        CHECK(k == ffr_can_frame_count(FFR_MSG_INPUTS, fd));
        CHECK(r == 1 && ol == n && memcmp(out, msg, n) == 0);
        CHECK(!fd || dlen == 48u); /* 34 bytes padded to the next FD length */
    }
    /* a segment received twice (a lost ACK): taken once */
    ffr_can_rx_init(&rx);
    for (k = 0; ffr_can_frame(msg, n, 0, k, &id, data, &dlen) == 1; ++k) {
        r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
        if (k == 1u) {
            CHECK(r == 0 && ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
        }
    }
    CHECK(r == 1 && ol == n && memcmp(out, msg, n) == 0);
    /* a lost segment: the partial message is dropped, the next one is whole */
    ffr_can_rx_init(&rx);
    CHECK(ffr_can_frame(msg, n, 0, 0, &id, data, &dlen) == 1);
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
    CHECK(ffr_can_frame(msg, n, 0, 2, &id, data, &dlen) == 1);
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == FFR_E_SEGMENT);
    CHECK(ffr_can_frame(msg, n, 0, 3, &id, data, &dlen) == 1); /* the rest of it: ignored, once is enough */
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
    /* a flipped bit: the CRC catches it */
    ffr_can_rx_init(&rx);
    for (k = 0; ffr_can_frame(msg, n, 0, k, &id, data, &dlen) == 1; ++k) {
        if (k == 1u) {
            data[3] ^= 0x04u;
        }
        r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
    }
    CHECK(r == FFR_E_CRC);
    CHECK(ffr_can_rx_push(&rx, 0x7u, data, 8, out, sizeof(out), &ol) == FFR_E_SEGMENT);
    CHECK(ffr_can_rx_push(&rx, 0x800u, data, 8, out, sizeof(out), &ol) == FFR_E_SEGMENT);
}

void suite_codec(void)
{
    test_crc();
    test_cobs();
    test_wire_struct();
    test_frames();
    test_can();
}
