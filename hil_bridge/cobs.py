"""COBS (Consistent Overhead Byte Stuffing): frames without a zero byte.

The same algorithm as ``firmware/codec/cobs.c``, written for Python: a block
is a series of runs, each a code byte (run length + 1) and up to 254 non-zero
bytes; a run shorter than 254 stands for "these bytes, then a zero" unless it
ends the block. A full run that ends the data gets no trailing code, as in C.
"""

from __future__ import annotations

from hil_bridge.errors import DecodeError, Status


def encode(data: bytes) -> bytes:
    out = bytearray()
    parts = bytes(data).split(b"\x00")
    last = len(parts) - 1
    for i, part in enumerate(parts):
        while len(part) >= 254:
            out.append(0xFF)
            out += part[:254]
            part = part[254:]
            if not part and i == last:
                return bytes(out)  # a full run ends the data: no trailing code
        out.append(len(part) + 1)
        out += part
    return bytes(out)


def decode(block: bytes, cap: int | None = None) -> bytes:
    """Decode one block. With ``cap``, more than cap bytes of output is Status.LONG, found at the
    same point as the C decoder with a cap-byte buffer (so a damaged frame gets the same verdict)."""
    n = len(block)
    if n == 0:
        raise DecodeError(Status.SHORT, "empty COBS block")
    out = bytearray()
    i = 0
    while i < n:
        code = block[i]
        if code == 0:
            raise DecodeError(Status.COBS, f"zero byte at {i}")
        run = block[i + 1:i + code]
        if len(run) != code - 1:
            raise DecodeError(Status.COBS, f"run at {i} claims {code - 1} bytes, {len(run)} left")
        if cap is not None and len(out) + len(run) > cap:
            raise DecodeError(Status.LONG, f"more than {cap} bytes decoded")
        if 0 in run:
            raise DecodeError(Status.COBS, f"zero byte inside the run at {i}")
        out += run
        i += code
        if code != 0xFF and i < n:
            if cap is not None and len(out) >= cap:
                raise DecodeError(Status.LONG, f"more than {cap} bytes decoded")
            out.append(0)
    return bytes(out)
