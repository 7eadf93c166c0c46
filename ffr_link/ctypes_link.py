"""In-process link: the host build of the firmware (libffr.so) through ctypes."""

from __future__ import annotations

import ctypes

import numpy as np

from ffr_link.base import FirmwareLink, LinkCounters
from ffr_link.library import (  # noqa: F401 - re-exported: where callers have always found them
    DEFAULT_LIB,
    REPO,
    default_config,
    firmware_info,
    library_path,
    load_library,
)


class CtypesLink(FirmwareLink):
    """The firmware as a host shared library; its state in a numpy buffer we own."""

    def __init__(self, path: str | None = None) -> None:
        super().__init__()
        self.path = str(library_path(path))
        self.lib, self.layout = load_library(self.path)
        self.firmware = self.layout
        size = self.layout.sizes[99]
        # 8-byte aligned storage for ffr_state_t
        self._state = np.zeros((size + 7) // 8, dtype=np.uint64)
        self._state_ptr = self._state.ctypes.data
        self._step_fn = self.lib.ffr_step
        # raw addresses for the compiled loop (harness/tick.py), which calls ffr_step itself
        self.step_address = int(ctypes.cast(self._step_fn, ctypes.c_void_p).value or 0)
        self.state_address = int(self._state_ptr)
        self._bound: tuple[int, int, int, int] | None = None

    def _reset_impl(self, config: np.ndarray) -> None:
        self.lib.ffr_init(self._state_ptr, config.ctypes.data)

    def _step_impl(self, inputs: np.ndarray, outputs: np.ndarray) -> None:
        self._step_fn(self._state_ptr, inputs.ctypes.data, outputs.ctypes.data)

    def link_counters(self) -> LinkCounters:
        # a function call neither loses nor damages anything: one message each way per step
        n = self.earlier_steps + self.steps
        return LinkCounters(sent=n, received=n)

    def bind(self, inputs: np.ndarray, outputs: np.ndarray) -> None:
        """Fix the I/O buffers for ``step_bound`` (the loop's fast path)."""
        self._bound = (id(inputs), id(outputs), inputs.ctypes.data, outputs.ctypes.data)

    def step_bound(self) -> None:
        """``step`` on the bound buffers without re-deriving pointers (hot loop)."""
        assert self._bound is not None
        self._step_fn(self._state_ptr, self._bound[2], self._bound[3])
        self.steps += 1


def open_ctypes(url: str) -> FirmwareLink:
    """``ctypes:`` (our build) or ``ctypes:PATH`` (any library that meets the contract)."""
    rest = url.partition(":")[2]
    return CtypesLink(rest or None)
