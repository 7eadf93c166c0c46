"""Loading a firmware library that meets the contract (docs/contract.md): where it is, its
self-description checked and read (``firmware_info``), its default configuration. Used by the
in-process link (``ctypes_link``) and, for the host build's description, by every link."""

from __future__ import annotations

import ctypes
from functools import lru_cache
from pathlib import Path

import numpy as np

from ffr_link.abi import (
    FirmwareLayoutError,
    LibraryLayout,
    check_layout,
    read_layout,
)
from ffr_link.errors import LinkError

REPO = Path(__file__).resolve().parents[1]
DEFAULT_LIB = REPO / "build" / "host" / "libffr.so"  # a checkout's (make firmware-host)


def library_path(explicit: str | None = None) -> Path:
    """``ctypes:PATH``, else ``$FFR_FIRMWARE_LIB``, else our firmware: a checkout's build, or, for an
    installed ffr, the build in the user's cache (compiled from the shipped sources on first use)."""
    if explicit:
        return Path(explicit)
    from ffr_firmware.build import BuildError, locate

    try:
        return locate("library", "FFR_FIRMWARE_LIB")
    except BuildError as exc:
        raise LinkError(f"firmware library: {exc}") from None


@lru_cache(maxsize=8)
def load_library(path: str) -> tuple[ctypes.CDLL, LibraryLayout]:
    """Load and check a firmware library once per path."""
    p = Path(path)
    if not p.exists():
        raise LinkError(f"firmware library {p} not found: build it with `make firmware-host`")
    try:
        lib = ctypes.CDLL(str(p))
    except OSError as exc:
        raise LinkError(f"firmware library {p}: cannot be loaded: {exc}") from None
    try:
        layout = read_layout(lib, str(p))
    except AttributeError as exc:
        raise FirmwareLayoutError(f"{p}: not an ffr firmware library ({exc})") from None
    check_layout(layout, str(p))
    vp = ctypes.c_void_p
    lib.ffr_init.argtypes = [vp, vp]
    lib.ffr_init.restype = None
    lib.ffr_step.argtypes = [vp, vp, vp]
    lib.ffr_step.restype = None
    if hasattr(lib, "ffr_step_many"):  # our firmware's extra: used where present, never required
        lib.ffr_step_many.argtypes = [vp, vp, vp, ctypes.c_uint32]
        lib.ffr_step_many.restype = None
    lib.ffr_config_default.argtypes = [vp]
    lib.ffr_config_default.restype = None
    return lib, layout


def firmware_info(path: str | None = None) -> LibraryLayout:
    """What the firmware library (``path``, else $FFR_FIRMWARE_LIB, else ours) says about itself:
    its config dtype, state and failure names, name and layout hash."""
    return load_library(str(library_path(path)))[1]


def default_config(path: str | None = None) -> np.ndarray:
    """The firmware's own defaults (ffr_config_default) as a record of its config dtype."""
    lib, layout = load_library(str(library_path(path)))
    cfg = np.zeros((), dtype=layout.config_dtype)
    lib.ffr_config_default(cfg.ctypes.data)
    return cfg
