"""The firmware link interface (a template method, in the manner of python-can's BusABC).

``step()`` is the public call: it stamps nothing, checks the reply's sequence
number against the request, and counts; each transport only implements
``_step_impl`` (and ``_reset_impl``). Transports are chosen by URL scheme from
a registry, like pyserial's URL handlers.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields
from importlib.metadata import EntryPoint, entry_points

import numpy as np

from ffr_link.abi import INPUTS_DTYPE, OUTPUTS_DTYPE, LibraryLayout
from ffr_link.errors import LinkError


@dataclass
class LinkCounters:
    """What crossed a link. On a link without injected faults every error counter stays 0:
    a retry, a CRC error, an error report or a stale answer there is a defect, never noise."""

    sent: int = 0          # messages sent (retries included)
    received: int = 0      # messages received and decoded
    crc_errors: int = 0    # frames that failed their CRC or framing, either side
    retries: int = 0       # messages sent again
    stale: int = 0         # late or repeated answers, ignored
    board_errors: int = 0  # error reports from the board
    watchdog: int = 0      # the board's watchdog tripped during a mission
    # ... or between two missions, while the host ran none: the board stopped a robot nobody was
    # driving, as it should; reported at the next reset, not an error of either mission
    idle_watchdog: int = 0

    ERRORS = ("crc_errors", "retries", "stale", "board_errors", "watchdog")

    def __str__(self) -> str:
        return (f"sent {self.sent}, received {self.received}, CRC errors {self.crc_errors}, "
                f"retries {self.retries}")

    def __sub__(self, other: LinkCounters) -> LinkCounters:
        return LinkCounters(**{f.name: getattr(self, f.name) - getattr(other, f.name) for f in fields(self)})

    def copy(self) -> LinkCounters:
        return LinkCounters(**asdict(self))

    def as_dict(self) -> dict[str, int]:
        return asdict(self)

    @property
    def errors(self) -> dict[str, int]:
        """The error counters that are not 0 (empty on a clean link)."""
        return {k: getattr(self, k) for k in self.ERRORS if getattr(self, k)}


class FirmwareLink(ABC):
    """One firmware instance, stepped in lockstep."""

    url: str = ""

    def __init__(self) -> None:
        self.steps = 0  # since the last reset
        self.earlier_steps = 0  # before it
        self.counters = LinkCounters()

    @property
    def faults_injected(self) -> bool:
        """True when the link was asked to damage frames (then error counters are expected)."""
        return False

    def link_counters(self) -> LinkCounters:
        """The counters so far (a snapshot)."""
        return self.counters.copy()

    @property
    def firmware(self) -> LibraryLayout:
        """What the firmware behind this link says about itself (its config dtype, names, hash).
        A board runs the firmware of the host build ($FFR_FIRMWARE_LIB, else ours): its library's."""
        fw = self.__dict__.get("_firmware")
        if fw is None:
            from ffr_link.library import firmware_info

            fw = self.__dict__["_firmware"] = firmware_info()
        return fw

    @firmware.setter
    def firmware(self, value: LibraryLayout) -> None:
        self.__dict__["_firmware"] = value

    def reset(self, config: np.ndarray) -> None:
        """(Re)start the firmware with a configuration (a record of ``self.firmware.config_dtype``)."""
        if config.dtype != self.firmware.config_dtype:
            raise TypeError("config must be a record of the firmware's config dtype")
        self.earlier_steps += self.steps
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


# Link schemes. A scheme is found, in this order, among those registered in this process
# (``register_link``) and those installed as entry points of the group ``ffr.links``: a
# distribution's ``[project.entry-points."ffr.links"] myscheme = "pkg.module:factory"``, the way
# python-can finds its interfaces. ffr's own schemes are entry points of ffr itself (pyproject.toml),
# so a team's link (a Bluetooth serial, a USB HID board, a logic-analyser replay) is a pip package,
# not a patch. A factory takes the whole URL and returns an open FirmwareLink.
ENTRY_POINT_GROUP = "ffr.links"

_REGISTRY: dict[str, Callable[[str], FirmwareLink]] = {}


def register_link(scheme: str, factory: Callable[[str], FirmwareLink]) -> None:
    _REGISTRY[scheme] = factory


def _installed() -> dict[str, EntryPoint]:
    return {ep.name: ep for ep in entry_points(group=ENTRY_POINT_GROUP)}


def known_schemes() -> list[str]:
    return sorted(set(_REGISTRY) | set(_installed()))


def _factory(url: str, scheme: str) -> Callable[[str], FirmwareLink]:
    factory = _REGISTRY.get(scheme)
    if factory is not None:
        return factory
    ep = _installed().get(scheme)
    if ep is None:
        raise LinkError(f"--link = {url!r}: unknown scheme '{scheme}', known: {known_schemes()}")
    try:
        loaded = ep.load()  # the module imports its transport only now: ctypes runs load no pyserial
    except (ImportError, AttributeError) as exc:
        raise LinkError(f"--link = {url!r}: the link plug-in {ep.value!r} ({ep.group}) does not load: "
                        f"{exc}") from None
    if not callable(loaded):
        raise LinkError(f"--link = {url!r}: the link plug-in {ep.value!r} is not a factory")
    register_link(scheme, loaded)
    return loaded


def open_link(url: str) -> FirmwareLink:
    """Open a link from its URL, e.g. ``ctypes:`` or ``ctypes:path/to/libffr.so``."""
    scheme, sep, _ = url.partition(":")
    if not sep or not scheme:
        raise LinkError(f"--link = {url!r}: not a link URL (scheme:rest), known: {known_schemes()}")
    link = _factory(url, scheme)(url)
    if not isinstance(link, FirmwareLink):
        raise LinkError(f"--link = {url!r}: the '{scheme}' factory gave {type(link).__name__}, not a FirmwareLink")
    link.url = url
    return link


def new_inputs() -> np.ndarray:
    return np.zeros((), dtype=INPUTS_DTYPE)


def new_outputs() -> np.ndarray:
    return np.zeros((), dtype=OUTPUTS_DTYPE)
