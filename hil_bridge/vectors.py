"""The shared wire test vectors: written by this (Python) codec, checked by
the C codec's tests (``firmware/tests/wire/test_vectors.c``) and, for
staleness, by pytest (``tests/bridge/test_codec.py``).

    python -m hil_bridge.vectors > tests/bridge/vectors/wire_vectors.txt

One vector per line: ``kind input expected`` (hex), where kind is crc, cobs,
frame, msg, can, canfd or bad (a frame and the status both codecs must give).
"""

from __future__ import annotations

import sys

import numpy as np

from hil_bridge import cobs, codec
from hil_bridge.broken_pipe import exit_with
from hil_bridge.codec import MsgType
from hil_bridge.crc import crc16
from hil_bridge.errors import DecodeError, Status


def _fill(rec: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Every field of a record set to a finite value of its type, negatives included."""
    for name in rec.dtype.names or ():
        sub = rec[name]
        dt = sub.dtype
        if dt.names:  # the array of route steps: field by field over all steps
            _fill(sub, rng)
            continue
        if dt.kind == "f":
            sub[...] = (rng.normal(0, 300, sub.shape)).astype(dt)
        else:
            info = np.iinfo(dt)
            sub[...] = rng.integers(info.min, info.max, sub.shape, endpoint=True, dtype=np.int64).astype(dt)
    return rec


def sample_messages(rng: np.random.Generator) -> list[bytes]:
    out = []
    for t in MsgType:
        rec = np.zeros((), dtype=codec.NATIVE.get(t, codec.BODY_WIRE[t]))
        out.append(codec.encode_msg(t, rec))  # all zero
        out.append(codec.encode_msg(t, _fill(rec, rng)))
    out.append(codec.encode_msg(MsgType.HELLO, codec.record(MsgType.HELLO, proto=1, watchdog_ms=250)))
    out.append(codec.encode_msg(MsgType.ERROR, codec.record(MsgType.ERROR, code=8, seq=1234)))
    return out


def _status_of(frame: bytes) -> int:
    try:
        codec.decode_msg(codec.frame_decode(frame))
    except DecodeError as exc:
        return int(exc.status)
    return int(Status.OK)


def generate() -> list[str]:
    rng = np.random.default_rng(20240601)
    lines = ["# ffr wire test vectors (python -m hil_bridge.vectors); docs/protocol.md"]
    crc_inputs = [b"123456789", b"", b"\x00", bytes(range(256)), rng.bytes(33)]
    lines += [f"crc {d.hex() or '-'} {crc16(d):04x}" for d in crc_inputs]
    nz = bytes((i % 255) + 1 for i in range(600))
    cobs_inputs = [b"", b"\x00", b"\x00\x00", b"\x11\x22\x00\x33", b"\x11\x00", nz[:253], nz[:254], nz[:255],
                   nz[:254] + b"\x00", b"\x00" + nz[:254], nz[:508], nz[:600], rng.bytes(300),
                   bytes(rng.integers(0, 3, 200, dtype=np.uint8))]
    lines += [f"cobs {d.hex() or '-'} {cobs.encode(d).hex()}" for d in cobs_inputs]
    msgs = sample_messages(rng)
    for m in msgs:
        lines.append(f"msg {m.hex()} -")
        lines.append(f"frame {m.hex()} {codec.frame_encode(m).hex()}")
        for kind, fd in (("can", False), ("canfd", True)):
            frames = ",".join(f"{cid:03x}:{data.hex()}" for cid, data in codec.can_frames(m, fd))
            lines.append(f"{kind} {m.hex()} {frames}")
    # bad frames: flipped bits, cut short, glued, garbage; the status is what this codec says
    good = [codec.frame_encode(m)[:-1] for m in msgs[:8]]
    bad = [b"\x01", b"\x02\x05\x01", b"\x05\x01\x02", good[3][:-1], good[3] + good[4], b"\x01" * (codec.FRAME_MAX + 1)]
    for g in good:
        for _ in range(3):
            b = bytearray(g)
            i = int(rng.integers(len(b)))
            b[i] ^= 1 << int(rng.integers(8))
            if 0 not in b:
                bad.append(bytes(b))
    # well-framed messages the message layer must refuse: unknown type, wrong length
    bad.append(codec.frame_encode(b"\x63" + bytes(24))[:-1])
    bad.append(codec.frame_encode(b"\x03" + bytes(31))[:-1])
    lines += [f"bad {b.hex()} {_status_of(b)}" for b in bad]
    return lines


def main() -> None:
    sys.stdout.write("\n".join(generate()) + "\n")


if __name__ == "__main__":
    exit_with(main)
