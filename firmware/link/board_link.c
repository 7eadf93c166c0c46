/*
 * The board side of the link protocol, shared by every board (see ffr_link.h).
 */
#include "ffr_link.h"

#define FW(b) ((ffr_state_t *)(void *)(b)->fw)

static size_t error_reply(ffr_board_link_t *b, uint8_t code, uint8_t detail, uint32_t seq, uint8_t *reply,
                          size_t cap)
{
    b->msg.type = FFR_MSG_ERROR;
    b->msg.u.error.code = code;
    b->msg.u.error.detail = detail;
    b->msg.u.error.reserved = 0u;
    b->msg.u.error.seq = seq;
    b->tx_msgs++;
    return ffr_msg_encode(&b->msg, reply, cap);
}

static void stop_actuators(ffr_board_link_t *b)
{
    b->pwm[0] = 0;
    b->pwm[1] = 0;
    b->fan = 0u;
}

void ffr_board_link_init(ffr_board_link_t *b, uint32_t watchdog_ms, uint32_t now_ms)
{
    size_t i;
    uint8_t *raw = (uint8_t *)b;
    for (i = 0; i < sizeof(*b); ++i) {
        raw[i] = 0u;
    }
    b->watchdog_ms = watchdog_ms;
    b->last_rx_ms = now_ms;
    b->step_clock = 0;
}

static void step_firmware(ffr_board_link_t *b)
{
    uint32_t c0, dc;
    if (b->step_clock == 0) {
        ffr_step(FW(b), &b->msg.u.inputs, &b->last_out);
        return;
    }
    c0 = b->step_clock();
    ffr_step(FW(b), &b->msg.u.inputs, &b->last_out);
    dc = (b->step_clock() - c0) & 0xFFFFFFu;
    b->prof_steps++;
    b->prof_sum += dc;
    b->prof_max = dc > b->prof_max ? dc : b->prof_max;
}

static size_t on_inputs(ffr_board_link_t *b, uint32_t now_ms, uint8_t *reply, size_t cap)
{
    uint32_t seq = b->msg.u.inputs.seq;
    if (!b->configured) {
        return error_reply(b, FFR_ERR_NOT_READY, 0u, seq, reply, cap);
    }
    if (b->have_out && seq == b->last_out.seq) {
        b->repeats++; /* our answer was lost: the same answer again, no second step */
    } else if (!b->have_out || seq == b->last_out.seq + 1u) {
        step_firmware(b);
        b->have_out = 1u;
    } else {
        return error_reply(b, FFR_ERR_SEQUENCE, 0u, seq, reply, cap);
    }
    b->last_rx_ms = now_ms;
    b->tripped = 0u;
    b->pwm[0] = b->last_out.pwm[0];
    b->pwm[1] = b->last_out.pwm[1];
    b->fan = b->last_out.fan;
    b->msg.type = FFR_MSG_OUTPUTS;
    b->msg.u.outputs = b->last_out;
    b->tx_msgs++;
    return ffr_msg_encode(&b->msg, reply, cap);
}

size_t ffr_board_link_on_msg(ffr_board_link_t *b, const uint8_t *msg, size_t len, uint32_t now_ms, uint8_t *reply,
                             size_t cap)
{
    int st = ffr_msg_decode(msg, len, &b->msg);
    if (st != FFR_OK) {
        b->rx_errors++;
        return error_reply(b, st == FFR_E_TYPE ? FFR_ERR_TYPE : FFR_ERR_LENGTH, len > 0u ? msg[0] : 0u,
                           b->last_out.seq, reply, cap);
    }
    b->rx_msgs++;
    switch (b->msg.type) {
    case FFR_MSG_HELLO:
        if (b->msg.u.hello.proto != FFR_PROTO_VERSION) {
            return error_reply(b, FFR_ERR_PROTO, (uint8_t)FFR_PROTO_VERSION, 0u, reply, cap);
        }
        if (b->msg.u.hello.watchdog_ms != 0u) {
            b->watchdog_ms = b->msg.u.hello.watchdog_ms;
        }
        b->msg.type = FFR_MSG_INFO;
        b->msg.u.info.proto = (uint16_t)FFR_PROTO_VERSION;
        b->msg.u.info.watchdog_ms = (uint16_t)(b->watchdog_ms > 0xFFFFu ? 0xFFFFu : b->watchdog_ms);
        b->msg.u.info.fw_version = ffr_version();
        b->msg.u.info.layout_hash = ffr_layout_hash();
        b->msg.u.info.inputs_size = (uint16_t)ffr_wire_size(FFR_S_INPUTS);
        b->msg.u.info.outputs_size = (uint16_t)ffr_wire_size(FFR_S_OUTPUTS);
        b->msg.u.info.config_size = (uint16_t)ffr_wire_size(FFR_S_CONFIG);
        b->msg.u.info.reserved = 0u;
        b->tx_msgs++;
        return ffr_msg_encode(&b->msg, reply, cap);
    case FFR_MSG_RESET:
        if (ffr_sizeof(FFR_S_STATE) > sizeof(b->fw)) { /* built with too small an FFR_STATE_MAX */
            b->rx_errors++;
            return error_reply(b, FFR_ERR_LENGTH, FFR_MSG_RESET, 0u, reply, cap);
        }
        ffr_init(FW(b), FFR_MSG_CONFIG(&b->msg));
        b->configured = 1u;
        b->have_out = 0u;
        b->tripped = 0u;
        stop_actuators(b);
        b->msg.type = FFR_MSG_READY;
        b->msg.u.ready.config_crc = ffr_crc16(msg + 1, len - 1u);
        b->msg.u.ready.reserved = 0u;
        b->tx_msgs++;
        return ffr_msg_encode(&b->msg, reply, cap);
    case FFR_MSG_INPUTS:
        return on_inputs(b, now_ms, reply, cap);
    default: /* a board-to-host type sent to the board */
        b->rx_errors++;
        return error_reply(b, FFR_ERR_TYPE, b->msg.type, b->last_out.seq, reply, cap);
    }
}

size_t ffr_board_link_on_bad_frame(ffr_board_link_t *b, int status, uint8_t *reply, size_t cap)
{
    uint8_t code = FFR_ERR_FRAMING;
    b->rx_errors++;
    if (status == FFR_E_CRC) {
        code = FFR_ERR_CRC;
    } else if (status == FFR_E_SEGMENT) {
        code = FFR_ERR_SEGMENT;
    }
    return error_reply(b, code, (uint8_t)(-status), b->last_out.seq, reply, cap);
}

size_t ffr_board_link_poll(ffr_board_link_t *b, uint32_t now_ms, uint8_t *reply, size_t cap)
{
    if (b->watchdog_ms == 0u || !b->have_out || b->tripped) {
        return 0u;
    }
    if ((uint32_t)(now_ms - b->last_rx_ms) <= b->watchdog_ms) {
        return 0u;
    }
    b->tripped = 1u;
    b->watchdog_trips++;
    stop_actuators(b);
    return error_reply(b, FFR_ERR_WATCHDOG, 0u, b->last_out.seq, reply, cap);
}

void ffr_board_link_actuators(const ffr_board_link_t *b, int16_t pwm[2], uint8_t *fan)
{
    pwm[0] = b->pwm[0];
    pwm[1] = b->pwm[1];
    *fan = b->fan;
}

size_t ffr_board_link_sizeof(void) { return sizeof(ffr_board_link_t); }
