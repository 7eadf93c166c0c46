"""The firmware link layer: one interface, several transports, chosen by URL.

The bottom package that both ``harness`` (the lockstep loop) and ``hil_bridge`` (the wire
transports) import, and that imports neither: the firmware ABI (``abi``), the ``FirmwareLink``
interface and its scheme registry (``base``), and the in-process host library (``ctypes_link``).
``open_link("ctypes:")`` gives the in-process library; ``serial:``, ``can:``, ``host-board:`` and
``qemu:`` are entry points of the group ``ffr.links``, found the same way as a team's own scheme,
so the lockstep loop never knows which one it drives.
"""

from ffr_link.base import ENTRY_POINT_GROUP, FirmwareLink, LinkError, known_schemes, open_link, register_link

__all__ = ["ENTRY_POINT_GROUP", "FirmwareLink", "LinkError", "known_schemes", "open_link", "register_link"]
