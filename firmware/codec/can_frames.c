/*
 * CAN: a message's body and its CRC-16 (over type + body, as on serial) cut
 * into segments of 8 bytes (classic CAN) or 64 bytes (CAN FD). The type and
 * segment index are the 11-bit identifier (type << 7 | segment, FD adds
 * FFR_CAN_FD_BIT), so every segment has its own DBC entry with real signals,
 * and a lower segment also wins arbitration: a controller with several
 * transmit buffers still sends them in order. The bus's own CRC-15 guards
 * each frame; the CRC-16 guards the reassembled message end to end.
 */
#include "ffr_codec.h"

static const uint8_t k_fd_len[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64};

static uint8_t fd_round_up(size_t n)
{
    size_t i;
    for (i = 0; i < sizeof(k_fd_len); ++i) {
        if (k_fd_len[i] >= n) {
            return k_fd_len[i];
        }
    }
    return 64u;
}

uint32_t ffr_can_id(uint8_t type, uint32_t segment, int fd)
{
    return ((uint32_t)type << FFR_CAN_SEG_BITS) | (segment & (FFR_CAN_SEG_MAX - 1u)) | (fd ? FFR_CAN_FD_BIT : 0u);
}

uint32_t ffr_can_frame_count(uint8_t type, int fd)
{
    size_t body = ffr_msg_body_size(type);
    size_t chunk = fd ? 64u : 8u;
    if (body == 0u) {
        return 0u;
    }
    return (uint32_t)((body + 2u + chunk - 1u) / chunk);
}

int ffr_can_frame(const uint8_t *msg, size_t len, int fd, uint32_t index, uint32_t *id, uint8_t data[64],
                  uint8_t *dlen)
{
    size_t chunk = fd ? 64u : 8u;
    size_t body;
    size_t total;
    size_t start;
    size_t n;
    size_t i;
    uint16_t crc;
    if (msg == NULL || len < 1u) {
        return FFR_E_SHORT;
    }
    body = ffr_msg_body_size(msg[0]);
    if (body == 0u) {
        return FFR_E_TYPE;
    }
    if (len != 1u + body) {
        return FFR_E_LENGTH;
    }
    total = body + 2u; /* body, then the CRC big-endian */
    start = (size_t)index * chunk;
    if (start >= total) {
        return 0;
    }
    crc = ffr_crc16(msg, len);
    n = total - start < chunk ? total - start : chunk;
    for (i = 0; i < n; ++i) {
        size_t at = start + i;
        if (at < body) {
            data[i] = msg[1u + at];
        } else {
            data[i] = at == body ? (uint8_t)(crc >> 8) : (uint8_t)crc;
        }
    }
    *dlen = (uint8_t)n;
    if (fd) {
        *dlen = fd_round_up(n);
        for (i = n; i < *dlen; ++i) {
            data[i] = 0u;
        }
    }
    *id = ffr_can_id(msg[0], index, fd);
    return 1;
}

void ffr_can_rx_init(ffr_can_rx_t *r)
{
    r->have = 0;
    r->type = 0;
    r->next = 0;
}

int ffr_can_rx_push(ffr_can_rx_t *r, uint32_t id, const uint8_t *data, uint8_t dlen, uint8_t *msg, size_t cap,
                    size_t *msg_len)
{
    int fd = (id & FFR_CAN_FD_BIT) != 0u;
    uint8_t type = (uint8_t)((id & ~FFR_CAN_FD_BIT) >> FFR_CAN_SEG_BITS);
    uint32_t seg = id & (FFR_CAN_SEG_MAX - 1u);
    size_t chunk = fd ? 64u : 8u;
    size_t body = ffr_msg_body_size(type);
    size_t total = body + 2u;
    size_t want;
    size_t i;
    *msg_len = 0;
    if (id > 0x7FFu || body == 0u || seg >= ffr_can_frame_count(type, fd)) {
        ffr_can_rx_init(r);
        return FFR_E_SEGMENT;
    }
    if (seg == 0u) { /* a new message starts; any partial one is abandoned */
        r->type = type;
        r->have = 0;
        r->next = 0;
        r->buf[0] = type;
    } else if (r->type == 0u) {
        return 0; /* the rest of a message already given up on (or begun before we listened): once is enough */
    } else if (r->type == type && seg + 1u == r->next) {
        return 0; /* the segment just taken, again: CAN's double reception when an ACK was lost */
    } else if (r->type != type || r->next != seg) {
        ffr_can_rx_init(r);
        return FFR_E_SEGMENT;
    }
    want = total - (size_t)seg * chunk < chunk ? total - (size_t)seg * chunk : chunk;
    if (dlen < want || dlen > (fd ? 64u : 8u) || (!fd && dlen != want) || (fd && dlen != fd_round_up(want))) {
        ffr_can_rx_init(r);
        return FFR_E_LENGTH;
    }
    for (i = 0; i < want; ++i) {
        r->buf[1u + r->have + i] = data[i];
    }
    r->have = (uint16_t)(r->have + want);
    r->next = (uint8_t)(seg + 1u);
    if (r->have < total) {
        return 0;
    }
    /* complete: CRC over type + body + CRC is zero */
    if (ffr_crc16(r->buf, 1u + total) != 0u) {
        ffr_can_rx_init(r);
        return FFR_E_CRC;
    }
    if (cap < 1u + body) {
        ffr_can_rx_init(r);
        return FFR_E_LONG;
    }
    for (i = 0; i < 1u + body; ++i) {
        msg[i] = r->buf[i];
    }
    *msg_len = 1u + body;
    ffr_can_rx_init(r);
    return 1;
}

size_t ffr_can_rx_sizeof(void) { return sizeof(ffr_can_rx_t); }
