"""The firmware link over raw Ethernet frames carried as datagrams (an emulator's network card).

QEMU's ``-netdev dgram`` moves each Ethernet frame its emulated network card sends or receives
as one datagram on a local socket. This link is the other end: each message goes out as one
serial frame (COBS(message + CRC) + 0x00, the very bytes a UART carries: docs/protocol.md)
behind a 14-byte Ethernet header with the EtherType ``ETH_TYPE_FFR``, one frame per datagram;
answers come back the same way. A board on an emulated Ethernet thus costs one hand-over per
message instead of two per byte (docs/pil.md, "Speed").

Datagrams are not a stream: one lost (never seen on a local socket, but the protocol allows it)
costs one timeout and is counted as a retry; a clean link shows none. Fault injection
(``#drop=...``) works on whole frames, as on the serial link.
"""

from __future__ import annotations

import contextlib
import socket
import time
from pathlib import Path

from ffr_link.base import LinkError
from hil_bridge.errors import DecodeError, Status
from hil_bridge.frame_link import FrameLink
from hil_bridge.options import WireOptions

ETH_TYPE_FFR = 0x88B5  # IEEE 802 "local experimental" EtherType 1 (the board's eth_lan9118.c)
HOST_MAC = bytes((0x02, 0x00, 0x00, 0x00, 0x0F, 0xF1))  # locally administered
BOARD_MAC = bytes((0x02, 0x00, 0x00, 0x00, 0x0F, 0xF2))
HEADER = BOARD_MAC + HOST_MAC + ETH_TYPE_FFR.to_bytes(2, "big")
_MAX_DGRAM = 2048


class DatagramLink(FrameLink):
    """WireLink over a local datagram socket whose peer forwards Ethernet frames (QEMU's dgram
    netdev): ``local`` is our socket's path, ``peer`` the other end's."""

    def __init__(self, local: Path, peer: Path, opts: WireOptions) -> None:
        super().__init__(opts)
        self.peer = str(peer)
        self.sock: socket.socket | None = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
        try:
            self.sock.bind(str(local))
        except OSError as exc:
            self.sock.close()
            self.sock = None
            raise LinkError(f"datagram link: cannot bind {local}: {exc}") from None

    def _write(self, frame: bytes) -> None:
        assert self.sock is not None
        try:
            self.sock.sendto(HEADER + frame, self.peer)
        except OSError as exc:  # the peer's socket is gone (its process ended) or never was
            raise LinkError(f"{self.url}: {self.side} gone {self._where()}: "
                            f"{self._gone(0.5) or f'send failed ({exc})'}; {self.counters}") from None

    def _take(self, dgram: bytes) -> None:
        """One datagram: our EtherType, then one frame up to its delimiter (padding after it)."""
        if len(dgram) < len(HEADER) or int.from_bytes(dgram[12:14], "big") != ETH_TYPE_FFR:
            return  # not ours (nothing else is on this wire)
        payload = dgram[len(HEADER):]
        end = payload.find(0)
        if end <= 0:
            self._pending.append(DecodeError(Status.SHORT if end == 0 else Status.COBS,
                                             "datagram without a whole frame"))
            return
        if not self.first_byte_at:
            self.first_byte_at = time.perf_counter()
        self.reads += 1
        # faults on the way in: a whole frame lost, garbled or late
        self._pending.extend(f[:-1] for f in self.faults_rx.filter(payload[:end + 1]))

    def _read(self, timeout_s: float) -> None:
        assert self.sock is not None
        self.sock.settimeout(max(timeout_s, 0.0))
        try:
            self._take(self.sock.recv(_MAX_DGRAM))
            self.sock.setblocking(False)
            while True:  # whatever else has arrived, without waiting
                self._take(self.sock.recv(_MAX_DGRAM))
        except (BlockingIOError, TimeoutError):
            pass
        except OSError as exc:
            raise LinkError(f"{self.url}: {self.side} gone {self._where()}: "
                            f"{self._gone(0.5) or f'receive failed ({exc})'}; {self.counters}") from None
        self._pending.extend(f[:-1] for f in self.faults_rx.due())

    def _recv_msg(self, timeout_s: float) -> bytes | None:
        deadline = time.monotonic() + timeout_s
        while True:
            msg = self._take_pending()
            if msg is not None:
                return msg
            if self.faults_tx.holding:
                self._release_held()
            left = deadline - time.monotonic()
            # a held fault is due soon: look again then; otherwise wait for the deadline (one last
            # look when it has passed: a stalled process is no silence when the answer is there)
            self._read(min(left, 0.005) if self.faults_tx.holding or self.faults_rx.holding else left)
            if not self._pending and time.monotonic() >= deadline:
                return None

    def close(self) -> None:
        if self.sock is not None:
            with contextlib.suppress(OSError):
                self.sock.close()
            self.sock = None
