"""The firmware link interface (a template method, in the manner of python-can's BusABC).

``step()`` is the public call: it stamps nothing, checks the reply's sequence
number against the request, and counts; each transport only implements
``_step_impl`` (and ``_reset_impl``). Transports are chosen by URL scheme from
a registry, like pyserial's URL handlers.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable

import numpy as np

from harness.firmware_abi import CONFIG_DTYPE, INPUTS_DTYPE, OUTPUTS_DTYPE


class LinkError(RuntimeError):
    """The firmware side failed, went silent or answered out of turn."""


class FirmwareLink(ABC):
    """One firmware instance, stepped in lockstep."""

    url: str = ""

    def __init__(self) -> None:
        self.steps = 0

    def reset(self, config: np.ndarray) -> None:
        """(Re)start the firmware with a configuration (a CONFIG_DTYPE record)."""
        if config.dtype != CONFIG_DTYPE:
            raise TypeError("config must be a CONFIG_DTYPE record")
        self.steps = 0
        self._reset_impl(config)

    def step(self, inputs: np.ndarray, outputs: np.ndarray) -> None:
        """Send one tick of inputs; fill ``outputs`` with the firmware's answer."""
        self._step_impl(inputs, outputs)
        if outputs["seq"] != inputs["seq"]:
            raise LinkError(
                f"{self.url}: reply for sequence {int(outputs['seq'])} to request {int(inputs['seq'])}")
        self.steps += 1

    def close(self) -> None:  # noqa: B027 - optional hook
        """Release the transport."""

    def __enter__(self) -> FirmwareLink:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    @abstractmethod
    def _reset_impl(self, config: np.ndarray) -> None: ...

    @abstractmethod
    def _step_impl(self, inputs: np.ndarray, outputs: np.ndarray) -> None: ...


_REGISTRY: dict[str, Callable[[str], FirmwareLink]] = {}


def register_link(scheme: str, factory: Callable[[str], FirmwareLink]) -> None:
    _REGISTRY[scheme] = factory


def open_link(url: str) -> FirmwareLink:
    """Open a link from its URL, e.g. ``ctypes:`` or ``ctypes:path/to/libffr.so``."""
    scheme, sep, _ = url.partition(":")
    if not sep:
        raise LinkError(f"--link = {url!r}: not a link URL (scheme:rest), known: {sorted(_REGISTRY)}")
    _load_builtin()
    factory = _REGISTRY.get(scheme)
    if factory is None:
        raise LinkError(f"--link = {url!r}: unknown scheme '{scheme}', known: {sorted(_REGISTRY)}")
    link = factory(url)
    link.url = url
    return link


def _load_builtin() -> None:
    # Imported lazily: a transport's dependencies load only when it is used.
    from harness.links import ctypes_link  # noqa: F401
    from hil_bridge import links  # noqa: F401  serial:, can:, host-board:


def new_inputs() -> np.ndarray:
    return np.zeros((), dtype=INPUTS_DTYPE)


def new_outputs() -> np.ndarray:
    return np.zeros((), dtype=OUTPUTS_DTYPE)
