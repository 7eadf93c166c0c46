/*
 * CRC-16/IBM-3740 (often called CRC-16/CCITT-FALSE): width 16, poly 0x1021,
 * init 0xFFFF, no reflection, xorout 0x0000, check("123456789") = 0x29B1.
 * Bitwise, so no table in flash; a frame is at most a few hundred bytes.
 * Python's binascii.crc_hqx(data, 0xFFFF) computes the same CRC.
 */
#include "ffr_codec.h"

uint16_t ffr_crc16_update(uint16_t crc, const uint8_t *data, size_t len)
{
    size_t i;
    int b;
    for (i = 0; i < len; ++i) {
        crc = (uint16_t)(crc ^ (uint16_t)((uint16_t)data[i] << 8));
        for (b = 0; b < 8; ++b) {
            uint16_t top = (uint16_t)(crc & 0x8000u);
            crc = (uint16_t)(crc << 1);
            if (top != 0u) {
                crc = (uint16_t)(crc ^ 0x1021u);
            }
        }
    }
    return crc;
}

uint16_t ffr_crc16(const uint8_t *data, size_t len) { return ffr_crc16_update(0xFFFFu, data, len); }
