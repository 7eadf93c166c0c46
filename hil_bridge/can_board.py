"""A CAN board without hardware: the C board link on a python-can bus.

A thread plays the microcontroller's CAN interrupt and main loop: frames in
-> the C reassembler (ffr_can_rx_push) -> the C board link (handshake,
reset, ffr_step, watchdog) -> the C segmenter (ffr_can_frame) -> frames out.
Python only moves frames between the bus and those C functions, so what runs
is the codec and firmware a CAN microcontroller would run.
"""

from __future__ import annotations

import itertools
import threading
import time

import can

from hil_bridge import codec
from hil_bridge.can_link import CanLink
from hil_bridge.codec import MsgType
from hil_bridge.native import CBoardLink, CCanRx, CCodec, wire_library
from hil_bridge.options import WireOptions
from hil_bridge.owned_board import OwnsItsBoard

_HOST_TO_BOARD = {int(MsgType.INPUTS), int(MsgType.HELLO), int(MsgType.RESET)}


def _now_ms() -> int:
    return int(time.monotonic() * 1000) & 0xFFFFFFFF


class CanBoard:
    def __init__(self, bus: can.BusABC, fd: bool = False, watchdog_ms: int = 500) -> None:
        lib = wire_library()
        self.bus = bus
        self.fd = fd
        self.link = CBoardLink(watchdog_ms, _now_ms(), lib)
        self._rx = CCanRx(lib)
        self._codec = CCodec(lib)
        self._stop = threading.Event()
        self.error: BaseException | None = None
        self.watchdog_trips = 0
        self.thread = threading.Thread(target=self._run, name="ffr-can-board", daemon=True)

    def start(self) -> None:
        self.thread.start()

    def stop(self, timeout_s: float = 1.0) -> None:
        self._stop.set()
        if self.thread.is_alive():
            self.thread.join(timeout_s)

    def gone(self, wait_s: float = 0.0) -> str | None:
        if wait_s > 0:
            self.thread.join(wait_s)
        if self.thread.is_alive():
            return None
        return f"board thread ended ({self.error!r})" if self.error else "board thread stopped"

    def _send(self, msg: bytes) -> None:
        for cid, data in self._codec.can_frames(msg, self.fd):
            self.bus.send(can.Message(arbitration_id=cid, data=data, is_extended_id=False, is_fd=self.fd,
                                      bitrate_switch=self.fd))

    def _run(self) -> None:
        try:
            while not self._stop.is_set():
                m = self.bus.recv(timeout=0.005)
                now = _now_ms()
                if m is not None and not m.is_extended_id and not m.is_error_frame and not m.is_remote_frame:
                    t, _, _ = codec.can_split_id(m.arbitration_id)
                    if t in _HOST_TO_BOARD:
                        r = self._rx.push(m.arbitration_id, bytes(m.data))
                        reply = None
                        if isinstance(r, bytes):
                            reply = self.link.on_msg(r, now)
                        elif isinstance(r, int):
                            reply = self.link.on_bad_frame(r)
                        if reply:
                            self._send(reply)
                alarm = self.link.poll(now)
                if alarm:
                    self.watchdog_trips += 1
                    self._send(alarm)
        except BaseException as exc:  # noqa: BLE001 - reported through gone()
            self.error = exc


class HostBoardCanLink(OwnsItsBoard, CanLink):
    """The CAN link to a CAN board it started on a private virtual bus."""

    def __init__(self, board: CanBoard, board_bus: can.BusABC, bus: can.BusABC, opts: WireOptions) -> None:
        self.board = board
        self._board_bus = board_bus
        super().__init__(bus, opts)

    def _release_board(self) -> None:
        super()._release_board()
        self._board_bus.shutdown()


_channels = itertools.count()


def open_host_board_can(opts: WireOptions) -> HostBoardCanLink:
    channel = f"ffr-host-board-{next(_channels)}"  # a private virtual bus per link (virtual is per process)
    board_bus = can.Bus(interface="virtual", channel=channel)
    board = CanBoard(board_bus, fd=opts.fd, watchdog_ms=opts.watchdog_ms or 500)
    board.start()
    try:
        return HostBoardCanLink(board, board_bus, can.Bus(interface="virtual", channel=channel), opts)
    except Exception:
        board.stop()
        board_bus.shutdown()
        raise
