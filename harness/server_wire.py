"""What ``ffr`` and its warm server (harness/server.py) share: where the server's socket is, the
fingerprint of the code it serves, and the messages on the socket. Standard library only: every
``ffr`` command imports it before it starts (harness/launch.py).

A server serves only the code it was started with: its socket's name is a fingerprint of the
interpreter, our packages' Python files (path, size, mtime), the import path's directories
(a package installed or removed changes them) and numba's environment. An edit gives another
fingerprint, so the next command runs in its own process, cold, and never on stale code.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
import socket
import struct
import sys
from pathlib import Path

from ffr_firmware.cache import cache_root

# Our top-level packages (pyproject.toml's [tool.setuptools] packages, by their import names).
PACKAGES = ("harness", "sim_plant", "ffr_link", "hil_bridge", "ffr_firmware")
SOCKET_SUFFIX = ".sock"
# A Unix socket's path is limited to 108 bytes with its NUL (sockaddr_un.sun_path on Linux).
MAX_SOCKET_PATH = 107
# Messages: a 4-byte big-endian length, then JSON (requests) or one signed 4-byte int (replies).
_LEN = struct.Struct(">I")
_INT = struct.Struct(">i")
# Signals a user sends to "ffr" that the command itself must receive.
FORWARDED_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


def server_dir() -> Path:
    """Where servers put their sockets: ``$FFR_SERVER_DIR``, else ``server/`` in ffr's cache."""
    env = os.environ.get("FFR_SERVER_DIR")
    return Path(env) if env else cache_root() / "server"


def _package_dirs() -> list[Path]:
    import importlib.util

    dirs = []
    for name in PACKAGES:
        spec = importlib.util.find_spec(name)
        if spec is not None and spec.submodule_search_locations:
            dirs.extend(Path(p) for p in spec.submodule_search_locations)
    return dirs


def fingerprint(package_dirs: list[Path] | None = None, environ: dict[str, str] | None = None) -> str:
    """What a warm server's state depends on, hashed (see the module's docstring)."""
    env = os.environ if environ is None else environ
    h = hashlib.sha256()
    h.update(f"{sys.executable}\0{sys.version}\0".encode())
    for d in sorted(_package_dirs() if package_dirs is None else package_dirs):
        for f in sorted(d.rglob("*.py")):
            st = f.stat()
            h.update(f"{f}\0{st.st_size}\0{st.st_mtime_ns}\0".encode())
    # sys.path[0] is the caller's script directory or, under ``python -m``, its working directory:
    # not the server's business (the fork takes the caller's, harness/server.py); the rest is
    for p in sys.path[1:]:  # a package installed or removed (a link plug-in, a new numba) changes these
        try:
            h.update(f"{p}\0{os.stat(p).st_mtime_ns}\0".encode())
        except OSError:
            h.update(f"{p}\0-\0".encode())
    for k in sorted(env):
        if k.startswith("NUMBA_") or k in ("PYTHONPATH", "PYTHONHASHSEED"):
            h.update(f"{k}={env[k]}\0".encode())
    return h.hexdigest()[:20]


def socket_path(fp: str | None = None) -> Path:
    return server_dir() / f"ffr-{fp or fingerprint()}{SOCKET_SUFFIX}"


def send_msg(sock: socket.socket, obj: dict, fds: list[int] | None = None) -> None:
    data = json.dumps(obj).encode()
    payload = _LEN.pack(len(data)) + data
    if fds:
        sent = socket.send_fds(sock, [payload], fds)
        sock.sendall(payload[sent:])
    else:
        sock.sendall(payload)


def recv_exact(sock: socket.socket, n: int) -> bytes | None:
    buf = bytearray()
    while len(buf) < n:
        chunk = sock.recv(n - len(buf))
        if not chunk:
            return None
        buf += chunk
    return bytes(buf)


def recv_msg(sock: socket.socket, head: bytes = b"") -> dict | None:
    """A message ``send_msg`` sent; ``head``: its first bytes, already read (with the fds)."""
    if len(head) < _LEN.size:
        more = recv_exact(sock, _LEN.size - len(head))
        if more is None:
            return None
        head += more
    n = _LEN.unpack(head[:_LEN.size])[0]
    body = head[_LEN.size:]
    if len(body) < n:
        more = recv_exact(sock, n - len(body))
        if more is None:
            return None
        body += more
    return json.loads(body)


def send_int(sock: socket.socket, value: int) -> None:
    sock.sendall(_INT.pack(value))


def recv_int(sock: socket.socket) -> int | None:
    data = recv_exact(sock, _INT.size)
    return None if data is None else _INT.unpack(data)[0]
