"""The datagram link's framing (hil_bridge/datagram_link.py, docs/protocol.md "Over Ethernet"),
against a plain socket standing in for QEMU's network card: one serial frame per Ethernet
frame, padding after the delimiter ignored, other EtherTypes ignored, a payload without a
delimiter a decode error, a vanished peer a clear LinkError."""

from __future__ import annotations

import socket
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ffr_link.base import LinkError
from hil_bridge import codec
from hil_bridge.codec import MsgType
from hil_bridge.datagram_link import ETH_TYPE_FFR, HEADER, DatagramLink
from hil_bridge.errors import DecodeError
from hil_bridge.options import WireOptions


@pytest.fixture()
def pair(tmp_path: Path) -> Iterator[tuple[DatagramLink, socket.socket]]:
    board = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    board.bind(str(tmp_path / "board.sock"))
    board.settimeout(2.0)
    link = DatagramLink(tmp_path / "host.sock", tmp_path / "board.sock", WireOptions())
    link.url = "test:datagram"
    try:
        yield link, board
    finally:
        link.close()
        board.close()


def _board_header() -> bytes:
    return HEADER[6:12] + HEADER[:6] + ETH_TYPE_FFR.to_bytes(2, "big")


@settings(max_examples=30, deadline=None)
@given(body=st.binary(min_size=0, max_size=200), pad=st.integers(min_value=0, max_value=60))
def test_one_frame_per_datagram_both_ways_padding_ignored(tmp_path_factory: pytest.TempPathFactory,
                                                          body: bytes, pad: int) -> None:
    tmp = tmp_path_factory.mktemp("dgram")
    board = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    board.bind(str(tmp / "board.sock"))
    board.settimeout(2.0)
    link = DatagramLink(tmp / "host.sock", tmp / "board.sock", WireOptions())
    try:
        msg = bytes([MsgType.ERROR]) + body
        link._send_msg(msg)
        got = board.recv(4096)
        assert got == HEADER + codec.frame_encode(msg)  # the header, then exactly the serial frame
        board.sendto(_board_header() + codec.frame_encode(msg) + bytes(pad), str(tmp / "host.sock"))
        assert link._recv_msg(2.0) == msg
        assert link._recv_msg(0.0) is None  # the padding made no second message
    finally:
        link.close()
        board.close()


def test_other_ethertypes_are_not_ours(pair: tuple[DatagramLink, socket.socket], tmp_path: Path) -> None:
    link, board = pair
    msg = bytes([MsgType.ERROR]) + bytes(8)
    board.sendto(HEADER[:12] + (0x0800).to_bytes(2, "big") + codec.frame_encode(msg), str(tmp_path / "host.sock"))
    board.sendto(b"short", str(tmp_path / "host.sock"))
    assert link._recv_msg(0.2) is None


@pytest.mark.parametrize("payload", [b"\x03ab", b"\x00\x03ab\x00"])
def test_a_datagram_without_a_whole_frame_is_a_decode_error(pair: tuple[DatagramLink, socket.socket],
                                                             tmp_path: Path, payload: bytes) -> None:
    link, board = pair
    board.sendto(_board_header() + payload, str(tmp_path / "host.sock"))
    with pytest.raises(DecodeError):
        link._recv_msg(2.0)


def test_a_vanished_peer_is_one_clear_line(pair: tuple[DatagramLink, socket.socket]) -> None:
    link, board = pair
    board.close()
    with pytest.raises(LinkError, match="test:datagram: board gone during the handshake: send failed"):
        link._send_msg(bytes([MsgType.HELLO]) + bytes(4))
