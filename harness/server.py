"""``ffr server start|stop|status``: a warm process that runs ``ffr`` commands by forking.

Why: docs/architecture.md, "Start-up". The server imports what the commands use, runs a short
mission of each noise kind once so numba has loaded its cached kernels, and then waits on a
Unix socket (harness/launch.py computes its name). For each command it forks; the child takes
the caller's standard streams (passed over the socket), working directory, environment and
umask, runs ``harness.cli.main`` and exits; the server sends the child's exit status back. What
a child does cannot reach the next one: it is a separate process, and the server itself never
runs a command. So that a child sees the files as they are now, the warm-up runs on a copy of
the firmware library (a library is loaded once per path and process) and every cache keyed by a
file's name is emptied after it.

The server ends after ``--idle`` seconds without a command (default one hour), on ``ffr server
stop``, or when its socket file is removed or replaced. Each command runs in a process group of
its own, and the caller passes on the signals it gets (Ctrl-C, SIGTERM, SIGHUP, SIGQUIT) to that
group, as a shell's job would get them. A caller that goes away (killed, or its terminal closed)
takes its command with it: the server sends the group SIGTERM.
"""

from __future__ import annotations

import contextlib
import io
import os
import selectors
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from harness.server_wire import (
    MAX_SOCKET_PATH,
    SOCKET_SUFFIX,
    recv_msg,
    send_int,
    send_msg,
    server_dir,
    socket_path,
)

DEFAULT_IDLE_S = 3600.0
READY_TIMEOUT_S = 300.0  # a cold numba cache compiles every kernel during the warm-up: minutes on a slow machine


class ServerError(Exception):
    """One line for the user (exit status 2)."""


# -- the command side: ffr server start|stop|status -----------------------------------------------

def _request(path: Path, obj: dict, timeout: float = 5.0) -> dict | None:
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(timeout)
    try:
        s.connect(str(path))
        send_msg(s, obj)
        return recv_msg(s)
    except (OSError, ValueError):
        return None
    finally:
        s.close()


def _sockets() -> list[Path]:
    d = server_dir()
    return sorted(d.glob(f"ffr-*{SOCKET_SUFFIX}")) if d.is_dir() else []


def status_lines() -> list[str]:
    current = socket_path()
    lines = []
    for p in _sockets():
        info = _request(p, {"op": "status"})
        if info is None:
            lines.append(f"{p}: not answering (a server that ended; its socket is removed by the next start)")
            continue
        which = "current" if p == current else "stale: started on other code, used by nobody"
        lines.append(f"{p}: pid {info['pid']}, {which}, up {info['up_s']:.0f} s, idle {info['idle_s']:.0f} s, "
                     f"commands run {info['served']}, running {info['running']}, warm-up {info['warmup_s']:.2f} s")
    return lines or [f"no server in {server_dir()}"]


def stop_all() -> int:
    n = 0
    for p in _sockets():
        info = _request(p, {"op": "stop"})
        if info is not None:
            n += 1
        with contextlib.suppress(FileNotFoundError):
            if info is None:
                p.unlink()
    return n


def start(idle_s: float) -> str:
    path = socket_path()
    if len(os.fsencode(path)) > MAX_SOCKET_PATH:
        raise ServerError(f"FFR_SERVER_DIR = {str(server_dir())!r}: the socket path {str(path)!r} is longer than "
                          f"{MAX_SOCKET_PATH} bytes; set FFR_SERVER_DIR to a shorter directory")
    info = _request(path, {"op": "status"})
    if info is not None:
        return f"ffr server: already running (pid {info['pid']}, {path})"
    stop_all()  # servers of other code: nobody can use them any more
    d = server_dir()
    d.mkdir(parents=True, exist_ok=True)
    os.chmod(d, 0o700)
    log = d / f"{path.stem}.log"
    with open(log, "wb") as err:
        proc = subprocess.Popen([sys.executable, "-m", "harness.serve", "--serve", str(path), "--idle", str(idle_s)],
                                stdin=subprocess.DEVNULL, stdout=err, stderr=err, start_new_session=True,
                                env={**os.environ, "FFR_NO_SERVER": "1"})
    deadline = time.monotonic() + READY_TIMEOUT_S
    while time.monotonic() < deadline:
        info = _request(path, {"op": "status"})
        if info is not None:
            return (f"ffr server: ready (pid {info['pid']}, warm-up {info['warmup_s']:.2f} s); "
                    f"ffr commands now start warm; `ffr server stop` ends it, or {idle_s:.0f} s idle")
        if proc.poll() is not None:
            tail = log.read_text(errors="replace").strip().splitlines()[-1:] or ["(no output)"]
            raise ServerError(f"ffr server: it ended during its warm-up (exit {proc.returncode}): {tail[0]} "
                              f"(whole log: {log})")
        time.sleep(0.05)
    proc.terminate()
    raise ServerError(f"ffr server: not ready after {READY_TIMEOUT_S:.0f} s (log: {log})")


def command(action: str, idle_s: float) -> int:
    """``ffr server ACTION`` (harness/cli.py)."""
    if action == "start":
        print(start(idle_s))
    elif action == "stop":
        n = stop_all()
        print(f"ffr server: stopped {n} server{'s' if n != 1 else ''}")
    else:
        print("\n".join(status_lines()))
    return 0


# -- the server side -------------------------------------------------------------------------------

# What runs a command: harness.cli.main, given by harness/serve.py (this module does not import
# the commands, which import it for ``ffr server``).
Runner = Callable[[list[str]], int]


def warm_up(run: Runner) -> None:
    """Run one short mission per noise kind, so that everything the commands import is imported
    and numba has loaded every kernel a command calls; then forget whatever names a file."""
    from ffr_link.library import library_path, load_library

    try:
        lib = library_path(None)
    except Exception:  # no library yet: the first command builds it; the imports are still warm
        lib = None
    if lib is not None:
        with tempfile.TemporaryDirectory(prefix="ffr-warm-") as tmp:
            copy = Path(tmp) / "libffr-warm.so"  # its own path: the real one is loaded afresh by each command
            shutil.copyfile(lib, copy)
            sink = io.StringIO()
            with contextlib.redirect_stdout(sink), contextlib.redirect_stderr(sink):
                for noise in ("none", "typical", "realistic"):
                    run(["run", "--room", "1", "--firmware", str(copy), "--noise", noise])
    _forget_file_caches()
    load_library.cache_clear()


def _forget_file_caches() -> None:
    """Empty every functools cache in our modules: some are keyed by a file's path (a library, an
    arena), and the file may change while the server waits. The rest refill in microseconds."""
    import functools

    for name, mod in list(sys.modules.items()):
        if name.split(".")[0] not in ("harness", "sim_plant", "ffr_link", "hil_bridge", "ffr_firmware"):
            continue
        for obj in list(vars(mod).values()):
            if isinstance(obj, functools._lru_cache_wrapper):
                obj.cache_clear()


@dataclass
class Server:
    path: Path
    idle_s: float
    run: Runner
    started: float = field(default_factory=time.monotonic)
    last: float = field(default_factory=time.monotonic)
    served: int = 0
    warmup_s: float = 0.0
    children: dict[int, socket.socket] = field(default_factory=dict)  # pid -> its caller's connection
    stopping: bool = False
    pipe: tuple[int, int] = (-1, -1)  # signal wake-up: read end, write end

    def serve(self) -> None:
        t0 = time.monotonic()
        warm_up(self.run)
        self.warmup_s = time.monotonic() - t0
        listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        tmp = self.path.with_name(self.path.name + f".{os.getpid()}")
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        listener.bind(str(tmp))
        os.chmod(tmp, 0o600)
        listener.listen(16)
        os.replace(tmp, self.path)  # appears whole: a caller never connects to a half-made server
        my_inode = self.path.stat().st_ino
        wake_r, wake_w = self.pipe = os.pipe()
        os.set_blocking(wake_w, False)
        signal.set_wakeup_fd(wake_w)
        signal.signal(signal.SIGCHLD, lambda *_: None)
        signal.signal(signal.SIGTERM, lambda *_: setattr(self, "stopping", True))
        sel = selectors.DefaultSelector()
        sel.register(listener, selectors.EVENT_READ, "listen")
        sel.register(wake_r, selectors.EVENT_READ, "wake")
        self.last = time.monotonic()
        try:
            while not (self.stopping and not self.children):
                if not self.children and time.monotonic() - self.last > self.idle_s:
                    break
                try:
                    if self.path.stat().st_ino != my_inode:
                        break
                except FileNotFoundError:
                    break
                for key, _ in sel.select(timeout=1.0):
                    if key.data == "listen":
                        self._accept(listener, sel)
                    elif key.data == "wake":
                        os.read(wake_r, 512)
                    else:  # a caller's connection: readable only when the caller has gone
                        self._caller_gone(key.data, sel)
                self._reap(sel)
        finally:
            with contextlib.suppress(FileNotFoundError):
                if self.path.stat().st_ino == my_inode:
                    self.path.unlink()
            for pid in self.children:
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(pid, signal.SIGTERM)

    def _accept(self, listener: socket.socket, sel: selectors.BaseSelector) -> None:
        conn, _ = listener.accept()
        try:
            uid = _peer_uid(conn)
            if uid != os.getuid():
                conn.close()
                return
            msg, fds = _recv_request(conn)
        except (OSError, ValueError):
            conn.close()
            return
        op = msg.get("op")
        if op == "status" or op == "stop":
            now = time.monotonic()
            send_msg(conn, {"pid": os.getpid(), "up_s": now - self.started, "idle_s": now - self.last,
                            "served": self.served, "running": len(self.children), "children": sorted(self.children),
                            "warmup_s": self.warmup_s})
            conn.close()
            if op == "stop":
                self.stopping = True
            return
        if op != "run" or len(fds) != 3 or self.stopping:
            for fd in fds:
                os.close(fd)
            conn.close()
            return
        pid = os.fork()
        if pid == 0:
            # The child keeps no descriptor of the server's: a caller waits on its connection's end,
            # which must close when the server does, whatever its children still run.
            sel.close()
            for c in (listener, conn, *self.children.values()):
                c.close()
            signal.set_wakeup_fd(-1)
            for fd in self.pipe:
                os.close(fd)
            os._exit(_child(msg, fds, self.run))
        with contextlib.suppress(OSError):  # as a shell does, both sides: the group exists before the caller
            os.setpgid(pid, pid)            # learns the pid and may signal it
        for fd in fds:
            os.close(fd)
        self.served += 1
        self.last = time.monotonic()
        self.children[pid] = conn
        with contextlib.suppress(OSError):
            send_int(conn, pid)
        sel.register(conn, selectors.EVENT_READ, pid)

    def _caller_gone(self, pid: int, sel: selectors.BaseSelector) -> None:
        conn = self.children.get(pid)
        if conn is None:
            return
        sel.unregister(conn)
        with contextlib.suppress(ProcessLookupError):
            os.killpg(pid, signal.SIGTERM)

    def _reap(self, sel: selectors.BaseSelector) -> None:
        while self.children:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            conn = self.children.pop(pid, None)
            if conn is None:
                continue
            with contextlib.suppress(KeyError, ValueError):
                sel.unregister(conn)
            with contextlib.suppress(OSError):
                send_int(conn, os.waitstatus_to_exitcode(status))
            conn.close()
            self.last = time.monotonic()


def _peer_uid(conn: socket.socket) -> int:
    import struct

    creds = conn.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, struct.calcsize("3i"))
    return struct.unpack("3i", creds)[1]


def _recv_request(conn: socket.socket) -> tuple[dict, list[int]]:
    conn.settimeout(5.0)
    head, fds, _flags, _addr = socket.recv_fds(conn, 1 << 16, 3)
    msg = recv_msg(conn, head)
    if msg is None:
        for fd in fds:
            os.close(fd)
        raise ValueError("short request")
    conn.settimeout(None)
    return msg, fds


def _child(msg: dict, fds: list[int], run: Runner) -> int:
    """In the fork: become the caller's ``ffr`` process, run its command, return its exit status."""
    try:
        import atexit

        atexit._clear()  # the server's exit handlers are not this command's
        os.setpgid(0, 0)  # a group of its own, like a shell's job: the caller's signals reach its workers too
        for s in (signal.SIGCHLD, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGPIPE):
            signal.signal(s, signal.SIG_DFL if s != signal.SIGPIPE else signal.SIG_IGN)
        signal.signal(signal.SIGINT, signal.default_int_handler)
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        sys.stdin = io.TextIOWrapper(open(0, "rb", closefd=False))  # noqa: SIM115  (lives as long as the process)
        sys.stdout = _text_stream(1)
        sys.stderr = _text_stream(2, errors="backslashreplace")
        os.environ.clear()
        os.environ.update(msg["env"])
        os.chdir(msg["cwd"])
        os.umask(int(msg["umask"]))
        sys.argv = ["ffr", *msg["argv"]]
        sys.path[:] = [str(p) for p in msg["path"]]  # the caller's: its first entry is its own
    except Exception as exc:  # the caller's directory went, or a stream: say so where the caller sees it
        with contextlib.suppress(OSError):
            os.write(2, f"ffr: error: the warm server could not take the command: {exc}\n".encode())
        return 2
    try:
        code = run(msg["argv"])
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
        if not isinstance(exc.code, int) and exc.code is not None:
            print(exc.code, file=sys.stderr)
    except BaseException:
        import traceback

        traceback.print_exc()
        code = 1
    try:
        atexit._run_exitfuncs()
        sys.stdout.flush()
        sys.stderr.flush()
    except BrokenPipeError:
        pass
    return int(code)


def _text_stream(fd: int, errors: str = "strict") -> io.TextIOWrapper:
    tty = os.isatty(fd)
    return io.TextIOWrapper(open(fd, "wb", closefd=False), encoding="utf-8", errors=errors,  # noqa: SIM115
                            line_buffering=tty, write_through=fd == 2)
