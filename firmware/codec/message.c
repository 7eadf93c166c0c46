/*
 * Messages: one type byte, then a body whose size is fixed by the type
 * (docs/protocol.md). The small handshake bodies are written field by field;
 * the firmware structs go through the layout-driven wire codec.
 */
#include "ffr_codec.h"

static void put16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static void put32(uint8_t *p, uint32_t v)
{
    put16(p, (uint16_t)v);
    put16(p + 2, (uint16_t)(v >> 16));
}

static uint16_t get16(const uint8_t *p) { return (uint16_t)(p[0] | (uint16_t)(p[1] << 8)); }

static uint32_t get32(const uint8_t *p) { return (uint32_t)get16(p) | ((uint32_t)get16(p + 2) << 16); }

size_t ffr_msg_body_size(uint8_t type)
{
    switch (type) {
    case FFR_MSG_ERROR:
        return FFR_ERROR_SIZE;
    case FFR_MSG_OUTPUTS:
        return ffr_wire_size(FFR_S_OUTPUTS);
    case FFR_MSG_INPUTS:
        return ffr_wire_size(FFR_S_INPUTS);
    case FFR_MSG_INFO:
        return FFR_INFO_SIZE;
    case FFR_MSG_HELLO:
        return FFR_HELLO_SIZE;
    case FFR_MSG_READY:
        return FFR_READY_SIZE;
    case FFR_MSG_RESET: /* the firmware's config: refused beyond the contract's limit */
        return ffr_sizeof(FFR_S_CONFIG) <= FFR_CONFIG_MAX ? ffr_wire_size(FFR_S_CONFIG) : 0u;
    default:
        return 0u;
    }
}

size_t ffr_msg_encode(const ffr_msg_t *m, uint8_t *buf, size_t cap)
{
    size_t body = ffr_msg_body_size(m->type);
    uint8_t *b = buf + 1;
    if (body == 0u || cap < 1u + body) {
        return 0u;
    }
    buf[0] = m->type;
    switch (m->type) {
    case FFR_MSG_ERROR:
        b[0] = m->u.error.code;
        b[1] = m->u.error.detail;
        put16(b + 2, m->u.error.reserved);
        put32(b + 4, m->u.error.seq);
        break;
    case FFR_MSG_HELLO:
        put16(b, m->u.hello.proto);
        put16(b + 2, m->u.hello.watchdog_ms);
        break;
    case FFR_MSG_INFO:
        put16(b, m->u.info.proto);
        put16(b + 2, m->u.info.watchdog_ms);
        put32(b + 4, m->u.info.fw_version);
        put32(b + 8, m->u.info.layout_hash);
        put16(b + 12, m->u.info.inputs_size);
        put16(b + 14, m->u.info.outputs_size);
        put16(b + 16, m->u.info.config_size);
        put16(b + 18, m->u.info.reserved);
        break;
    case FFR_MSG_READY:
        put16(b, m->u.ready.config_crc);
        put16(b + 2, m->u.ready.reserved);
        break;
    case FFR_MSG_INPUTS:
        return ffr_wire_encode(FFR_S_INPUTS, &m->u.inputs, b, cap - 1u) == body ? 1u + body : 0u;
    case FFR_MSG_OUTPUTS:
        return ffr_wire_encode(FFR_S_OUTPUTS, &m->u.outputs, b, cap - 1u) == body ? 1u + body : 0u;
    default: /* FFR_MSG_RESET */
        return ffr_wire_encode(FFR_S_CONFIG, m->u.config, b, cap - 1u) == body ? 1u + body : 0u;
    }
    return 1u + body;
}

int ffr_msg_decode(const uint8_t *buf, size_t len, ffr_msg_t *m)
{
    const uint8_t *b = buf + 1;
    size_t body;
    size_t i;
    uint8_t *raw = (uint8_t *)m;
    for (i = 0; i < sizeof(*m); ++i) { /* padding and unsent fields read as zero */
        raw[i] = 0u;
    }
    if (len < 1u) {
        return FFR_E_SHORT;
    }
    body = ffr_msg_body_size(buf[0]);
    if (body == 0u) {
        return FFR_E_TYPE;
    }
    if (len != 1u + body) {
        return FFR_E_LENGTH;
    }
    m->type = buf[0];
    switch (m->type) {
    case FFR_MSG_ERROR:
        m->u.error.code = b[0];
        m->u.error.detail = b[1];
        m->u.error.reserved = get16(b + 2);
        m->u.error.seq = get32(b + 4);
        break;
    case FFR_MSG_HELLO:
        m->u.hello.proto = get16(b);
        m->u.hello.watchdog_ms = get16(b + 2);
        break;
    case FFR_MSG_INFO:
        m->u.info.proto = get16(b);
        m->u.info.watchdog_ms = get16(b + 2);
        m->u.info.fw_version = get32(b + 4);
        m->u.info.layout_hash = get32(b + 8);
        m->u.info.inputs_size = get16(b + 12);
        m->u.info.outputs_size = get16(b + 14);
        m->u.info.config_size = get16(b + 16);
        m->u.info.reserved = get16(b + 18);
        break;
    case FFR_MSG_READY:
        m->u.ready.config_crc = get16(b);
        m->u.ready.reserved = get16(b + 2);
        break;
    case FFR_MSG_INPUTS:
        return ffr_wire_decode(FFR_S_INPUTS, b, body, &m->u.inputs) == body ? FFR_OK : FFR_E_LENGTH;
    case FFR_MSG_OUTPUTS:
        return ffr_wire_decode(FFR_S_OUTPUTS, b, body, &m->u.outputs) == body ? FFR_OK : FFR_E_LENGTH;
    default: /* FFR_MSG_RESET */
        return ffr_wire_decode(FFR_S_CONFIG, b, body, m->u.config) == body ? FFR_OK : FFR_E_LENGTH;
    }
    return FFR_OK;
}
