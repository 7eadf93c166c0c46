"""The ``ffr`` command's entry point: hand the command to a warm server when one runs, else run it here.

A fresh Python process pays ~0.6 s before its first compiled kernel runs: importing numba and
numba's first use (docs/architecture.md, "Start-up"). ``ffr server start`` (harness/server.py)
keeps one process past that point; each command is then run by a fork of it, with this
process's arguments, working directory, environment, umask and standard streams, and its exit
status comes back here. Without a server, or with ``FFR_NO_SERVER=1``, the command runs in this
process exactly as before. This module imports only the standard library and
harness/server_wire.py: it is what every ``ffr`` pays before the command starts.

A server serves only the code it was started with (harness/server_wire.py's fingerprint).
"""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import sys

from harness.server_wire import FORWARDED_SIGNALS, MAX_SOCKET_PATH, recv_int, send_msg, socket_path


def _served(argv: list[str]) -> int | None:
    """Run ``argv`` on a warm server; None when there is none to run it (then the caller runs it)."""
    if os.environ.get("FFR_NO_SERVER", "") not in ("", "0"):
        return None
    if argv[:1] == ["server"]:  # ffr server start/stop/status: always this process
        return None
    try:
        path = socket_path()
    except OSError:
        return None
    if len(os.fsencode(path)) > MAX_SOCKET_PATH or not path.exists():
        return None
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        sock.connect(str(path))
        umask = os.umask(0)
        os.umask(umask)
        send_msg(sock, {"op": "run", "argv": argv, "cwd": os.getcwd(), "env": dict(os.environ),
                        "umask": umask, "path": sys.path}, fds=[0, 1, 2])
        pid = recv_int(sock)
    except OSError:  # a server that died or is stopping: its socket is left, nobody answers
        sock.close()
        return None
    if pid is None:
        sock.close()
        return None

    def forward(signum: int, _frame: object) -> None:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(pid, signum)  # the command's group (harness/server.py), its workers with it

    for s in FORWARDED_SIGNALS:
        signal.signal(s, forward)
    status = recv_int(sock)  # the command's exit status (negative: killed by that signal)
    sock.close()
    if status is None:
        print("ffr: error: the warm server ended before the command did (ffr server status)", file=sys.stderr)
        return 1
    if status < 0:  # die of the same signal, as the command did, so the caller sees what it would have
        for s in FORWARDED_SIGNALS:
            signal.signal(s, signal.SIG_DFL)
        sys.stdout.flush()
        os.kill(os.getpid(), -status)
        return 128 - status
    return status


def main() -> int:
    argv = sys.argv[1:]
    status = _served(argv)
    if status is not None:
        return status
    from harness.cli import main as cli_main

    return cli_main(argv)
