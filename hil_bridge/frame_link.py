"""What the two links that carry whole serial frames share: the serial line and the datagram link.

Each frame is COBS-encoded with its delimiter (``codec.frame_encode``); faults are injected per
frame on the way out and on the way in (each direction its own seeded stream); frames read but not
yet taken wait in ``_pending`` (a decode error waits there too, to be raised in its turn); and
``sent_at``/``first_byte_at``/``reads`` give ``make bench`` its tick anatomy. A subclass writes one
frame (``_write``) and fills ``_pending`` when it reads.
"""

from __future__ import annotations

import time
from abc import abstractmethod
from dataclasses import replace

from hil_bridge import codec
from hil_bridge.errors import DecodeError
from hil_bridge.faults import FaultInjector, flip_bit
from hil_bridge.options import WireOptions
from hil_bridge.wire_link import WireLink


class FrameLink(WireLink):
    def __init__(self, opts: WireOptions) -> None:
        super().__init__(opts)
        self._pending: list[bytes | DecodeError] = []
        self.sent_at = self.first_byte_at = 0.0
        self.reads = 0
        self.faults_tx: FaultInjector[bytes] = FaultInjector(opts.faults, flip_bit)
        # the way back draws from its own stream, so each direction's pattern is fixed by the seed
        self.faults_rx: FaultInjector[bytes] = FaultInjector(replace(opts.faults, seed=opts.faults.seed + 1), flip_bit)

    @abstractmethod
    def _write(self, frame: bytes) -> None:
        """One encoded frame (delimiter included) onto the transport."""

    def _send_msg(self, msg: bytes) -> None:
        self._release_held()
        for f in self.faults_tx.filter(codec.frame_encode(msg)):
            self._write(f)
        self.sent_at = time.perf_counter()
        self.first_byte_at = 0.0

    def _release_held(self) -> None:
        """Frames the fault injector held back (late frames) that are due now."""
        for f in self.faults_tx.due():
            self._write(f)

    def _take_pending(self) -> bytes | None:
        """The next message read, None when none waits; a bad frame raises its DecodeError."""
        if not self._pending:
            return None
        item = self._pending.pop(0)
        if isinstance(item, DecodeError):
            raise item
        return codec.frame_decode(item)
