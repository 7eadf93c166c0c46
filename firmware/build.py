"""Build the firmware for the host: the in-process library (``libffr.so``, the ``ctypes:`` link)
and the host board program (``ffr-host-board``, the ``host-board:`` links).

In a checkout the Makefile builds them into ``build/host/`` and this module only points there.
An installed ffr has no checkout: the first run compiles the sources shipped in this package with
the machine's C compiler into a cache directory (``$FFR_CACHE``, else ``$XDG_CACHE_HOME/ffr``,
else ``~/.cache/ffr``), keyed by a hash of the sources, the flags and the compiler's version, so a
new ffr or another compiler never reuses an old build. ``ffr build`` does the same on demand, also
for a team's own firmware tree laid out like ours (``src/*.c``, ``include/*.h``; its library is
named after the tree's directory: ``examples/firmware/wall_follower`` gives ``libwall_follower.so``).

The flags are the Makefile's (``tests/firmware/test_build.py`` keeps them equal): the same sources
and flags give the same bits as a checkout's build.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ffr_firmware.cache import cache_root

HERE = Path(__file__).resolve().parent
CHECKOUT = HERE.parent if (HERE.parent / "Makefile").exists() and (HERE / "src").is_dir() else None

CSTD = ["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic", "-Wshadow", "-Wconversion",
        "-Wdouble-promotion", "-ffp-contract=off", "-fno-common"]
LIB_FLAGS = ["-O2", "-fPIC", "-shared"]
BOARD_FLAGS = ["-O2"]


class BuildError(RuntimeError):
    """The compiler is missing or refused the sources (the message is one line)."""


@dataclass(frozen=True)
class Tree:
    """A firmware source tree: ``src/*.c`` and ``include/*.h`` (a team's, or ours with the wire
    codec ``codec/``, the board link ``link/`` and the host board ``boards/host/``)."""

    root: Path

    @property
    def name(self) -> str:
        """``ffr`` for ours, else the tree's directory name: its library is ``lib<name>.so``."""
        if self.root == HERE:
            return "ffr"
        return "".join(c if c.isalnum() or c in "_-" else "_" for c in self.root.name) or "firmware"

    def firmware(self) -> list[Path]:
        return sorted((self.root / "src").glob("*.c"))

    def wire(self) -> list[Path]:
        return sorted([*(HERE / "codec").glob("*.c"), *(HERE / "link").glob("*.c")])

    def host_board(self) -> list[Path]:
        return sorted((HERE / "boards" / "host").glob("*.c"))

    def includes(self) -> list[str]:
        own = [f"-I{self.root / 'include'}", f"-I{self.root / 'src'}"]
        return own if self.root == HERE else [*own, f"-I{HERE / 'include'}"]

    def headers(self) -> list[Path]:
        return sorted([*self.root.glob("include/*.h"), *self.root.glob("src/*.h"), *HERE.glob("include/*.h"),
                       *(HERE / "boards" / "host").glob("*.h")])


def _cc() -> str:
    return os.environ.get("CC", "cc")



def _key(tree: Tree, cc: str) -> str:
    h = hashlib.sha256()
    try:
        h.update(subprocess.run([cc, "--version"], capture_output=True, check=True).stdout)
    except (OSError, subprocess.CalledProcessError) as exc:
        raise BuildError(f"no C compiler: {cc!r} ({exc}); install gcc, or set CC") from None
    for flags in (CSTD, LIB_FLAGS, BOARD_FLAGS):
        h.update(" ".join(flags).encode())
    for f in [*tree.firmware(), *tree.wire(), *tree.host_board(), *tree.headers()]:
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def _compile(cc: str, args: list[str], out: Path) -> None:
    """Compile into a temporary file beside ``out`` and rename it: never a half-written build."""
    out.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{out.name}.", dir=out.parent)
    os.close(fd)
    try:
        p = subprocess.run([cc, *args, "-o", tmp], capture_output=True, text=True)
        if p.returncode != 0:
            first = next((ln for ln in p.stderr.splitlines() if "error" in ln), p.stderr.strip()[:200])
            raise BuildError(f"{cc} could not build {out.name}: {first}")
        os.chmod(tmp, 0o755)
        os.replace(tmp, out)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)


def build(tree: Tree, out_dir: Path, *, board: bool = True) -> dict[str, Path]:
    """Compile the host library (and the host board program) of ``tree`` into ``out_dir``."""
    cc = _cc()
    if shutil.which(cc) is None:
        raise BuildError(f"no C compiler: {cc!r} not found; install gcc, or set CC")
    fw = tree.firmware()
    if not fw:
        raise BuildError(f"{tree.root / 'src'}: no C sources")
    out = {"library": out_dir / f"lib{tree.name}.so"}
    _compile(cc, [*CSTD, *tree.includes(), *LIB_FLAGS, *map(str, fw + tree.wire())], out["library"])
    if board:
        out["host_board"] = out_dir / "ffr-host-board"
        _compile(cc, [*CSTD, *tree.includes(), f"-I{HERE / 'boards' / 'host'}", *BOARD_FLAGS,
                      *map(str, fw + tree.wire() + tree.host_board())], out["host_board"])
    return out


def host_build(kind: str) -> Path:
    """Our firmware's ``library`` or ``host_board``: the checkout's build/host/, else the cache
    (built now when missing)."""
    name = {"library": "libffr.so", "host_board": "ffr-host-board"}[kind]
    if CHECKOUT is not None:
        return CHECKOUT / "build" / "host" / name
    tree = Tree(HERE)
    where = cache_root() / _key(tree, _cc())
    if not (where / name).exists():
        build(tree, where)
    return where / name


def locate(kind: str, env_var: str) -> Path:
    """Our firmware's ``library`` or ``host_board`` as the harness runs it: ``$env_var`` when set,
    else ``host_build(kind)``."""
    env = os.environ.get(env_var)
    return Path(env) if env else host_build(kind)
