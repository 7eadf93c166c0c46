"""The firmware link over CAN: any python-can interface and channel.

A message's body and CRC-16 travel in 8-byte (or, with ``#fd=1``, 64-byte
CAN FD) segments whose 11-bit identifier is type << 7 | segment
(docs/protocol.md, ``hil_bridge/ffr.dbc``). Frames that are not ours, or
not for the host, are ignored, so the link can share a bus.
"""

from __future__ import annotations

import time
from collections import deque
from dataclasses import replace

import can
import numpy as np

from ffr_link.base import LinkError
from hil_bridge import codec
from hil_bridge.faults import FaultInjector, flip_bit
from hil_bridge.options import WireOptions, parse_url
from hil_bridge.wire_link import WireLink

_POLL_S = 0.005  # wait slice while delayed frames are held


def _corrupt(m: can.Message, rng: np.random.Generator) -> can.Message:
    # the bus's own CRC would drop such a frame; delivering it garbled tests our end-to-end CRC
    return can.Message(arbitration_id=m.arbitration_id, data=flip_bit(bytes(m.data), rng),
                       is_extended_id=False, is_fd=m.is_fd, bitrate_switch=m.bitrate_switch)


class CanLink(WireLink):
    def __init__(self, bus: can.BusABC, opts: WireOptions) -> None:
        super().__init__(opts)
        self.bus = bus
        self.fd = opts.fd
        self._rx = codec.CanReassembler()
        self._pending: deque[can.Message] = deque()
        self.faults_tx: FaultInjector[can.Message] = FaultInjector(opts.faults, _corrupt)
        self.faults_rx: FaultInjector[can.Message] = FaultInjector(
            replace(opts.faults, seed=opts.faults.seed + 1), _corrupt)

    def _send_frame(self, m: can.Message) -> None:
        try:
            self.bus.send(m, timeout=0.5)
        except can.CanError as exc:
            raise LinkError(f"{self.url}: cannot send {self._where()}: {exc}; {self.counters}") from None

    def _send_msg(self, msg: bytes) -> None:
        for m in self.faults_tx.due():
            self._send_frame(m)
        for cid, data in codec.can_frames(msg, self.fd):
            m = can.Message(arbitration_id=cid, data=data, is_extended_id=False, is_fd=self.fd,
                            bitrate_switch=self.fd)
            for f in self.faults_tx.filter(m):
                self._send_frame(f)

    def _recv_msg(self, timeout_s: float) -> bytes | None:
        deadline = time.monotonic() + timeout_s
        # past the deadline, one last look without waiting: a process held by a busy machine past
        # its deadline has not heard silence when the frames are queued (seen on a loaded CI)
        looked = False
        while True:
            while self._pending:
                m = self._pending.popleft()
                out = self._rx.push(m.arbitration_id, bytes(m.data))  # DecodeError propagates
                if out is not None:
                    return out
            if self.faults_tx.holding:
                for m in self.faults_tx.due():
                    self._send_frame(m)
            self._pending.extend(self.faults_rx.due())
            left = deadline - time.monotonic()
            if left <= 0:
                if looked:
                    return None
                looked, left = True, 0.0
            elif self.faults_tx.holding or self.faults_rx.holding:
                left = min(left, _POLL_S)
            try:
                m = self.bus.recv(timeout=left)
            except can.CanError as exc:
                raise LinkError(f"{self.url}: {self.side} gone {self._where()}: {exc}; {self.counters}") from None
            if m is None or m.is_extended_id or m.is_error_frame or m.is_remote_frame:
                continue
            t, _, _ = codec.can_split_id(m.arbitration_id)
            if t not in codec.BOARD_TO_HOST:
                continue  # our own frames echoed, or another node's
            self._pending.extend(self.faults_rx.filter(m))
            looked = False  # a frame came: look again for the rest of its message

    def close(self) -> None:
        self.bus.shutdown()


def open_can(url: str) -> CanLink:
    target, opts = parse_url(url)
    interface, sep, channel = target.partition(":")
    if not sep or not interface or not channel:
        raise LinkError(f"--link = {url!r}: expected can:<interface>:<channel>, e.g. can:socketcan:vcan0")
    kw: dict[str, object] = {"fd": True} if opts.fd else {}
    if opts.bitrate:
        kw["bitrate"] = opts.bitrate
    try:
        bus = can.Bus(interface=interface, channel=channel, **kw)
    except (can.CanError, ImportError, OSError, ValueError, NotImplementedError) as exc:
        raise LinkError(f"--link = {url!r}: cannot open CAN interface {interface!r} channel {channel!r}: "
                        f"{str(exc).splitlines()[0] if str(exc) else type(exc).__name__}") from None
    link = CanLink(bus, opts)
    link.url = url
    return link
