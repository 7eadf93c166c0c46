"""The Python codec against the C codec: the shared vectors, and hypothesis
round trips in both directions (Python encodes, C decodes through ctypes,
and the reverse), for COBS, CRC, messages, serial frames and CAN segments."""

from __future__ import annotations

import ctypes
import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hil_bridge import cobs, codec, vectors
from hil_bridge.codec import MsgType
from hil_bridge.crc import CHECK, crc16
from hil_bridge.errors import DecodeError, Status
from hil_bridge.native import CCodec

VECTORS = Path(__file__).parent / "vectors" / "wire_vectors.txt"
# random examples while developing (failures land in the hypothesis database); the same ones on CI
FAST = settings(max_examples=150, deadline=None, derandomize=bool(os.environ.get("CI")))


@pytest.fixture(scope="module")
def c() -> CCodec:
    return CCodec()


def test_vectors_file_is_what_the_python_codec_writes() -> None:
    assert VECTORS.read_text().splitlines() == vectors.generate(), (
        "stale: python -m hil_bridge.vectors > tests/bridge/vectors/wire_vectors.txt")


def _h(x: str) -> bytes:
    return b"" if x == "-" else bytes.fromhex(x)


def test_vectors_decode_in_python() -> None:
    """The decoding direction, from the file's bytes (the C tests check the same file)."""
    kinds: dict[str, int] = {}
    for line in VECTORS.read_text().splitlines():
        if line.startswith("#"):
            continue
        kind, a, b = line.split(" ")
        kinds[kind] = kinds.get(kind, 0) + 1
        if kind == "crc":
            assert crc16(_h(a)) == int(b, 16)
        elif kind == "cobs":
            assert cobs.decode(_h(b)) == _h(a)
        elif kind == "frame":
            assert _h(b)[-1] == 0 and codec.frame_decode(_h(b)[:-1]) == _h(a)
        elif kind == "msg":
            t, rec = codec.decode_msg(_h(a))
            assert codec.encode_msg(t, rec) == _h(a)
        elif kind in ("can", "canfd"):
            ra = codec.CanReassembler()
            got = [ra.push(int(i, 16), bytes.fromhex(d)) for i, d in (f.split(":") for f in b.split(","))]
            assert got[-1] == _h(a) and all(g is None for g in got[:-1])
        elif kind == "bad":
            with pytest.raises(DecodeError) as exc:
                codec.decode_msg(codec.frame_decode(_h(a)))
            assert int(exc.value.status) == int(b)
    assert kinds.keys() == {"crc", "cobs", "frame", "msg", "can", "canfd", "bad"}
    assert kinds["msg"] == len(MsgType) * 2 + 2 and kinds["bad"] >= 20


def test_crc_check_value_and_c_agree(c: CCodec) -> None:
    assert crc16(b"123456789") == CHECK == c.crc16(b"123456789") == 0x29B1


def test_layout_hash_is_the_library_s_and_wire_sizes_agree() -> None:
    from ffr_link.abi import contract_hash
    from ffr_link.ctypes_link import library_path, load_library

    lib, layout = load_library(str(library_path()))
    assert codec.layout_hash() == layout.layout_hash == contract_hash(layout)  # the documented recipe
    lib.ffr_wire_size.restype = ctypes.c_size_t
    lib.ffr_wire_size.argtypes = [ctypes.c_uint32]
    for sid in range(3):
        assert lib.ffr_wire_size(sid) == codec.wire_size(sid)
    assert lib.ffr_wire_size(16) == 8  # our route step, a sub-struct of the config
    assert lib.ffr_wire_size(99) == 0 and lib.ffr_wire_size(3) == 0  # the state; no such struct


@FAST
@given(st.binary(max_size=700))
def test_cobs_python_encodes_c_decodes_and_back(c: CCodec, data: bytes) -> None:
    enc = cobs.encode(data)
    assert 0 not in enc
    assert enc == c.cobs_encode(data)
    assert c.cobs_decode(enc) == data
    assert cobs.decode(c.cobs_encode(data)) == data


@FAST
@given(st.binary(max_size=300))
def test_crc_agrees(c: CCodec, data: bytes) -> None:
    assert crc16(data) == c.crc16(data)


@st.composite
def messages(draw: st.DrawFn) -> bytes:
    t = draw(st.sampled_from(list(MsgType)))
    return bytes((int(t),)) + draw(st.binary(min_size=codec.body_size(t), max_size=codec.body_size(t)))


@FAST
@given(messages())
def test_messages_python_to_c_and_c_to_python(c: CCodec, msg: bytes) -> None:
    # any body bytes are a valid message of its type: both codecs give the same bytes back
    t, rec = codec.decode_msg(msg)
    assert codec.encode_msg(t, rec) == msg
    assert c.msg_roundtrip(msg) == msg
    frame = codec.frame_encode(msg)
    assert frame == c.frame_encode(msg)
    assert c.frame_decode(frame[:-1]) == msg
    assert codec.frame_decode(c.frame_encode(msg)[:-1]) == msg


@FAST
@given(messages(), st.booleans())
def test_can_segments_python_to_c_and_c_to_python(c: CCodec, msg: bytes, fd: bool) -> None:
    frames = codec.can_frames(msg, fd)
    assert frames == c.can_frames(msg, fd)
    assert len(frames) == codec.can_frame_count(msg[0], fd)
    assert c.can_reassemble(frames) == msg
    ra = codec.CanReassembler()
    out = [ra.push(i, d) for i, d in c.can_frames(msg, fd)]
    assert out[-1] == msg


def _py_status(frame: bytes) -> int:
    try:
        codec.decode_msg(codec.frame_decode(frame))
    except DecodeError as exc:
        return int(exc.status)
    return 0


def _c_status(c: CCodec, frame: bytes) -> int:
    try:
        c.msg_roundtrip(c.frame_decode(frame))
    except DecodeError as exc:
        return int(exc.status)
    return 0


def test_a_damaged_code_byte_that_decodes_past_the_buffer_is_too_long_in_both(c: CCodec) -> None:
    """Hypothesis found it: the largest message (a RESET, long runs without zeros) with its first
    COBS code byte damaged decodes to more than MSG_MAX + 2 bytes; C stops at its buffer (LONG),
    and the Python mirror must say the same, not go on to a CRC verdict."""
    msg = bytes([int(MsgType.RESET)]) + bytes([1]) * (codec.MSG_MAX - 1)
    b = bytearray(codec.frame_encode(msg)[:-1])
    for bit in range(8):
        frame = bytearray(b)
        frame[0] ^= 1 << bit
        assert _py_status(bytes(frame)) == _c_status(c, bytes(frame)) == int(Status.LONG)


@FAST
@given(messages(), st.lists(st.tuples(st.integers(0, 10_000), st.integers(0, 7)), min_size=1, max_size=3),
       st.integers(0, 3))
def test_damaged_frames_get_the_same_verdict(c: CCodec, msg: bytes, flips, cut: int) -> None:
    b = bytearray(codec.frame_encode(msg)[:-1])
    for i, bit in flips:
        b[i % len(b)] ^= 1 << bit
    frame = bytes(b[:len(b) - cut])
    if 0 in frame:
        return  # a zero byte would end the frame on the wire: the deframer's business
    py, cc = _py_status(frame), _c_status(c, frame)
    assert py == cc
    assert py != 0 or codec.frame_decode(frame)[0] in {int(t) for t in MsgType}


@FAST
@given(st.binary(max_size=200))
def test_garbage_gets_the_same_verdict(c: CCodec, frame: bytes) -> None:
    frame = frame.replace(b"\x00", b"\x01")
    assert _py_status(frame) == _c_status(c, frame)


@FAST
@given(st.lists(messages(), min_size=1, max_size=5), st.integers(1, 40))
def test_deframer_finds_every_frame_in_any_chunking(msgs: list[bytes], chunk: int) -> None:
    stream = b"\x00\x00" + b"".join(codec.frame_encode(m) for m in msgs)
    d = codec.Deframer()
    got = []
    for k in range(0, len(stream), chunk):
        got += list(d.push(stream[k:k + chunk]))
    assert [codec.frame_decode(f) for f in got] == msgs


def test_overlong_frame_is_refused_and_the_next_one_found() -> None:
    d = codec.Deframer()
    hello = codec.encode_msg(MsgType.HELLO, codec.record(MsgType.HELLO, proto=1))
    got = list(d.push(b"\x01" * (codec.FRAME_MAX + 10) + b"\x00" + codec.frame_encode(hello)))
    assert isinstance(got[0], DecodeError) and got[0].status == Status.LONG
    assert len(got) == 2 and codec.frame_decode(got[1]) == hello


def test_native_structs_round_trip_exactly() -> None:
    from ffr_link.ctypes_link import default_config

    cfg = default_config()
    t, back = codec.decode_msg(codec.encode_msg(MsgType.RESET, cfg))
    assert t == MsgType.RESET and back.dtype == cfg.dtype and back.tobytes() == cfg.tobytes()
    inp = np.zeros((), dtype=codec.INPUTS_DTYPE)
    inp["seq"], inp["enc"], inp["ir_mv"] = 7, (-5, 9), (1, 2, 3, 4, 65535)
    msg = codec.encode_msg(MsgType.INPUTS, inp)
    assert len(msg) == 33 and msg[5] == 7 and msg[9:13] == (-5).to_bytes(4, "little", signed=True)
