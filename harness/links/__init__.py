"""Links to the firmware: one interface, several transports, chosen by URL.

``open_link("ctypes:")`` gives the in-process host library; the wire links
(serial, CAN, host board, QEMU) register their schemes the same way, so the
lockstep loop never knows which one it drives.
"""

from harness.links.base import FirmwareLink, LinkError, open_link, register_link

__all__ = ["FirmwareLink", "LinkError", "open_link", "register_link"]
