"""The firmware link over serial: any pyserial URL (a port, ``socket://``, a pty).

Frames are COBS with a CRC-16 and a zero delimiter (docs/protocol.md). The
port's read timeout stays fixed and short (changing it reconfigures the port
on every call); the link keeps its own deadlines on top.
"""

from __future__ import annotations

import contextlib
import socket
import time

import serial

from ffr_link.base import LinkError
from hil_bridge import codec
from hil_bridge.errors import DecodeError
from hil_bridge.frame_link import FrameLink
from hil_bridge.options import WireOptions, parse_url

_POLL_S = 0.002  # the port's read timeout: how often a wait looks at its deadline
# pyserial's socket:// write raises a timeout whenever the call as a whole took longer, even
# when every byte went out: a process stalled by a busy machine is not a stuck line
_WRITE_TIMEOUT_S = 5.0


class SerialLink(FrameLink):
    def __init__(self, port_url: str, opts: WireOptions) -> None:
        super().__init__(opts)
        self.port_url = port_url
        self.ser: serial.SerialBase | None = None
        self._deframer = codec.Deframer()
        try:
            self.ser = serial.serial_for_url(port_url, baudrate=opts.baud, timeout=_POLL_S,
                                              write_timeout=_WRITE_TIMEOUT_S)
        except (serial.SerialException, ValueError, OSError) as exc:
            raise LinkError(f"serial:{port_url}: cannot open: {exc}") from None
        sock = getattr(self.ser, "_socket", None)  # socket://: one frame, one segment, no Nagle delay
        if sock is not None:
            with contextlib.suppress(OSError):
                sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def _write(self, frame: bytes) -> None:
        assert self.ser is not None
        try:
            self.ser.write(frame)
        except (serial.SerialException, OSError) as exc:
            raise LinkError(f"{self.url}: {self.side} gone {self._where()}: "
                            f"{self._gone(0.5) or f'write failed ({exc})'}; {self.counters}") from None

    def _read_frames(self) -> None:
        assert self.ser is not None
        try:
            n = self.ser.in_waiting
            data = self.ser.read(n if n > 0 else 1)
        except (serial.SerialException, OSError) as exc:
            gone = self._gone(0.5)
            raise LinkError(f"{self.url}: {self.side} gone {self._where()}: "
                            f"{gone or f'the line closed ({exc})'}; {self.counters}") from None
        if data:
            # where a tick's time goes (make bench): request sent -> first answer byte -> whole answer
            self.reads += 1
            if not self.first_byte_at:
                self.first_byte_at = time.perf_counter()
            for item in self._deframer.push(data):
                if isinstance(item, DecodeError):
                    self._pending.append(item)
                    continue
                # faults on the way in: a whole frame lost, garbled or late (delimiter kept)
                self._pending.extend(f[:-1] for f in self.faults_rx.filter(item + b"\x00"))
        self._pending.extend(f[:-1] for f in self.faults_rx.due())

    def _recv_msg(self, timeout_s: float) -> bytes | None:
        deadline = time.monotonic() + timeout_s
        while True:
            msg = self._take_pending()
            if msg is not None:
                return msg
            if self.faults_tx.holding:
                self._release_held()
            if time.monotonic() >= deadline and not self._arrived():
                return None  # nothing came by the deadline
            self._read_frames()

    def _arrived(self) -> bool:
        """Bytes waiting in the port: a deadline that passed while this process was held by a
        busy machine (not reading) is no silence when the answer is there (seen on a loaded CI)."""
        assert self.ser is not None
        try:
            return self.ser.in_waiting > 0
        except (serial.SerialException, OSError):
            return True  # let the read report the line's end

    def close(self) -> None:
        if self.ser is not None:
            with contextlib.suppress(serial.SerialException, OSError):
                self.ser.close()
            self.ser = None


def open_serial(url: str) -> SerialLink:
    target, opts = parse_url(url)
    if not target:
        raise LinkError(f"--link = {url!r}: expected serial:<pyserial URL>, e.g. serial:/dev/ttyACM0 or "
                        "serial:socket://127.0.0.1:5000")
    link = SerialLink(target, opts)
    link.url = url
    return link
