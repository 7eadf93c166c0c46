/* The board link with a fake clock and plain messages: handshake, reset,
 * lockstep with repeats, sequence errors, and the watchdog. */
#include <string.h>

#include "ffr.h"
#include "ffr_link.h"
#include "unit.h"
#include "wire_tests.h"

static ffr_board_link_t g_b; /* big: keep it off the test's stack */
static ffr_msg_t g_m;

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

void suite_board_link(void)
{
    ffr_board_link_t *b = &g_b;
    static ffr_msg_t r;
    uint8_t rep[FFR_MSG_MAX], bad[2] = {FFR_MSG_HELLO, 1};
    int16_t pwm[2];
    uint8_t fan;
    uint32_t t = 1000u, seq;
    ffr_outputs_t first;

    ffr_board_link_init(b, 100u, t);
    /* handshake */
    memset(&g_m, 0, sizeof(g_m));
    g_m.type = FFR_MSG_HELLO;
    g_m.u.hello.proto = FFR_PROTO_VERSION;
    g_m.u.hello.watchdog_ms = 50u;
    CHECK(send(b, &g_m, t, &r) == 1u + FFR_INFO_SIZE);
    CHECK(r.type == FFR_MSG_INFO && r.u.info.layout_hash == ffr_layout_hash() && r.u.info.watchdog_ms == 50u);
    CHECK(r.u.info.fw_version == ffr_version() && r.u.info.inputs_size == 32u && r.u.info.outputs_size == 24u);
    g_m.u.hello.proto = 9u;
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_PROTO);
    /* inputs before a reset: refused */
    inputs(&g_m, 0u);
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_NOT_READY);
    /* a malformed message: an error naming its type */
    CHECK(ffr_board_link_on_msg(b, bad, sizeof(bad), t, rep, sizeof(rep)) > 0u);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_LENGTH &&
          r.u.error.detail == FFR_MSG_HELLO);
    /* reset with the default configuration */
    memset(&g_m, 0, sizeof(g_m));
    g_m.type = FFR_MSG_RESET;
    ffr_config_default(FFR_MSG_CONFIG(&g_m));
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_READY && b->configured);
    /* lockstep: the robot starts driving within a second */
    for (seq = 0; seq < 100u; ++seq) {
        inputs(&g_m, seq);
        send(b, &g_m, t, &r);
        CHECK(r.type == FFR_MSG_OUTPUTS && r.u.outputs.seq == seq);
        t += 10u;
        CHECK(ffr_board_link_poll(b, t, rep, sizeof(rep)) == 0u);
    }
    first = r.u.outputs;
    CHECK(first.pwm[0] != 0 || first.pwm[1] != 0);
    ffr_board_link_actuators(b, pwm, &fan);
    CHECK(pwm[0] == first.pwm[0] && pwm[1] == first.pwm[1]);
    /* a repeated request (our answer was lost) gets the same answer, no second step */
    inputs(&g_m, 99u);
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_OUTPUTS && memcmp(&r.u.outputs, &first, sizeof(first)) == 0 && b->repeats == 1u);
    /* a sequence number out of turn is refused */
    inputs(&g_m, 120u);
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_ERROR && r.u.error.code == FFR_ERR_SEQUENCE && r.u.error.seq == 120u);
    /* the watchdog: silent inputs for longer than 50 ms stop motors and fans, once */
    CHECK(ffr_board_link_poll(b, t + 50u, rep, sizeof(rep)) == 0u);
    CHECK(ffr_board_link_poll(b, t + 51u, rep, sizeof(rep)) == 1u + FFR_ERROR_SIZE);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_WATCHDOG &&
          r.u.error.seq == 99u);
    ffr_board_link_actuators(b, pwm, &fan);
    CHECK(pwm[0] == 0 && pwm[1] == 0 && fan == 0u && b->tripped && b->watchdog_trips == 1u);
    CHECK(ffr_board_link_poll(b, t + 500u, rep, sizeof(rep)) == 0u);
    /* the next inputs re-arm it and the motors follow the firmware again */
    t += 600u;
    inputs(&g_m, 100u);
    send(b, &g_m, t, &r);
    CHECK(r.type == FFR_MSG_OUTPUTS && !b->tripped);
    ffr_board_link_actuators(b, pwm, &fan);
    CHECK(pwm[0] == r.u.outputs.pwm[0] && pwm[1] == r.u.outputs.pwm[1]);
    /* bad frames get error reports */
    CHECK(ffr_board_link_on_bad_frame(b, FFR_E_CRC, rep, sizeof(rep)) == 1u + FFR_ERROR_SIZE);
    CHECK(ffr_msg_decode(rep, 1u + FFR_ERROR_SIZE, &r) == FFR_OK && r.u.error.code == FFR_ERR_CRC);
    /* watchdog 0 = off */
    ffr_board_link_init(b, 0u, 0u);
    b->have_out = 1u;
    CHECK(ffr_board_link_poll(b, 100000u, rep, sizeof(rep)) == 0u);
}
