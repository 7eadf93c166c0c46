"""The host side of the link protocol (docs/protocol.md), whatever the wire.

``WireLink`` implements the harness's ``FirmwareLink`` once: handshake
(protocol, firmware version, layout hash), reset with the configuration, and
lockstep steps with a timeout on every wait and bounded retries. A transport
(serial, CAN) only moves messages: ``_send_msg`` and ``_recv_msg``.

Every failure is a ``LinkError`` with one line that names the silent side,
the tick and the counters, e.g.
``host-board:serial: board silent at tick 412 (t 4.12 s): no OUTPUTS after 6 tries in 0.30 s;
sent 830, received 824, CRC errors 1, retries 5``.
"""

from __future__ import annotations

import time
from abc import abstractmethod

import numpy as np

from ffr_link.abi import CONTRACT_MAJOR, INPUTS_DTYPE
from ffr_link.base import FirmwareLink, LinkError
from hil_bridge import codec
from hil_bridge.codec import MsgType
from hil_bridge.crc import crc16
from hil_bridge.errors import DecodeError, ErrCode, Status
from hil_bridge.options import WireOptions

FW_VERSION_MAJOR = CONTRACT_MAJOR  # the firmware contract this harness speaks (FFR_CONTRACT_MAJOR)
# HELLO and RESET may be sent many times on a lossy line (options.py, handshake_try_s);
# handshake_timeout_s still bounds the wait.
_HANDSHAKE_RETRIES = 50


# Board error reports that mean "send it again" rather than "give up".
_TRANSIENT = {ErrCode.CRC, ErrCode.FRAMING, ErrCode.SEGMENT, ErrCode.LENGTH}


# A long wait looks every this often whether the other side has gone (its process ended), so a
# dead board ends the run at once whatever the timeout.
GONE_POLL_S = 0.1


class WireLink(FirmwareLink):
    """FirmwareLink over a message transport; subclasses move the bytes."""

    side = "board"

    def __init__(self, opts: WireOptions) -> None:
        super().__init__()
        self.opts = opts
        self.info: np.ndarray | None = None
        self._in_msg = bytearray(1 + INPUTS_DTYPE.itemsize)
        self._in_msg[0] = int(MsgType.INPUTS)
        self._raw_inputs = codec._raw_ok(INPUTS_DTYPE, codec.INPUTS_WIRE)
        self._t_ms = 0
        self._tick: int | None = None  # None: handshake or reset

    @property
    def faults_injected(self) -> bool:
        return self.opts.faults.active

    @property
    def _handshake_try_s(self) -> float:
        return min(self.opts.handshake_try_s, self.opts.timeout_s)  # a lossy line asks for short tries

    # ---- transport ------------------------------------------------------------------------------------------
    @abstractmethod
    def _send_msg(self, msg: bytes) -> None:
        """Send one message (type + body)."""

    @abstractmethod
    def _recv_msg(self, timeout_s: float) -> bytes | None:
        """One message (type + body) within timeout_s, None on timeout; DecodeError for a bad frame;
        LinkError when the transport is gone."""

    def _gone(self, wait_s: float = 0.0) -> str | None:
        """Why the other side can no longer answer (its process ended, ...), None if it may;
        wait_s: how long to wait for that to show (the line closes before a process is reaped)."""
        return None

    # ---- protocol -------------------------------------------------------------------------------------------
    def _where(self) -> str:
        return "during the handshake" if self._tick is None else f"at tick {self._tick} (t {self._t_ms / 1000:.2f} s)"

    def _fail(self, what: str, tries: int, t0: float, garbled: bool = False) -> LinkError:
        where = self._where()
        gone = self._gone()
        if gone:
            head = f"{self.url}: {self.side} gone {where}: {gone}"
        else:
            # silent: the last try met no answer at all; garbled: only broken frames or error reports
            how = "garbled" if garbled else "silent"
            head = (f"{self.url}: {self.side} {how} {where}: no {what} after {tries} "
                    f"{'try' if tries == 1 else 'tries'} in {time.monotonic() - t0:.2f} s")
        return LinkError(f"{head}; {self.counters}")

    def _transact(self, msg: bytes, want: MsgType, seq: int | None, timeout_s: float, retries: int,
                  budget_s: float) -> bytes:
        """Send msg until an answer of type `want` (for `seq`) comes: at most retries + 1 times,
        within budget_s in all.

        Silence: the next try waits twice as long (a lost frame costs one timeout; a host or board
        stalled by a busy machine still gets its time). A garbled answer or an error report: send
        again after a backoff that doubles from 1/16 of the timeout (listening meanwhile, since
        the right answer may still come), never a burst of immediate resends into a board that is
        already struggling."""
        t0 = time.monotonic()
        tries = silent = garbled = 0
        while True:
            self._send_msg(msg)
            self.counters.sent += 1
            tries += 1
            deadline = min(time.monotonic() + timeout_s * (1 << min(silent, 4)), t0 + budget_s)
            heard = False
            looked = False
            while True:
                left = deadline - time.monotonic()
                if left <= 0:
                    if looked:
                        break
                    looked = True  # the deadline passed: one last look, in case this process was held
                try:
                    reply = self._recv_msg(min(max(left, 0.0), GONE_POLL_S))
                except DecodeError as exc:
                    if exc.status in (Status.CRC, Status.COBS, Status.SHORT, Status.LONG, Status.SEGMENT,
                                      Status.LENGTH):
                        self.counters.crc_errors += 1
                    reply = None
                    heard = True
                else:
                    if reply is None:
                        if time.monotonic() < deadline and not self._gone():
                            continue  # a slice of the wait ended and the other side is still there
                        break
                    self.counters.received += 1
                    t = reply[0]
                    if t == want:
                        if seq is None or int.from_bytes(reply[1:5], "little") == seq:
                            return reply
                        self.counters.stale += 1  # an answer to an earlier try or tick
                        continue
                    if t != MsgType.ERROR:
                        self.counters.stale += 1
                        continue
                    if not self._board_error(reply, seq):
                        continue
                    heard = True
                # garbled: resend after the backoff, still listening until then
                backoff = timeout_s / 16 * (1 << min(garbled, 4))
                garbled += 1
                deadline = min(deadline, time.monotonic() + backoff)
            silent += 0 if heard else 1
            gone = self._gone()
            if gone or tries > retries or time.monotonic() >= t0 + budget_s:
                raise self._fail(want.name, tries, t0, garbled=heard)
            self.counters.retries += 1

    def _board_error(self, reply: bytes, seq: int | None) -> bool:
        """An error report: True to send again now; raises on errors that retrying cannot fix."""
        _, rec = codec.decode_msg(reply)
        code = ErrCode(int(rec["code"])) if int(rec["code"]) in ErrCode._value2member_map_ else None
        self.counters.board_errors += 1
        if code == ErrCode.WATCHDOG:
            self.counters.watchdog += 1
            return False
        if code in _TRANSIENT:
            return True
        if seq is not None and int(rec["seq"]) != seq:
            self.counters.stale += 1  # about an old, late frame of ours
            return False
        where = self._where()
        name = code.name if code is not None else f"code {int(rec['code'])}"
        raise LinkError(f"{self.url}: {self.side} reported {name} (detail {int(rec['detail'])}, "
                        f"seq {int(rec['seq'])}) {where}; {self.counters}")

    def handshake(self) -> np.ndarray:
        hello = codec.encode_msg(MsgType.HELLO, codec.record(MsgType.HELLO, proto=codec.PROTO_VERSION,
                                                             watchdog_ms=self.opts.watchdog_ms))
        reply = self._transact(hello, MsgType.INFO, None, self._handshake_try_s, _HANDSHAKE_RETRIES,
                               self.opts.handshake_timeout_s)
        _, info = codec.decode_msg(reply)
        ver = int(info["fw_version"])
        major, minor = ver >> 16, ver & 0xFFFF
        # the board runs the host build's firmware: the same hash (layout, names, firmware name)
        want_hash = self.firmware.layout_hash
        sizes = (int(info["inputs_size"]), int(info["outputs_size"]), int(info["config_size"]))
        wire = codec.wire_for(self.firmware.config_dtype)
        want_sizes = tuple(wire.body_wire[t].itemsize for t in (MsgType.INPUTS, MsgType.OUTPUTS, MsgType.RESET))
        if int(info["proto"]) != codec.PROTO_VERSION:
            raise LinkError(f"{self.url}: {self.side} speaks protocol {int(info['proto'])}, "
                            f"the harness {codec.PROTO_VERSION}: refused")
        if major != FW_VERSION_MAJOR or int(info["layout_hash"]) != want_hash or sizes != want_sizes:
            raise LinkError(
                f"{self.url}: {self.side} firmware {major}.{minor} with layout hash 0x{int(info['layout_hash']):08x} "
                f"(sizes {sizes}) does not match the harness's {FW_VERSION_MAJOR}.x, 0x{want_hash:08x} "
                f"{want_sizes} ({self.firmware.firmware_name}): refused; build the board from the same "
                f"firmware as the host library")
        self.info = info
        return info

    def _drain_idle(self) -> None:
        """What the board said while no mission ran (since the last answer): its watchdog's report
        that the host fell silent after a mission ended counts as ``idle_watchdog``; anything
        else is as unexpected as ever (``stale``)."""
        while True:
            try:
                reply = self._recv_msg(0.0)
            except DecodeError:
                self.counters.crc_errors += 1
                continue
            if reply is None:
                return
            self.counters.received += 1
            if reply[0] == MsgType.ERROR:
                _, rec = codec.decode_msg(reply)
                if int(rec["code"]) == ErrCode.WATCHDOG:
                    self.counters.idle_watchdog += 1
                    continue
            self.counters.stale += 1

    def _reset_impl(self, config: np.ndarray) -> None:
        self._tick = None
        if self.info is None:
            self.handshake()
        else:
            self._drain_idle()
        msg = codec.encode_msg(MsgType.RESET, config)
        reply = self._transact(msg, MsgType.READY, None, self._handshake_try_s, _HANDSHAKE_RETRIES,
                               self.opts.handshake_timeout_s)
        _, ready = codec.decode_msg(reply)
        if int(ready["config_crc"]) != crc16(msg[1:]):
            raise LinkError(f"{self.url}: {self.side} acknowledged a different configuration "
                            f"(CRC 0x{int(ready['config_crc']):04x}, sent 0x{crc16(msg[1:]):04x}); {self.counters}")

    def _step_impl(self, inputs: np.ndarray, outputs: np.ndarray) -> None:
        if self._raw_inputs and inputs.dtype == INPUTS_DTYPE:
            self._in_msg[1:] = inputs.tobytes()
            msg = bytes(self._in_msg)
        else:
            msg = codec.encode_msg(MsgType.INPUTS, inputs)
        seq = int(inputs["seq"])
        self._t_ms = int(inputs["t_ms"])
        self._tick = seq
        reply = self._transact(msg, MsgType.OUTPUTS, seq, self.opts.timeout_s, self.opts.retries,
                               self.opts.step_budget_s)
        if len(reply) != 1 + outputs.dtype.itemsize:
            raise LinkError(f"{self.url}: OUTPUTS of {len(reply) - 1} bytes at tick {seq}; {self.counters}")
        _, rec = codec.decode_msg(reply)
        outputs[...] = rec

