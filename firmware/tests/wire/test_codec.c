/* The codec on its own: CRC, COBS, the wire structs, serial frames and the
 * deframer, CAN segmentation; each test builds its own inputs. */
#include <string.h>

#include "ffr.h"
#include "ffr_codec.h"
#include "unit.h"
#include "wire_tests.h"

TEST(crc16_of_the_check_string_is_29b1)
{
    const uint8_t check[] = "123456789";
    CHECK(ffr_crc16(check, 9) == 0x29B1u);
}

TEST(a_message_followed_by_its_crc_leaves_residue_zero)
{
    const uint8_t check[] = "123456789";
    uint8_t with_crc[11];
    uint16_t c = ffr_crc16(check, 9);
    memcpy(with_crc, check, 9);
    with_crc[9] = (uint8_t)(c >> 8);
    with_crc[10] = (uint8_t)c;
    CHECK(ffr_crc16(with_crc, 11) == 0u); /* the residue the decoders check */
}

TEST(crc16_of_nothing_is_the_initial_value)
{
    const uint8_t check[] = "123456789";
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

TEST(cobs_encodes_the_textbook_examples)
{
    static const uint8_t a[] = {0x00};
    static const uint8_t b[] = {0x11, 0x22, 0x00, 0x33};
    uint8_t enc[16];
    size_t n;
    CHECK(ffr_cobs_encode(a, 1, enc, sizeof(enc)) == 2u && enc[0] == 1u && enc[1] == 1u);
    n = ffr_cobs_encode(b, 4, enc, sizeof(enc));
    CHECK(n == 5u && enc[0] == 3u && enc[1] == 0x11u && enc[3] == 2u && enc[4] == 0x33u);
}

TEST(cobs_round_trips_a_block_with_zeros)
{
    uint8_t big[600];
    size_t i;
    for (i = 0; i < sizeof(big); ++i) {
        big[i] = (uint8_t)(i % 7u == 3u ? 0u : i + 1u);
    }
    cobs_roundtrip(big, sizeof(big));
}

/* no zeros: full 254-byte runs */
static void no_zeros(uint8_t *big, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        big[i] = (uint8_t)(i % 255u + 1u);
    }
}

TEST(cobs_round_trips_full_runs_and_nothing)
{
    uint8_t big[600];
    no_zeros(big, sizeof(big));
    cobs_roundtrip(big, 254);
    cobs_roundtrip(big, 255);
    cobs_roundtrip(big, 508);
    cobs_roundtrip(big, 0);
}

TEST(cobs_refuses_a_too_small_output_instead_of_overrunning)
{
    uint8_t big[600], enc[16];
    no_zeros(big, sizeof(big));
    CHECK(ffr_cobs_encode(big, 254, enc, sizeof(enc)) == 0u);
}

TEST(cobs_rejects_a_run_longer_than_the_block)
{
    uint8_t enc[2] = {5, 1}, out[8];
    size_t m;
    CHECK(ffr_cobs_decode(enc, 2, out, sizeof(out), &m) == FFR_E_COBS);
}

TEST(cobs_rejects_a_zero_inside_a_block)
{
    uint8_t enc[3] = {3, 0, 1}, out[8];
    size_t m;
    CHECK(ffr_cobs_decode(enc, 3, out, sizeof(out), &m) == FFR_E_COBS);
}

/* fixture: inputs with a value in the first, a middle and the last field */
static void sample_inputs(ffr_inputs_t *in)
{
    memset(in, 0, sizeof(*in));
    in->t_ms = 0x01020304u;
    in->seq = 7u;
    in->enc[0] = -2;
    in->ir_mv[4] = 0xBEEFu;
    in->start = 1u;
}

TEST(wire_struct_sizes_are_the_protocol_s)
{
    CHECK(ffr_wire_size(FFR_S_INPUTS) == 32u);
    CHECK(ffr_wire_size(FFR_S_OUTPUTS) == 24u);
    CHECK(ffr_wire_size(FFR_S_ROUTE_STEP) == 8u);
    CHECK(ffr_wire_size(FFR_S_CONFIG) <= sizeof(ffr_config_t));
}

TEST(inputs_encode_little_endian_at_their_offsets)
{
    ffr_inputs_t in;
    uint8_t buf[64];
    sample_inputs(&in);
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, sizeof(buf)) == 32u);
    CHECK(buf[0] == 0x04u && buf[3] == 0x01u && buf[4] == 7u); /* little-endian */
    CHECK(buf[8] == 0xFEu && buf[11] == 0xFFu);
    CHECK(buf[24] == 0xEFu && buf[25] == 0xBEu && buf[31] == 1u);
}

TEST(inputs_round_trip)
{
    ffr_inputs_t in, back;
    uint8_t buf[64];
    sample_inputs(&in);
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, sizeof(buf)) == 32u);
    memset(&back, 0xA5, sizeof(back));
    CHECK(ffr_wire_decode(FFR_S_INPUTS, buf, 32, &back) == 32u);
    CHECK(memcmp(&in, &back, sizeof(in)) == 0);
}

TEST(a_buffer_one_byte_short_is_refused_both_ways)
{
    ffr_inputs_t in, back;
    uint8_t buf[64];
    sample_inputs(&in);
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, sizeof(buf)) == 32u);
    CHECK(ffr_wire_decode(FFR_S_INPUTS, buf, 31, &back) == 0u);
    CHECK(ffr_wire_encode(FFR_S_INPUTS, &in, buf, 31) == 0u);
}

TEST(the_default_config_round_trips)
{
    ffr_config_t cfg, cfg2;
    uint8_t buf[sizeof(ffr_config_t)];
    ffr_config_default(&cfg);
    memset(&cfg2, 0, sizeof(cfg2));
    CHECK(ffr_wire_encode(FFR_S_CONFIG, &cfg, buf, sizeof(buf)) == ffr_wire_size(FFR_S_CONFIG));
    CHECK(ffr_wire_decode(FFR_S_CONFIG, buf, ffr_wire_size(FFR_S_CONFIG), &cfg2) == ffr_wire_size(FFR_S_CONFIG));
    CHECK(memcmp(&cfg, &cfg2, sizeof(cfg)) == 0);
    CHECK(cfg2.route_len == cfg.route_len && cfg2.route[3].param == cfg.route[3].param);
}

/* fixture: an outputs message (msg, *n bytes) and its serial frame (returns its length) */
static size_t outputs_frame(uint8_t msg[FFR_MSG_MAX + 2u], size_t *n, uint8_t frame[FFR_FRAME_MAX])
{
    ffr_msg_t m;
    memset(&m, 0, sizeof(m));
    m.type = FFR_MSG_OUTPUTS;
    m.u.outputs.seq = 42u;
    m.u.outputs.pwm[0] = -300;
    m.u.outputs.fan = 1u;
    *n = ffr_msg_encode(&m, msg, FFR_MSG_MAX + 2u);
    return ffr_frame_encode(msg, *n, frame, FFR_FRAME_MAX);
}

TEST(an_outputs_message_is_its_type_and_24_bytes)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n;
    outputs_frame(msg, &n, frame);
    CHECK(n == 25u && msg[0] == FFR_MSG_OUTPUTS);
}

TEST(a_frame_has_one_zero_its_last_byte)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n, i, f = outputs_frame(msg, &n, frame);
    CHECK(f > n + 2u && frame[f - 1u] == 0u);
    for (i = 0; i + 1u < f; ++i) {
        CHECK(frame[i] != 0u);
    }
}

TEST(a_frame_decodes_to_its_message)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX], out[FFR_MSG_MAX + 2u];
    size_t n, ol = 0, f = outputs_frame(msg, &n, frame);
    ffr_msg_t d;
    CHECK(ffr_frame_decode(frame, f - 1u, out, sizeof(out), &ol) == FFR_OK && ol == n && memcmp(out, msg, n) == 0);
    CHECK(ffr_msg_decode(out, ol, &d) == FFR_OK && d.u.outputs.seq == 42u && d.u.outputs.pwm[0] == -300);
}

TEST(a_flipped_bit_in_a_frame_fails_the_crc)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX], out[FFR_MSG_MAX + 2u];
    size_t n, ol = 0, f = outputs_frame(msg, &n, frame);
    frame[3] ^= 0x10u;
    CHECK(ffr_frame_decode(frame, f - 1u, out, sizeof(out), &ol) == FFR_E_CRC);
}

TEST(a_message_shorter_than_its_type_is_a_length_error)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n;
    ffr_msg_t d;
    outputs_frame(msg, &n, frame);
    CHECK(ffr_msg_decode(msg, 3, &d) == FFR_E_LENGTH);
}

TEST(an_unknown_message_type_is_a_type_error)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n;
    ffr_msg_t d;
    outputs_frame(msg, &n, frame);
    msg[0] = 99u;
    CHECK(ffr_msg_decode(msg, 25, &d) == FFR_E_TYPE);
}

TEST(the_deframer_ends_noise_as_a_short_frame)
{
    ffr_deframer_t df;
    const uint8_t *got = NULL;
    size_t glen = 0, ol = 0;
    uint8_t out[FFR_MSG_MAX + 2u];
    ffr_deframer_init(&df);
    CHECK(ffr_deframer_push(&df, 0x55u, &got, &glen) == 0);
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == 1 && glen == 1u);
    CHECK(ffr_frame_decode(got, glen, out, sizeof(out), &ol) == FFR_E_SHORT);
}

/* fixture: a deframer fed noise, its delimiter, then the whole frame; returns the frames it gave */
static int feed_noise_then_frame(ffr_deframer_t *df, const uint8_t *frame, size_t f)
{
    const uint8_t *got = NULL;
    size_t glen = 0, i;
    int hits = 0;
    ffr_deframer_init(df);
    (void)ffr_deframer_push(df, 0x55u, &got, &glen);
    (void)ffr_deframer_push(df, 0x00u, &got, &glen);
    for (i = 0; i < f; ++i) {
        if (ffr_deframer_push(df, frame[i], &got, &glen) == 1) {
            hits++;
            CHECK(glen == f - 1u && memcmp(got, frame, glen) == 0);
        }
    }
    return hits;
}

TEST(the_deframer_finds_the_frame_after_noise_once)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n, f = outputs_frame(msg, &n, frame);
    ffr_deframer_t df;
    CHECK(feed_noise_then_frame(&df, frame, f) == 1);
}

TEST(an_idle_delimiter_after_a_frame_gives_nothing)
{
    uint8_t msg[FFR_MSG_MAX + 2u], frame[FFR_FRAME_MAX];
    size_t n, glen = 0, f = outputs_frame(msg, &n, frame);
    const uint8_t *got = NULL;
    ffr_deframer_t df;
    feed_noise_then_frame(&df, frame, f);
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == 0);
}

TEST(the_deframer_reports_an_overlong_frame_at_its_delimiter)
{
    ffr_deframer_t df;
    const uint8_t *got = NULL;
    size_t glen = 0, i;
    ffr_deframer_init(&df);
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == 0);
    for (i = 0; i < FFR_FRAME_MAX + 5u; ++i) {
        CHECK(ffr_deframer_push(&df, 0x01u, &got, &glen) == 0);
    }
    CHECK(ffr_deframer_push(&df, 0x00u, &got, &glen) == FFR_E_LONG);
}

/* fixture: an inputs message (returns its length) */
static size_t inputs_message(uint8_t msg[FFR_MSG_MAX])
{
    ffr_msg_t m;
    memset(&m, 0, sizeof(m));
    m.type = FFR_MSG_INPUTS;
    m.u.inputs.seq = 9u;
    m.u.inputs.t_ms = 90u;
    return ffr_msg_encode(&m, msg, FFR_MSG_MAX);
}

TEST(can_frame_counts_are_the_protocol_s)
{
    CHECK(ffr_can_frame_count(FFR_MSG_INPUTS, 0) == 5u); /* 32 + CRC over 8-byte frames */
    CHECK(ffr_can_frame_count(FFR_MSG_INPUTS, 1) == 1u);
    CHECK(ffr_can_frame_count(FFR_MSG_OUTPUTS, 0) == 4u);
}

TEST(can_ids_carry_type_and_segment)
{
    CHECK(ffr_can_id(FFR_MSG_INPUTS, 2, 0) == 0x182u && ffr_can_id(FFR_MSG_INPUTS, 0, 1) == 0x580u);
}

/* segments the inputs message (fd: CAN FD) and reassembles it, checking every id */
static void can_round_trip(int fd)
{
    uint8_t msg[FFR_MSG_MAX], data[64], out[FFR_MSG_MAX];
    size_t n = inputs_message(msg), ol = 0;
    uint32_t id, k;
    uint8_t dlen = 0;
    ffr_can_rx_t rx;
    int r = 0;
    ffr_can_rx_init(&rx);
    for (k = 0; ffr_can_frame(msg, n, fd, k, &id, data, &dlen) == 1; ++k) {
        CHECK(id == ffr_can_id(FFR_MSG_INPUTS, k, fd));
        r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
    }
    CHECK(k == ffr_can_frame_count(FFR_MSG_INPUTS, fd));
    CHECK(r == 1 && ol == n && memcmp(out, msg, n) == 0);
    CHECK(!fd || dlen == 48u); /* 34 bytes padded to the next FD length */
}

TEST(a_message_crosses_classic_can_in_segments)
{
    can_round_trip(0);
}

TEST(a_message_crosses_can_fd_in_one_padded_frame)
{
    can_round_trip(1);
}

TEST(a_can_segment_received_twice_is_taken_once)
{
    uint8_t msg[FFR_MSG_MAX], data[64], out[FFR_MSG_MAX];
    size_t n = inputs_message(msg), ol = 0;
    uint32_t id, k;
    uint8_t dlen;
    ffr_can_rx_t rx;
    int r = 0;
    /* a lost ACK: the sender repeats segment 1 */
    ffr_can_rx_init(&rx);
    for (k = 0; ffr_can_frame(msg, n, 0, k, &id, data, &dlen) == 1; ++k) {
        r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
        if (k == 1u) {
            CHECK(r == 0 && ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
        }
    }
    CHECK(r == 1 && ol == n && memcmp(out, msg, n) == 0);
}

TEST(a_lost_can_segment_is_one_segment_error)
{
    uint8_t msg[FFR_MSG_MAX], data[64], out[FFR_MSG_MAX];
    size_t n = inputs_message(msg), ol = 0;
    uint32_t id;
    uint8_t dlen;
    ffr_can_rx_t rx;
    /* the partial message is dropped */
    ffr_can_rx_init(&rx);
    CHECK(ffr_can_frame(msg, n, 0, 0, &id, data, &dlen) == 1);
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
    CHECK(ffr_can_frame(msg, n, 0, 2, &id, data, &dlen) == 1);
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == FFR_E_SEGMENT);
    CHECK(ffr_can_frame(msg, n, 0, 3, &id, data, &dlen) == 1); /* the rest of it: ignored, once is enough */
    CHECK(ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol) == 0);
}

TEST(a_flipped_bit_in_a_can_segment_fails_the_crc)
{
    uint8_t msg[FFR_MSG_MAX], data[64], out[FFR_MSG_MAX];
    size_t n = inputs_message(msg), ol = 0;
    uint32_t id, k;
    uint8_t dlen;
    ffr_can_rx_t rx;
    int r = 0;
    ffr_can_rx_init(&rx);
    for (k = 0; ffr_can_frame(msg, n, 0, k, &id, data, &dlen) == 1; ++k) {
        if (k == 1u) {
            data[3] ^= 0x04u;
        }
        r = ffr_can_rx_push(&rx, id, data, dlen, out, sizeof(out), &ol);
    }
    CHECK(r == FFR_E_CRC);
}

TEST(a_can_id_outside_the_wire_s_is_a_segment_error)
{
    uint8_t data[8] = {0}, out[FFR_MSG_MAX];
    size_t ol = 0;
    ffr_can_rx_t rx;
    ffr_can_rx_init(&rx);
    CHECK(ffr_can_rx_push(&rx, 0x7u, data, 8, out, sizeof(out), &ol) == FFR_E_SEGMENT);
    CHECK(ffr_can_rx_push(&rx, 0x800u, data, 8, out, sizeof(out), &ol) == FFR_E_SEGMENT);
}

SUITE(codec,
      TEST_REF(crc16_of_the_check_string_is_29b1),
      TEST_REF(a_message_followed_by_its_crc_leaves_residue_zero),
      TEST_REF(crc16_of_nothing_is_the_initial_value),
      TEST_REF(cobs_encodes_the_textbook_examples),
      TEST_REF(cobs_round_trips_a_block_with_zeros),
      TEST_REF(cobs_round_trips_full_runs_and_nothing),
      TEST_REF(cobs_refuses_a_too_small_output_instead_of_overrunning),
      TEST_REF(cobs_rejects_a_run_longer_than_the_block),
      TEST_REF(cobs_rejects_a_zero_inside_a_block),
      TEST_REF(wire_struct_sizes_are_the_protocol_s),
      TEST_REF(inputs_encode_little_endian_at_their_offsets),
      TEST_REF(inputs_round_trip),
      TEST_REF(a_buffer_one_byte_short_is_refused_both_ways),
      TEST_REF(the_default_config_round_trips),
      TEST_REF(an_outputs_message_is_its_type_and_24_bytes),
      TEST_REF(a_frame_has_one_zero_its_last_byte),
      TEST_REF(a_frame_decodes_to_its_message),
      TEST_REF(a_flipped_bit_in_a_frame_fails_the_crc),
      TEST_REF(a_message_shorter_than_its_type_is_a_length_error),
      TEST_REF(an_unknown_message_type_is_a_type_error),
      TEST_REF(the_deframer_ends_noise_as_a_short_frame),
      TEST_REF(the_deframer_finds_the_frame_after_noise_once),
      TEST_REF(an_idle_delimiter_after_a_frame_gives_nothing),
      TEST_REF(the_deframer_reports_an_overlong_frame_at_its_delimiter),
      TEST_REF(can_frame_counts_are_the_protocol_s),
      TEST_REF(can_ids_carry_type_and_segment),
      TEST_REF(a_message_crosses_classic_can_in_segments),
      TEST_REF(a_message_crosses_can_fd_in_one_padded_frame),
      TEST_REF(a_can_segment_received_twice_is_taken_once),
      TEST_REF(a_lost_can_segment_is_one_segment_error),
      TEST_REF(a_flipped_bit_in_a_can_segment_fails_the_crc),
      TEST_REF(a_can_id_outside_the_wire_s_is_a_segment_error));
