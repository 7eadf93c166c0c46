"""CRC-16/IBM-3740 (a.k.a. CRC-16/CCITT-FALSE), the CRC of every frame.

Width 16, polynomial 0x1021, initial value 0xFFFF, no reflection, no final
XOR; check value 0x29B1 for b"123456789". The standard library computes it:
``binascii.crc_hqx`` is this CRC with the initial value as its argument.
"""

from __future__ import annotations

import binascii

CHECK = 0x29B1


def crc16(data: bytes | bytearray | memoryview) -> int:
    return binascii.crc_hqx(data, 0xFFFF)


def append_crc(data: bytes) -> bytes:
    """``data`` followed by its CRC, big-endian: the CRC over the result is 0."""
    c = crc16(data)
    return data + bytes((c >> 8, c & 0xFF))


def crc_ok(data_with_crc: bytes | bytearray) -> bool:
    return crc16(data_with_crc) == 0
