/* The board link with a fake clock and plain messages: handshake, reset,
 * lockstep with repeats, sequence errors, and the watchdog. Every test
 * builds its own link on its stack with one of the fixtures below. */
#include <string.h>

#include "ffr.h"
#include "ffr_link.h"
#include "unit.h"
#include "wire_tests.h"

static size_t send(ffr_board_link_t *b, const ffr_msg_t *m, uint32_t now, ffr_msg_t *reply)
{
    uint8_t buf[FFR_MSG_MAX], rep[FFR_MSG_MAX];
    size_t n = ffr_msg_encode(m, buf, sizeof(buf));
    size_t r = ffr_board_link_on_msg(b, buf, n, now, rep, sizeof(rep));
    memset(reply, 0, sizeof(*reply));
    if (r > 0u) {
        CHECK(ffr_msg_decode(rep, r, reply) == FFR_OK);
    }
    return r;
}

static void inputs(ffr_msg_t *m, uint32_t seq)
{
    memset(m, 0, sizeof(*m));
    m->type = FFR_MSG_INPUTS;
    m->u.inputs.seq = seq;
    m->u.inputs.t_ms = seq * 10u;
    m->u.inputs.start = 1u;
    m->u.inputs.ir_mv[0] = 400u; /* a wall far ahead, nothing beside: the robot drives */
}

static void hello(ffr_msg_t *m, uint8_t proto)
{
    memset(m, 0, sizeof(*m));
    m->type = FFR_MSG_HELLO;
    m->u.hello.proto = proto;
    m->u.hello.watchdog_ms = 50u;
}

/* fixture: a link just powered up at t = 1000 ms (watchdog 100 ms) */
static void new_link(ffr_board_link_t *b)
{
    ffr_board_link_init(b, 100u, 1000u);
}

/* fixture: a link after the handshake (watchdog 50 ms) and a reset with the default configuration */
static void ready_link(ffr_board_link_t *b)
{
    ffr_msg_t m, r;
    new_link(b);
    hello(&m, FFR_PROTO_VERSION);
    send(b, &m, 1000u, &r);
    memset(&m, 0, sizeof(m));
    m.type = FFR_MSG_RESET;
    ffr_config_default(FFR_MSG_CONFIG(&m));
    send(b, &m, 1000u, &r);
    CHECK(r.type == FFR_MSG_READY && b->configured);
}

/* fixture: a ready link run 100 lockstep steps (seq 0..99, every 10 ms from 1000 ms);
 * returns the time after the last step and the last outputs */
static uint32_t driving_link(ffr_board_link_t *b, ffr_outputs_t *last)
{
    ffr_msg_t m, r;
    uint8_t rep[FFR_MSG_MAX];
    uint32_t t = 1000u, seq;
    ready_link(b);
    for (seq = 0; seq < 100u; ++seq) {
        inputs(&m, seq);
        send(b, &m, t, &r);
        CHECK(r.type == FFR_MSG_OUTPUTS && r.u.outputs.seq == seq);
        t += 10u;
        CHECK(ffr_board_link_poll(b, t, rep, sizeof(rep)) == 0u);
    }
    *last = r.u.outputs;
    return t;
}

/* fixture: a driving link whose last inputs (seq 99, repeated) came at the returned time, then
 * silence past the 50 ms watchdog: tripped */
static uint32_t tripped_link(ffr_board_link_t *b)
{
    ffr_msg_t m, r;
    ffr_outputs_t last;
    uint8_t rep[FFR_MSG_MAX];
    uint32_t t = driving_link(b, &last);
    inputs(&m, 99u);
    send(b, &m, t, &r);
    CHECK(ffr_board_link_poll(b, t + 51u, rep, sizeof(rep)) == 1u + FFR_ERROR_SIZE);
    return t;
}

TEST(a_hello_gets_the_board_s_info)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    new_link(&b);
    hello(&m, FFR_PROTO_VERSION);
    CHECK(send(&b, &m, 1000u, &r) == 1u + FFR_INFO_SIZE);
    CHECK(r.type == FFR_MSG_INFO && r.u.info.layout_hash == ffr_layout_hash() && r.u.info.watchdog_ms == 50u);
    CHECK(r.u.info.fw_version == ffr_version() && r.u.info.inputs_size == 32u && r.u.info.outputs_size == 24u);
}

TEST(a_hello_with_another_protocol_is_refused)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    new_link(&b);
    hello(&m, 9u);
    send(&b, &m, 1000u, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_PROTO);
}

TEST(inputs_before_a_reset_are_refused)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    new_link(&b);
    hello(&m, FFR_PROTO_VERSION);
    send(&b, &m, 1000u, &r);
    inputs(&m, 0u);
    send(&b, &m, 1000u, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_NOT_READY);
}

TEST(a_malformed_message_gets_an_error_naming_its_type)
{
    ffr_board_link_t b;
    ffr_msg_t r;
    uint8_t rep[FFR_MSG_MAX], bad[2] = {FFR_MSG_HELLO, 1};
    new_link(&b);
    CHECK(ffr_board_link_on_msg(&b, bad, sizeof(bad), 1000u, rep, sizeof(rep)) > 0u);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_LENGTH &&
          r.u.error.detail == FFR_MSG_HELLO);
}

TEST(a_reset_with_the_default_config_makes_the_board_ready)
{
    ffr_board_link_t b;
    ready_link(&b); /* its check is this test's */
}

TEST(in_lockstep_the_robot_starts_driving_within_a_second)
{
    ffr_board_link_t b;
    ffr_outputs_t first;
    int16_t pwm[2];
    uint8_t fan;
    driving_link(&b, &first);
    CHECK(first.pwm[0] != 0 || first.pwm[1] != 0);
    ffr_board_link_actuators(&b, pwm, &fan);
    CHECK(pwm[0] == first.pwm[0] && pwm[1] == first.pwm[1]);
}

TEST(a_repeated_request_gets_the_same_answer_and_no_second_step)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    ffr_outputs_t first;
    uint32_t t = driving_link(&b, &first);
    /* our answer was lost: the harness asks again */
    inputs(&m, 99u);
    send(&b, &m, t, &r);
    CHECK(r.type == FFR_MSG_OUTPUTS && memcmp(&r.u.outputs, &first, sizeof(first)) == 0 && b.repeats == 1u);
}

TEST(a_sequence_number_out_of_turn_is_refused)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    ffr_outputs_t first;
    uint32_t t = driving_link(&b, &first);
    inputs(&m, 120u);
    send(&b, &m, t, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_SEQUENCE && r.u.error.seq == 120u);
}

TEST(the_watchdog_stops_motors_and_fan_once_after_silence)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    ffr_outputs_t first;
    uint8_t rep[FFR_MSG_MAX];
    int16_t pwm[2];
    uint8_t fan;
    uint32_t t = driving_link(&b, &first);
    inputs(&m, 99u); /* the last inputs, at t */
    send(&b, &m, t, &r);
    CHECK(ffr_board_link_poll(&b, t + 50u, rep, sizeof(rep)) == 0u);
    CHECK(ffr_board_link_poll(&b, t + 51u, rep, sizeof(rep)) == 1u + FFR_ERROR_SIZE);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_WATCHDOG &&
          r.u.error.seq == 99u);
    ffr_board_link_actuators(&b, pwm, &fan);
    CHECK(pwm[0] == 0 && pwm[1] == 0 && fan == 0u && b.tripped && b.watchdog_trips == 1u);
    CHECK(ffr_board_link_poll(&b, t + 500u, rep, sizeof(rep)) == 0u);
}

TEST(the_next_inputs_rearm_the_watchdog_and_the_motors_follow_again)
{
    ffr_board_link_t b;
    ffr_msg_t m, r;
    int16_t pwm[2];
    uint8_t fan;
    uint32_t t = tripped_link(&b) + 600u;
    inputs(&m, 100u);
    send(&b, &m, t, &r);
    CHECK(r.type == FFR_MSG_OUTPUTS && !b.tripped);
    ffr_board_link_actuators(&b, pwm, &fan);
    CHECK(pwm[0] == r.u.outputs.pwm[0] && pwm[1] == r.u.outputs.pwm[1]);
}

TEST(a_bad_frame_gets_an_error_report)
{
    ffr_board_link_t b;
    ffr_msg_t r;
    uint8_t rep[FFR_MSG_MAX];
    ready_link(&b);
    CHECK(ffr_board_link_on_bad_frame(&b, FFR_E_CRC, rep, sizeof(rep)) == 1u + FFR_ERROR_SIZE);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_CRC);
}

TEST(watchdog_zero_is_off)
{
    ffr_board_link_t b;
    uint8_t rep[FFR_MSG_MAX];
    ffr_board_link_init(&b, 0u, 0u);
    b.have_out = 1u;
    CHECK(ffr_board_link_poll(&b, 100000u, rep, sizeof(rep)) == 0u);
}

SUITE(board_link,
      TEST_REF(a_hello_gets_the_board_s_info),
      TEST_REF(a_hello_with_another_protocol_is_refused),
      TEST_REF(inputs_before_a_reset_are_refused),
      TEST_REF(a_malformed_message_gets_an_error_naming_its_type),
      TEST_REF(a_reset_with_the_default_config_makes_the_board_ready),
      TEST_REF(in_lockstep_the_robot_starts_driving_within_a_second),
      TEST_REF(a_repeated_request_gets_the_same_answer_and_no_second_step),
      TEST_REF(a_sequence_number_out_of_turn_is_refused),
      TEST_REF(the_watchdog_stops_motors_and_fan_once_after_silence),
      TEST_REF(the_next_inputs_rearm_the_watchdog_and_the_motors_follow_again),
      TEST_REF(a_bad_frame_gets_an_error_report),
      TEST_REF(watchdog_zero_is_off));
