"""Output files written atomically: a temporary file beside the target, then a
rename, so an error never leaves a half-written file where the output goes."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextmanager
def atomic_path(path: str | Path, mode: int | None = None) -> Iterator[Path]:
    """Yield a temporary path (same folder, same suffix) to write; on success it
    replaces ``path``, with ``mode`` or an ordinary file's mode (mkstemp's is 0600)."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=p.parent, prefix=f".{p.name}.", suffix=p.suffix)
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, mode if mode is not None else 0o666 & ~_umask())
        os.replace(tmp, p)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def check_target(path: str | Path) -> str | None:
    """Why a file cannot be written at ``path`` (missing folders are created), or None: asked
    before any mission runs, so a bad output path costs one line, not a finished run."""
    p = Path(path)
    if p.is_dir():
        return "is a directory"
    parent = p.parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        return f"{parent} is not a directory"
    if not os.access(parent, os.W_OK | os.X_OK):
        return f"cannot write in {parent}"
    return None


def check_outputs(args: object, *options: str) -> str | None:
    """The first of the command's output options (attribute names, e.g. ``json``) that names a
    file that cannot be written, as ``--option = 'value': why``; None when all can be."""
    for name in options:
        value = getattr(args, name, None)
        if value and value != "-":
            why = check_target(value)
            if why:
                return f"--{name.replace('_', '-')} = {str(value)!r}: {why}"
    return None


def write_bytes_atomic(path: str | Path, data: bytes, mode: int | None = None) -> None:
    with atomic_path(path, mode) as tmp:
        tmp.write_bytes(data)


def write_text_atomic(path: str | Path, text: str, mode: int | None = None) -> None:
    write_bytes_atomic(path, text.encode("utf-8"), mode)


def write_json(dest: str | Path, payload: object) -> None:
    """A command's ``--json`` output: indented JSON to standard output for ``-``, else to the file
    (atomically)."""
    text = json.dumps(payload, indent=2) + "\n"
    if str(dest) == "-":
        sys.stdout.write(text)
    else:
        write_text_atomic(dest, text)
