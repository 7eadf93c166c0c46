"""Where ffr keeps what it builds and ships: ``$FFR_CACHE``, else ``$XDG_CACHE_HOME/ffr`` or
``~/.cache/ffr``. Standard library only (os, pathlib): ``ffr``'s launcher (harness/server_wire.py)
finds its warm server's socket here before anything else is imported."""

from __future__ import annotations

import os
from pathlib import Path


def cache_root() -> Path:
    env = os.environ.get("FFR_CACHE")
    if env:
        return Path(env)
    xdg = os.environ.get("XDG_CACHE_HOME")
    return (Path(xdg) if xdg else Path.home() / ".cache") / "ffr"
