"""The C codec and board link of the host library, through ctypes.

Used by the CAN board (which runs the very C code a CAN microcontroller
would) and by the tests that check the Python codec against the C one.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ffr_link.ctypes_link import library_path, load_library
from hil_bridge.codec import FRAME_MAX, MSG_MAX
from hil_bridge.errors import DecodeError, Status

_u8p = ctypes.POINTER(ctypes.c_uint8)
_sz = ctypes.c_size_t
_szp = ctypes.POINTER(ctypes.c_size_t)
_vp = ctypes.c_void_p

_SIGNATURES = {
    "ffr_crc16": (ctypes.c_uint16, [ctypes.c_char_p, _sz]),
    "ffr_cobs_encode": (_sz, [ctypes.c_char_p, _sz, _u8p, _sz]),
    "ffr_cobs_decode": (ctypes.c_int, [ctypes.c_char_p, _sz, _u8p, _sz, _szp]),
    "ffr_frame_encode": (_sz, [ctypes.c_char_p, _sz, _u8p, _sz]),
    "ffr_frame_decode": (ctypes.c_int, [ctypes.c_char_p, _sz, _u8p, _sz, _szp]),
    "ffr_msg_encode": (_sz, [_vp, _u8p, _sz]),
    "ffr_msg_decode": (ctypes.c_int, [ctypes.c_char_p, _sz, _vp]),
    "ffr_wire_size": (_sz, [ctypes.c_uint32]),
    "ffr_can_frame": (ctypes.c_int, [ctypes.c_char_p, _sz, ctypes.c_int, ctypes.c_uint32,
                                     ctypes.POINTER(ctypes.c_uint32), _u8p, _u8p]),
    "ffr_can_rx_init": (None, [_vp]),
    "ffr_can_rx_push": (ctypes.c_int, [_vp, ctypes.c_uint32, ctypes.c_char_p, ctypes.c_uint8, _u8p, _sz, _szp]),
    "ffr_can_rx_sizeof": (_sz, []),
    "ffr_deframer_init": (None, [_vp]),
    "ffr_board_link_init": (None, [_vp, ctypes.c_uint32, ctypes.c_uint32]),
    "ffr_board_link_on_msg": (_sz, [_vp, ctypes.c_char_p, _sz, ctypes.c_uint32, _u8p, _sz]),
    "ffr_board_link_on_bad_frame": (_sz, [_vp, ctypes.c_int, _u8p, _sz]),
    "ffr_board_link_poll": (_sz, [_vp, ctypes.c_uint32, _u8p, _sz]),
    "ffr_board_link_actuators": (None, [_vp, ctypes.POINTER(ctypes.c_int16), _u8p]),
    "ffr_board_link_sizeof": (_sz, []),
}


@lru_cache(maxsize=4)
def wire_library(path: str | None = None) -> ctypes.CDLL:
    """The host library with its wire functions declared (the layout checked as for ctypes:)."""
    lib, _ = load_library(str(library_path(path)))
    for name, (res, args) in _SIGNATURES.items():
        fn = getattr(lib, name)
        fn.restype = res
        fn.argtypes = args
    return lib


def _buf(n: int) -> ctypes.Array:
    return (ctypes.c_uint8 * n)()


def _status(rc: int, what: str) -> None:
    if rc != 0:
        raise DecodeError(Status(rc), f"C codec: {what}")


class CCodec:
    """The C codec with Python types, for cross-checks."""

    def __init__(self, lib: ctypes.CDLL | None = None) -> None:
        self.lib = lib or wire_library()

    def crc16(self, data: bytes) -> int:
        return self.lib.ffr_crc16(data, len(data))

    def cobs_encode(self, data: bytes) -> bytes:
        out = _buf(len(data) + len(data) // 254 + 2)
        n = self.lib.ffr_cobs_encode(data, len(data), out, len(out))
        if n == 0:
            raise ValueError("C codec refused to COBS-encode")
        return bytes(out[:n])

    def cobs_decode(self, block: bytes) -> bytes:
        out, n = _buf(len(block) + 1), ctypes.c_size_t()
        _status(self.lib.ffr_cobs_decode(block, len(block), out, len(out), ctypes.byref(n)), "COBS")
        return bytes(out[:n.value])

    def frame_encode(self, msg: bytes) -> bytes:
        out = _buf(FRAME_MAX)
        n = self.lib.ffr_frame_encode(msg, len(msg), out, len(out))
        if n == 0:
            raise ValueError("C codec refused to frame the message")
        return bytes(out[:n])

    def frame_decode(self, frame: bytes) -> bytes:
        out, n = _buf(MSG_MAX + 2), ctypes.c_size_t()
        _status(self.lib.ffr_frame_decode(frame, len(frame), out, len(out), ctypes.byref(n)), "frame")
        return bytes(out[:n.value])

    def msg_roundtrip(self, msg: bytes) -> bytes:
        """Decode with C into ffr_msg_t, encode again with C."""
        m = _buf(MSG_MAX + 16)  # ffr_msg_t: type byte, padding, the largest union member (the config)
        _status(self.lib.ffr_msg_decode(msg, len(msg), m), "message")
        out = _buf(MSG_MAX)
        n = self.lib.ffr_msg_encode(m, out, len(out))
        return bytes(out[:n])

    def can_frames(self, msg: bytes, fd: bool) -> list[tuple[int, bytes]]:
        frames, k = [], 0
        cid, data, dlen = ctypes.c_uint32(), _buf(64), ctypes.c_uint8()
        while True:
            rc = self.lib.ffr_can_frame(msg, len(msg), int(fd), k, ctypes.byref(cid), data, ctypes.byref(dlen))
            if rc == 0:
                return frames
            _status(rc if rc < 0 else 0, "CAN frame")
            frames.append((cid.value, bytes(data[:dlen.value])))
            k += 1

    def can_reassemble(self, frames: list[tuple[int, bytes]]) -> bytes | None:
        rx = _buf(self.lib.ffr_can_rx_sizeof())
        self.lib.ffr_can_rx_init(rx)
        out, n = _buf(MSG_MAX), ctypes.c_size_t()
        result = None
        for cid, data in frames:
            rc = self.lib.ffr_can_rx_push(rx, cid, data, len(data), out, len(out), ctypes.byref(n))
            _status(rc if rc < 0 else 0, f"CAN id 0x{cid:03X}")
            result = bytes(out[:n.value]) if rc == 1 else None
        return result


@dataclass
class CBoardLink:
    """One ffr_board_link_t (firmware state, watchdog) driven from Python: the CAN board's brain."""

    watchdog_ms: int
    now_ms: int
    lib: ctypes.CDLL = field(default_factory=wire_library)

    def __post_init__(self) -> None:
        size = self.lib.ffr_board_link_sizeof()
        self._mem = np.zeros((size + 7) // 8, dtype=np.uint64)  # 8-byte aligned
        self._ptr = self._mem.ctypes.data
        self._reply = _buf(MSG_MAX)
        self.lib.ffr_board_link_init(self._ptr, self.watchdog_ms, self.now_ms & 0xFFFFFFFF)

    def _out(self, n: int) -> bytes | None:
        return bytes(self._reply[:n]) if n else None

    def on_msg(self, msg: bytes, now_ms: int) -> bytes | None:
        return self._out(self.lib.ffr_board_link_on_msg(self._ptr, msg, len(msg), now_ms & 0xFFFFFFFF,
                                                        self._reply, MSG_MAX))

    def on_bad_frame(self, status: int) -> bytes | None:
        return self._out(self.lib.ffr_board_link_on_bad_frame(self._ptr, status, self._reply, MSG_MAX))

    def poll(self, now_ms: int) -> bytes | None:
        return self._out(self.lib.ffr_board_link_poll(self._ptr, now_ms & 0xFFFFFFFF, self._reply, MSG_MAX))

    def actuators(self) -> tuple[int, int, int]:
        pwm, fan = (ctypes.c_int16 * 2)(), ctypes.c_uint8()
        self.lib.ffr_board_link_actuators(self._ptr, pwm, ctypes.byref(fan))
        return pwm[0], pwm[1], fan.value


class CCanRx:
    """One ffr_can_rx_t: the CAN board's reassembler in C."""

    def __init__(self, lib: ctypes.CDLL) -> None:
        self.lib = lib
        self._mem = _buf(lib.ffr_can_rx_sizeof())
        lib.ffr_can_rx_init(self._mem)
        self._out = _buf(MSG_MAX)
        self._n = ctypes.c_size_t()

    def push(self, cid: int, data: bytes) -> bytes | int | None:
        """The message when complete, None when more is needed, a negative status on a bad frame."""
        rc = self.lib.ffr_can_rx_push(self._mem, cid, data, len(data), self._out, MSG_MAX, ctypes.byref(self._n))
        if rc == 1:
            return bytes(self._out[:self._n.value])
        return None if rc == 0 else rc
