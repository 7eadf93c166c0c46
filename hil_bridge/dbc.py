"""The DBC description of our CAN traffic, generated from the codec's own
tables so it cannot drift from the wire; ``hil_bridge/ffr.dbc`` is its
checked-in output (a test keeps the two equal, and decodes real traffic
with cantools).

    python -m hil_bridge.dbc > hil_bridge/ffr.dbc

Every segment of every message type is a DBC message (``FFR_INPUTS_S2``,
``FFR_OUTPUTS_S0_FD``, ...) whose signals are the struct fields that fall in
it, little-endian, plus ``crc`` (big-endian) in the last one. A field never
straddles two segments: every field is naturally aligned and at most 4
bytes, and segments are 8 or 64 bytes.
"""

from __future__ import annotations

import sys
from collections import OrderedDict

import numpy as np
from cantools.database.can import Database, Message, Node, Signal
from cantools.database.can.formats.dbc import DbcAttribute, DbcAttributeDefinition, DbcSpecifics

from hil_bridge import codec
from hil_bridge.broken_pipe import exit_with
from hil_bridge.codec import BOARD_TO_HOST, BODY_WIRE, MsgType

HOST, BOARD = "HOST", "BOARD"


def _flatten(dt: np.dtype, prefix: str = "", base: int = 0) -> list[tuple[str, int, np.dtype]]:
    """Scalar fields of a packed dtype: (name, byte offset, scalar dtype)."""
    out = []
    for name in dt.names or ():
        sub, off = dt.fields[name][:2]  # type: ignore[index]
        off += base
        if sub.subdtype is not None:
            elem, shape = sub.subdtype
            for k in range(int(np.prod(shape))):
                at = off + k * elem.itemsize
                if elem.names:
                    out += _flatten(elem, f"{prefix}{name}_{k}_", at)
                else:
                    out.append((f"{prefix}{name}_{k}", at, elem))
        elif sub.names:
            out += _flatten(sub, f"{prefix}{name}_", off)
        else:
            out.append((f"{prefix}{name}", off, sub))
    return out


def _signal(name: str, offset: int, dt: np.dtype) -> Signal:
    s = Signal(name, start=offset * 8, length=dt.itemsize * 8, byte_order="little_endian",
               is_signed=dt.kind == "i" or dt.kind == "f")
    if dt.kind == "f":
        s.is_float = True
    return s


def build() -> Database:
    messages = []
    for t in MsgType:
        wire = BODY_WIRE[t]
        fields = _flatten(wire)
        total = wire.itemsize + 2
        sender, receiver = (BOARD, HOST) if t in BOARD_TO_HOST else (HOST, BOARD)
        for fd in (False, True):
            chunk = 64 if fd else 8
            nseg = codec.can_frame_count(t, fd)
            for seg in range(nseg):
                lo, n = seg * chunk, min(chunk, total - seg * chunk)
                sigs = [_signal(name, off - lo, dt) for name, off, dt in fields if lo <= off < lo + n]
                if lo <= wire.itemsize < lo + n:  # the CRC-16, big-endian (Motorola: start at its MSB)
                    sigs.append(Signal("crc", start=(wire.itemsize - lo) * 8 + 7, length=16,
                                       byte_order="big_endian"))
                for s in sigs:
                    s.receivers = [receiver]
                name = f"FFR_{t.name}" + (f"_S{seg}" if nseg > 1 else "") + ("_FD" if fd else "")
                messages.append(Message(
                    frame_id=codec.can_id(t, seg, fd), name=name,
                    length=codec.fd_round_up(n) if fd else n, signals=sigs, senders=[sender], is_fd=fd,
                    comment=f"ffr {t.name} segment {seg + 1} of {nseg}" + (" (CAN FD)" if fd else "")))
    # BusType "CAN FD" makes cantools mark each FD message with VFrameFormat, so the flag survives a load
    bus_type = DbcAttributeDefinition("BusType", default_value="CAN", type_name="STRING")
    dbc = DbcSpecifics(attributes=OrderedDict(BusType=DbcAttribute("CAN FD", bus_type)),
                       attribute_definitions=OrderedDict(BusType=bus_type))
    return Database(messages=messages, nodes=[Node(HOST, "the test harness"), Node(BOARD, "the robot's board")],
                    version=f"ffr-proto-{codec.PROTO_VERSION}", dbc_specifics=dbc)


def dbc_text() -> str:
    return build().as_dbc_string()


def main() -> None:
    sys.stdout.write(dbc_text())


if __name__ == "__main__":
    exit_with(main)
