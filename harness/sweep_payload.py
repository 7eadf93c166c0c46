"""The files a sweep's missions read, shipped with the work to the cluster's workers.

A worker of a remote Dask cluster has ``pip install ffr`` and nothing else: no
checkout, no build directory, and none of the client's files. So the client reads
every file the jobs name (the firmware library of a ``ctypes:`` link, our own
build when the link is plain ``ctypes:``, and arena, robot and noise files), and
the sweep scatters those bytes to every worker once (``run_on``). A worker writes
each file into its own cache, keyed by the content's SHA-256
(``$FFR_CACHE/shipped/<sha>/<name>``), and runs the mission on those copies.
The rows still name the client's paths, so a failure's replay command works
where the sweep was started. Wire links (``serial:``, ``can:``, ``host-board:``,
``qemu:``) are not shipped: their board is where the worker runs.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

# job keys that hold a path the worker opens (a name of a shipped profile or arena is left alone)
FILE_KEYS = ("arena", "robot_file", "noise")


@dataclass(frozen=True)
class Payload:
    """Client path -> (SHA-256 hex, content)."""

    files: dict[str, tuple[str, bytes]] = field(default_factory=dict)

    def __bool__(self) -> bool:
        return bool(self.files)


def link_library(url: str) -> str | None:
    """The library file a ``ctypes:`` link loads, resolved on the client; None for a wire link."""
    scheme, _, rest = url.partition(":")
    if scheme != "ctypes":
        return None
    from ffr_link.base import LinkError
    from ffr_link.ctypes_link import library_path

    try:
        return str(library_path(rest or None))
    except LinkError:  # no build here: the worker finds or builds its own, as without a payload
        return None


def collect(jobs: Iterable[dict[str, Any]]) -> Payload:
    """Every file the jobs name, read once."""
    files: dict[str, tuple[str, bytes]] = {}
    for job in jobs:
        names = [job.get(k) for k in FILE_KEYS]
        lib = link_library(job.get("link", "ctypes:"))
        for name in [*names, lib]:
            if isinstance(name, str):
                name = name.partition("#")[0]  # a noise file's FILE.toml#profile
            if not isinstance(name, str) or name in files or not os.path.isfile(name):
                continue
            data = Path(name).read_bytes()
            files[name] = (hashlib.sha256(data).hexdigest(), data)
    # the plain "ctypes:" link: the library the client resolved travels under the URL itself
    for job in jobs:
        url = job.get("link", "ctypes:")
        lib = link_library(url)
        if lib is not None and lib in files and url not in files:
            files[url] = files[lib]
    return Payload(files)


_MATERIALISED: dict[str, str] = {}


def _shipped_dir() -> Path:
    from ffr_firmware.cache import cache_root

    return cache_root() / "shipped"


def materialise(payload: Payload | None) -> dict[str, str]:
    """Client path -> the path of its copy on this worker (written once, atomically)."""
    if not payload:
        return {}
    local: dict[str, str] = {}
    for name, (sha, data) in payload.files.items():
        base = Path(name.partition(":")[2] or "libffr.so").name if name.startswith("ctypes:") else Path(name).name
        key = f"{sha}/{base}"
        if key not in _MATERIALISED:
            target = _shipped_dir() / sha / base
            if not (target.is_file() and target.stat().st_size == len(data)):
                target.parent.mkdir(parents=True, exist_ok=True)
                fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=".part-")
                with os.fdopen(fd, "wb") as fh:
                    fh.write(data)
                os.replace(tmp, target)  # two workers on one machine write the same bytes: either wins
            _MATERIALISED[key] = str(target)
        local[name] = _MATERIALISED[key]
    return local


def local_name(name: Any, local: dict[str, str]) -> Any:
    """This worker's copy of a file the client named (``FILE.toml#profile`` keeps its profile)."""
    if not isinstance(name, str):
        return name
    if name in local:
        return local[name]
    path, sep, frag = name.partition("#")
    return local[path] + sep + frag if sep and path in local else name


def localise_link(url: str, local: dict[str, str]) -> str:
    """The link URL that loads the worker's copy of the client's library."""
    if url in local:
        return f"ctypes:{local[url]}"
    lib = url.partition(":")[2]
    if url.startswith("ctypes:") and lib in local:
        return f"ctypes:{local[lib]}"
    return url
