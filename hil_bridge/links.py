"""The wire links' URL schemes. pyproject.toml names each factory as an entry point of the
group ``ffr.links`` (ffr_link/base.py finds them there); each imports its transport only when
used, so ``ctypes:`` runs never load pyserial or python-can."""

from __future__ import annotations

from ffr_link.base import FirmwareLink


def open_serial_url(url: str) -> FirmwareLink:
    from hil_bridge.serial_link import open_serial

    return open_serial(url)


def open_can_url(url: str) -> FirmwareLink:
    from hil_bridge.can_link import open_can

    return open_can(url)


def open_host_board_url(url: str) -> FirmwareLink:
    from hil_bridge.host_board import open_host_board

    return open_host_board(url)


def open_qemu_url(url: str) -> FirmwareLink:
    from hil_bridge.qemu_board import open_qemu

    return open_qemu(url)
