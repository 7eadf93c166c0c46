"""``host-board:serial`` and ``host-board:can``: the firmware as a board, no hardware needed.

- serial: the C host board program (``build/host/ffr-host-board``: firmware,
  codec, board link and a POSIX transport) runs as a child process on a
  pseudo-terminal (or TCP on 127.0.0.1); the link talks to it through
  pyserial exactly as to a real port.
- can: a python-can ``virtual`` bus in this process with a board thread
  (``can_board.CanBoard``) that drives the same C codec, board link and
  firmware through ctypes (docs/protocol.md says why).

The board never outlives the link: ``close()`` ends it (stdin closes, then
terminate, then kill, each with a timeout), and the board program also exits
by itself when its stdin or its line closes, so a killed harness leaves
nothing behind either.
"""

from __future__ import annotations

import contextlib
import os
import select
import subprocess
import time
from pathlib import Path
from typing import IO

from ffr_link.base import LinkError
from hil_bridge.child_process import describe_exit, stop_process
from hil_bridge.options import WireOptions, parse_url, simulated_board
from hil_bridge.owned_board import OwnsItsBoard
from hil_bridge.serial_link import SerialLink
from hil_bridge.wire_link import WireLink

REPO = Path(__file__).resolve().parents[1]


def board_program() -> Path:
    """``$FFR_HOST_BOARD``, else a checkout's build, else the installed ffr's (built on first use)."""
    from ffr_firmware.build import BuildError, locate

    try:
        return locate("host_board", "FFR_HOST_BOARD")
    except BuildError as exc:
        raise LinkError(f"host board program: {exc}") from None


class BoardProcess:
    """The host board program as a child process."""

    def __init__(self, args: list[str], log: str = "", start_timeout_s: float = 5.0) -> None:
        path = board_program()
        if not path.exists():
            raise LinkError(f"host board program {path} not found: build it with `make firmware-host`")
        self._log: IO[bytes] | None = open(log, "ab") if log else None  # noqa: SIM115 - closed in stop()
        self.proc = subprocess.Popen(
            [str(path), *args, "--stdin-lifeline"], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
            stderr=self._log if self._log is not None else subprocess.DEVNULL, close_fds=True)
        try:
            self.announce = self._first_line(start_timeout_s)
        except LinkError:
            self.stop()
            raise

    def _first_line(self, timeout_s: float) -> str:
        """The board's "FFR-BOARD <transport> <where>" line, within the timeout."""
        assert self.proc.stdout is not None
        fd = self.proc.stdout.fileno()
        buf = b""
        deadline = time.monotonic() + timeout_s
        while b"\n" not in buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise LinkError(f"host board: no start-up line within {timeout_s:g} s")
            ready, _, _ = select.select([fd], [], [], left)
            if ready:
                chunk = os.read(fd, 256)
                if not chunk:
                    raise LinkError(f"host board: {self.gone() or 'closed its output'} before starting")
                buf += chunk
        line = buf.split(b"\n", 1)[0].decode(errors="replace").strip()
        if not line.startswith("FFR-BOARD "):
            raise LinkError(f"host board: unexpected start-up line {line!r}")
        return line

    @property
    def pid(self) -> int:
        return self.proc.pid

    def gone(self, wait_s: float = 0.0) -> str | None:
        return describe_exit(self.proc, f"board process {self.proc.pid}", wait_s)

    def stop(self) -> None:
        p = self.proc
        stop_process(p, (self._close_stdin, p.terminate, p.kill), wait_s=1.0)
        if p.stdout is not None:
            p.stdout.close()
        if self._log is not None:
            self._log.close()
            self._log = None

    def _close_stdin(self) -> None:
        if self.proc.stdin is not None and not self.proc.stdin.closed:
            with contextlib.suppress(OSError):
                self.proc.stdin.close()  # the board's lifeline: it exits


def _board_args(opts: WireOptions) -> list[str]:
    args = ["--tcp", "0"] if opts.transport == "tcp" else ["--pty"]
    if opts.watchdog_ms:
        args += ["--watchdog-ms", str(opts.watchdog_ms)]
    if opts.step_delay_us:
        args += ["--step-delay-us", str(opts.step_delay_us)]
    return args


class HostBoardSerialLink(OwnsItsBoard, SerialLink):
    """The serial link to a host board program it started and will stop."""

    def __init__(self, board: BoardProcess, port_url: str, opts: WireOptions) -> None:
        self.board = board
        super().__init__(port_url, opts)


def open_host_board_serial(opts: WireOptions) -> HostBoardSerialLink:
    if opts.transport not in ("pty", "tcp"):
        raise LinkError(f"host-board:serial: transport = {opts.transport!r}: expected pty or tcp")
    board = BoardProcess(_board_args(opts), opts.log)
    kind, _, where = board.announce.removeprefix("FFR-BOARD ").partition(" ")
    try:
        return HostBoardSerialLink(board, f"socket://{where}" if kind == "tcp" else where, opts)
    except LinkError:
        board.stop()
        raise


def open_host_board(url: str) -> WireLink:
    target, opts = parse_url(url)
    simulated_board(opts)
    link: WireLink
    if target == "serial":
        link = open_host_board_serial(opts)
    elif target == "can":
        from hil_bridge.can_board import open_host_board_can

        link = open_host_board_can(opts)
    else:
        raise LinkError(f"--link = {url!r}: expected host-board:serial or host-board:can")
    link.url = url
    return link
