"""The DBC file: generated from the codec, loaded by cantools, and decoding
real traffic between the harness and a CAN board (classic and FD)."""

from __future__ import annotations

import itertools
from pathlib import Path

import can
import cantools
import pytest

from ffr_link import open_link
from harness.loop import run_mission
from hil_bridge import codec, dbc
from hil_bridge.can_board import CanBoard
from hil_bridge.crc import crc16
from tests.bridge.conftest import short_scenario

DBC = Path(dbc.__file__).parent / "ffr.dbc"
_chan = itertools.count()


def test_checked_in_dbc_is_current() -> None:
    assert DBC.read_bytes().decode() == dbc.dbc_text(), "stale: python -m hil_bridge.dbc > hil_bridge/ffr.dbc"


def test_every_segment_of_every_message_is_described() -> None:
    db = cantools.database.load_file(str(DBC))
    for t in codec.MsgType:
        for fd in (False, True):
            for seg in range(codec.can_frame_count(t, fd)):
                m = db.get_message_by_frame_id(codec.can_id(t, seg, fd))
                assert m.is_fd == fd and not m.is_extended_frame
    inputs = db.get_message_by_name("FFR_INPUTS_S0")
    assert [s.name for s in inputs.signals] == ["t_ms", "seq"] and inputs.frame_id == 0x180
    assert db.get_message_by_name("FFR_RESET_S0").get_signal_by_name("wheel_radius_mm").is_float


@pytest.mark.parametrize("fd", [False, True], ids=["classic", "fd"])
def test_cantools_decodes_our_traffic(fd: bool) -> None:
    db = cantools.database.load_file(str(DBC))
    channel = f"ffr-dbc-test-{next(_chan)}"
    board_bus = can.Bus(interface="virtual", channel=channel)
    spy = can.Bus(interface="virtual", channel=channel)  # a third node that only listens
    board = CanBoard(board_bus, fd=fd)
    board.start()
    link = open_link(f"can:virtual:{channel}" + ("#fd=1" if fd else ""))
    try:
        res, trace = run_mission(short_scenario(seconds=2.0), link)
    finally:
        link.close()
        board.stop()
        board_bus.shutdown()
    frames = []
    while (m := spy.recv(timeout=0)) is not None:
        frames.append(m)
    spy.shutdown()
    n = len(trace.i)
    assert n > 150 and res.detail == "flame still burning after 2 s"

    decoded = [(db.get_message_by_frame_id(m.arbitration_id).name, db.decode_message(
        m.arbitration_id, bytes(m.data), decode_choices=False)) for m in frames]
    sfx = "_FD" if fd else "_S0"
    # a busy machine may make the link send a frame again: the same seq, the same content
    ins = {d["seq"]: d["t_ms"] for name, d in decoded if name == "FFR_INPUTS" + sfx}
    assert ins == {k: 10 * k for k in range(n)}
    outs = {d["seq"]: (d["pwm_0"], d["pwm_1"]) for name, d in decoded if name == "FFR_OUTPUTS" + sfx}
    assert [outs[k] for k in range(n)] == [tuple(map(int, row)) for row in trace.actuators[:, :2]]
    names = {name for name, _ in decoded}
    fdx = "_FD" if fd else ""
    assert {f"FFR_HELLO{fdx}", f"FFR_INFO{fdx or '_S0'}", f"FFR_READY{fdx}"} <= names
    # the CRC signal is the CRC-16 over type + body
    ra = codec.CanReassembler()
    for m, (name, d) in zip(frames, decoded, strict=True):
        if name.startswith("FFR_OUTPUTS") and "crc" in d:
            msg = ra.push(m.arbitration_id, bytes(m.data))
            assert msg is not None and d["crc"] == crc16(msg)
        elif name.startswith("FFR_OUTPUTS"):
            assert ra.push(m.arbitration_id, bytes(m.data)) is None
