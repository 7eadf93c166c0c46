"""Registers the wire links' URL schemes with the harness (imported lazily by
``harness.links.base``). Each factory imports its transport only when used,
so ``ctypes:`` runs never load pyserial or python-can."""

from __future__ import annotations

from harness.links.base import FirmwareLink, register_link


def _serial(url: str) -> FirmwareLink:
    from hil_bridge.serial_link import open_serial

    return open_serial(url)


def _can(url: str) -> FirmwareLink:
    from hil_bridge.can_link import open_can

    return open_can(url)


def _host_board(url: str) -> FirmwareLink:
    from hil_bridge.host_board import open_host_board

    return open_host_board(url)


def _qemu(url: str) -> FirmwareLink:
    from hil_bridge.qemu_board import open_qemu

    return open_qemu(url)


register_link("serial", _serial)
register_link("qemu", _qemu)
register_link("can", _can)
register_link("host-board", _host_board)
