"""The wire codec, Python side: the twin of ``firmware/include/ffr_codec.h``.

Layers (docs/protocol.md):

- struct <-> wire bytes: every field in layout order, little-endian, no
  padding (numpy "packed" dtypes derived from ``ffr_link.abi``);
- message = one type byte + a body of a size fixed by the type;
- serial frame = COBS(message || CRC-16 big-endian) || 0x00;
- CAN = (body || CRC-16) cut into 8-byte (classic) or 64-byte (FD) segments,
  identifier = type << 7 | segment (| 0x400 for FD).

The C codec and this one are checked against each other by shared vectors
(``tests/bridge/vectors/wire_vectors.txt``) and round trips through ctypes.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterator
from enum import IntEnum
from functools import lru_cache

import numpy as np

from ffr_link.abi import (
    CONFIG_MAX,
    INPUT_FIELDS,
    INPUTS_DTYPE,
    OUTPUT_FIELDS,
    OUTPUTS_DTYPE,
    S_CONFIG,
    S_INPUTS,
    S_OUTPUTS,
)
from hil_bridge import cobs
from hil_bridge.crc import append_crc, crc16
from hil_bridge.errors import DecodeError, Status

PROTO_VERSION = 1


class MsgType(IntEnum):
    ERROR = 1    # board -> host
    OUTPUTS = 2  # board -> host
    INPUTS = 3   # host -> board
    INFO = 4     # board -> host
    HELLO = 5    # host -> board
    READY = 6    # board -> host
    RESET = 7    # host -> board


BOARD_TO_HOST = frozenset({MsgType.ERROR, MsgType.OUTPUTS, MsgType.INFO, MsgType.READY})
_TYPES = {int(t): t for t in MsgType}


def _packed(fields: list[tuple[str, str, int]]) -> np.dtype:
    spec: list[tuple] = []
    for name, code, count in fields:
        base = np.dtype("<" + code)
        spec.append((name, base, (count,)) if count > 1 else (name, base))
    return np.dtype(spec)  # no align: packed, as on the wire


def packed(native: np.dtype) -> np.dtype:
    """The wire dtype of a struct dtype (a firmware's config read from its layout table): every
    field in table order, sub-structs packed alike, no padding."""
    spec: list[tuple] = []
    for name in native.names or ():
        dt = native.fields[name][0]  # type: ignore[index]
        base, shape = (dt.subdtype if dt.subdtype is not None else (dt, ()))
        base = packed(base) if base.names else base
        spec.append((name, base, shape) if shape else (name, base))
    return np.dtype(spec)


INPUTS_WIRE = _packed(INPUT_FIELDS)
OUTPUTS_WIRE = _packed(OUTPUT_FIELDS)
HELLO_WIRE = np.dtype([("proto", "<u2"), ("watchdog_ms", "<u2")])
INFO_WIRE = np.dtype([("proto", "<u2"), ("watchdog_ms", "<u2"), ("fw_version", "<u4"), ("layout_hash", "<u4"),
                      ("inputs_size", "<u2"), ("outputs_size", "<u2"), ("config_size", "<u2"),
                      ("reserved", "<u2")])
READY_WIRE = np.dtype([("config_crc", "<u2"), ("reserved", "<u2")])
ERROR_WIRE = np.dtype([("code", "u1"), ("detail", "u1"), ("reserved", "<u2"), ("seq", "<u4")])

_FIXED_WIRE: dict[MsgType, np.dtype] = {
    MsgType.ERROR: ERROR_WIRE, MsgType.OUTPUTS: OUTPUTS_WIRE, MsgType.INPUTS: INPUTS_WIRE,
    MsgType.INFO: INFO_WIRE, MsgType.HELLO: HELLO_WIRE, MsgType.READY: READY_WIRE,
}


def _same_bytes(native: np.dtype, wire: np.dtype) -> bool:
    """True when the aligned struct has no padding, so its bytes are the wire bytes (on little-endian)."""
    if sys.byteorder != "little" or native.itemsize != wire.itemsize:
        return False
    for name in wire.names or ():
        (nt, noff), (wt, woff) = native.fields[name][:2], wire.fields[name][:2]  # type: ignore[index]
        if noff != woff or nt.itemsize != wt.itemsize:
            return False
        if nt.subdtype is not None and nt.subdtype[0].names and not _same_bytes(nt.subdtype[0], wt.subdtype[0]):
            return False
    return True


class Wire:
    """The message bodies for one firmware: the fixed ones and the RESET body, its configuration
    (read from its layout table; ``docs/contract.md``). ``wire_for(config_dtype)`` caches one per
    firmware; the module's ``BODY_WIRE``, ``CONFIG_WIRE``... are those of the default firmware
    ($FFR_FIRMWARE_LIB, else ours), whose library is loaded on first use."""

    def __init__(self, config: np.ndarray | np.dtype) -> None:
        self.config_dtype = np.dtype(config)
        self.config_wire = packed(self.config_dtype)
        self.body_wire: dict[MsgType, np.dtype] = {**_FIXED_WIRE, MsgType.RESET: self.config_wire}
        # messages that carry a firmware struct: decoded into the harness's (aligned) dtype
        self.native: dict[MsgType, np.dtype] = {MsgType.OUTPUTS: OUTPUTS_DTYPE, MsgType.INPUTS: INPUTS_DTYPE,
                                                MsgType.RESET: self.config_dtype}
        self.raw_ok = {t: _same_bytes(d, self.body_wire[t]) for t, d in self.native.items()}


# Upper bounds, the same for every firmware (FFR_MSG_MAX, FFR_FRAME_MAX in ffr_codec.h): a message is
# the type byte and at most a config of the contract's largest (FFR_CONFIG_MAX); a serial frame adds
# the CRC, COBS overhead (one byte per 254) and the delimiter.
MSG_MAX = 1 + CONFIG_MAX
FRAME_MAX = MSG_MAX + 2 + (MSG_MAX + 2) // 254 + 2


_WIRES: dict[np.dtype, Wire] = {}
_DEFAULT: dict[str, Wire] = {}  # by $FFR_FIRMWARE_LIB


def wire_for(config: np.dtype | None = None) -> Wire:
    """The bodies for a firmware's config dtype (None: the default firmware's)."""
    if config is None:
        key = os.environ.get("FFR_FIRMWARE_LIB", "")
        w = _DEFAULT.get(key)
        if w is None:
            from ffr_link.ctypes_link import firmware_info

            w = _DEFAULT[key] = wire_for(firmware_info().config_dtype)
        return w
    w = _WIRES.get(config)
    if w is None:
        w = _WIRES[config] = Wire(config)
    return w


def __getattr__(name: str) -> object:  # PEP 562: the default firmware's bodies and sizes, on first use
    attrs = {"BODY_WIRE": "body_wire", "NATIVE": "native", "RAW_OK": "raw_ok", "CONFIG_WIRE": "config_wire",
             "CONFIG_DTYPE": "config_dtype"}
    if name in attrs:
        return getattr(wire_for(), attrs[name])
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def body_size(t: int, wire: Wire | None = None) -> int:
    mt = _TYPES.get(t)
    if mt is None:
        return 0
    if mt in _FIXED_WIRE:
        return _FIXED_WIRE[mt].itemsize
    return (wire or wire_for()).body_wire[mt].itemsize


def wire_size(struct_id: int, wire: Wire | None = None) -> int:
    if struct_id == S_CONFIG:
        return (wire or wire_for()).config_wire.itemsize
    return {S_INPUTS: INPUTS_WIRE, S_OUTPUTS: OUTPUTS_WIRE}[struct_id].itemsize


_NATIVE_FIXED = {MsgType.OUTPUTS: OUTPUTS_DTYPE, MsgType.INPUTS: INPUTS_DTYPE}


@lru_cache(maxsize=64)
def _raw_ok(native: np.dtype, wire: np.dtype) -> bool:
    return native == wire or _same_bytes(native, wire)


def encode_msg(t: MsgType, rec: np.ndarray) -> bytes:
    """Type byte + body from a record of the body's wire dtype or the native struct dtype; a RESET
    from a record of any firmware's config dtype (packed by its own fields)."""
    if t == MsgType.RESET:
        if not rec.dtype.names:
            raise TypeError(f"{t.name}: record of dtype {rec.dtype} cannot be encoded")
        native, wire = rec.dtype, packed(rec.dtype)
    else:
        wire, native = _FIXED_WIRE[t], _NATIVE_FIXED.get(t, _FIXED_WIRE[t])
    if rec.dtype == wire or rec.dtype == native and _raw_ok(native, wire):
        return bytes((int(t),)) + rec.tobytes()
    if rec.dtype == native:
        return bytes((int(t),)) + np.asarray(rec).astype(wire).tobytes()  # field by field, by position
    raise TypeError(f"{t.name}: record of dtype {rec.dtype} cannot be encoded")


def decode_msg(msg: bytes, wire_bodies: Wire | None = None) -> tuple[MsgType, np.ndarray]:
    """Type byte + body -> (type, 0-d record: the native struct dtype where there is one); a RESET
    by ``wire_bodies`` (default: the default firmware's)."""
    if len(msg) < 1:
        raise DecodeError(Status.SHORT, "empty message")
    t = _TYPES.get(msg[0])
    if t is None:
        raise DecodeError(Status.TYPE, f"unknown message type {msg[0]}")
    w = (wire_bodies or wire_for()) if t == MsgType.RESET else None
    wire = _FIXED_WIRE[t] if w is None else w.body_wire[t]
    if len(msg) != 1 + wire.itemsize:
        raise DecodeError(Status.LENGTH, f"{t.name}: body of {len(msg) - 1} bytes, {wire.itemsize} expected")
    rec = np.frombuffer(msg, dtype=wire, count=1, offset=1).reshape(())
    native = _NATIVE_FIXED.get(t) if w is None else w.config_dtype
    if native is not None:
        rec = rec.copy().view(native) if _raw_ok(native, wire) else rec.astype(native)
    return t, rec.copy()


def record(t: MsgType, **fields: int) -> np.ndarray:
    """A body record of type t with the given fields (the rest zero)."""
    native = _NATIVE_FIXED.get(t)
    if t == MsgType.RESET:
        native = wire_for().config_dtype
    rec = np.zeros((), dtype=native if native is not None else _FIXED_WIRE[t])
    for k, v in fields.items():
        rec[k] = v
    return rec


# ---- serial frames ---------------------------------------------------------------------------------------------
def frame_encode(msg: bytes) -> bytes:
    if not 1 <= len(msg) <= MSG_MAX:
        raise ValueError(f"message of {len(msg)} bytes (1..{MSG_MAX})")
    return cobs.encode(append_crc(msg)) + b"\x00"


def frame_decode(frame: bytes) -> bytes:
    """One frame without its delimiter -> the message; DecodeError with the C codec's status otherwise."""
    if len(frame) < 4:
        raise DecodeError(Status.SHORT, f"frame of {len(frame)} bytes")
    if len(frame) > FRAME_MAX:
        raise DecodeError(Status.LONG, f"frame of {len(frame)} bytes (at most {FRAME_MAX})")
    data = cobs.decode(frame, cap=MSG_MAX + 2)  # the buffer ffr_frame_decode's callers give it
    if len(data) < 3:
        raise DecodeError(Status.SHORT, f"{len(data)} bytes after COBS")
    if crc16(data) != 0:
        raise DecodeError(Status.CRC, f"CRC mismatch (got {data[-2:].hex()})")
    return data[:-2]


class Deframer:
    """Stream -> frames (without delimiters), like ffr_deframer_t but for chunks."""

    def __init__(self) -> None:
        self._buf = bytearray()

    def push(self, data: bytes) -> Iterator[bytes | DecodeError]:
        self._buf += data
        if 0 not in data:
            if len(self._buf) > FRAME_MAX:  # keep only the knowledge that it is too long
                del self._buf[FRAME_MAX + 1:]
            return
        *frames, rest = bytes(self._buf).split(b"\x00")
        self._buf = bytearray(rest)
        for f in frames:
            if not f:
                continue  # idle delimiters
            if len(f) > FRAME_MAX:
                yield DecodeError(Status.LONG, f"frame of more than {FRAME_MAX} bytes")
            else:
                yield f


# ---- CAN -------------------------------------------------------------------------------------------------------
CAN_FD_BIT = 0x400
CAN_SEG_BITS = 7
CAN_SEG_MAX = 1 << CAN_SEG_BITS
FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)


def fd_round_up(n: int) -> int:
    return next(v for v in FD_LENGTHS if v >= n)


def can_id(t: int, segment: int, fd: bool) -> int:
    return (t << CAN_SEG_BITS) | (segment & (CAN_SEG_MAX - 1)) | (CAN_FD_BIT if fd else 0)


def can_split_id(arbitration_id: int) -> tuple[int, int, bool]:
    """id -> (type, segment, fd)."""
    return (arbitration_id & ~CAN_FD_BIT) >> CAN_SEG_BITS, arbitration_id & (CAN_SEG_MAX - 1), bool(
        arbitration_id & CAN_FD_BIT)


def can_frame_count(t: int, fd: bool) -> int:
    n = body_size(t)
    chunk = 64 if fd else 8
    return 0 if n == 0 else (n + 2 + chunk - 1) // chunk


def can_frames(msg: bytes, fd: bool = False) -> list[tuple[int, bytes]]:
    """Message (type + body) -> [(identifier, data)], the CRC-16 after the body."""
    t = msg[0]
    if body_size(t) == 0:
        raise DecodeError(Status.TYPE, f"unknown message type {t}")
    if len(msg) != 1 + body_size(t):
        raise DecodeError(Status.LENGTH, f"message of {len(msg)} bytes for type {t}")
    c = crc16(msg)
    payload = msg[1:] + bytes((c >> 8, c & 0xFF))
    chunk = 64 if fd else 8
    out = []
    for k in range(0, len(payload), chunk):
        data = payload[k:k + chunk]
        if fd:
            data = data + bytes(fd_round_up(len(data)) - len(data))
        out.append((can_id(t, k // chunk, fd), data))
    return out


class CanReassembler:
    """Segments -> messages, like ffr_can_rx_t: in order, segment 0 starts a message."""

    def __init__(self) -> None:
        self._buf = bytearray()
        self._type = 0
        self._next = 0

    def reset(self) -> None:
        self._buf.clear()
        self._type = 0
        self._next = 0

    def push(self, arbitration_id: int, data: bytes) -> bytes | None:
        t, seg, fd = can_split_id(arbitration_id)
        n = body_size(t)
        if arbitration_id > 0x7FF or n == 0 or seg >= can_frame_count(t, fd):
            self.reset()
            raise DecodeError(Status.SEGMENT, f"CAN id 0x{arbitration_id:03X} is not ours")
        chunk = 64 if fd else 8
        if seg == 0:
            self._buf = bytearray((t,))
            self._type, self._next = t, 0
        elif self._type == 0:
            return None  # the rest of a message already given up on: reported once is enough
        elif self._type == t and seg + 1 == self._next:
            return None  # the segment just taken, again: CAN's double reception when an ACK was lost
        elif self._type != t or self._next != seg:
            want = self._next
            self.reset()
            raise DecodeError(Status.SEGMENT, f"CAN id 0x{arbitration_id:03X}: segment {seg}, {want} expected")
        total = n + 2
        want_len = min(chunk, total - seg * chunk)
        dlen = len(data)
        if dlen > chunk or (not fd and dlen != want_len) or (fd and dlen != fd_round_up(want_len)):
            self.reset()
            raise DecodeError(Status.LENGTH, f"CAN id 0x{arbitration_id:03X}: {dlen} bytes, {want_len} expected")
        self._buf += data[:want_len]
        self._next = seg + 1
        if len(self._buf) < 1 + total:
            return None
        msg = bytes(self._buf)
        self.reset()
        if crc16(msg) != 0:
            raise DecodeError(Status.CRC, f"CAN message type {t}: CRC mismatch")
        return msg[:-2]


# ---- the layout hash a board must report ----------------------------------------------------------------------
def layout_hash() -> int:
    """``ffr_layout_hash()`` of the host build ($FFR_FIRMWARE_LIB, else ours): a board must run the
    same firmware and report the same hash in its INFO (docs/contract.md, "Handshake")."""
    from ffr_link.ctypes_link import firmware_info

    return firmware_info().layout_hash
