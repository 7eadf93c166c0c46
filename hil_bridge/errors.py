"""Decoder statuses (the FFR_E_* codes of ffr_codec.h) and board error codes."""

from __future__ import annotations

from enum import IntEnum


class Status(IntEnum):
    OK = 0
    SHORT = -1
    LONG = -2
    COBS = -3
    CRC = -4
    TYPE = -5
    LENGTH = -6
    SEGMENT = -7


class ErrCode(IntEnum):
    """FFR_ERR_*: what a board's error report says went wrong."""

    NONE = 0
    CRC = 1
    FRAMING = 2
    LENGTH = 3
    TYPE = 4
    NOT_READY = 5
    SEQUENCE = 6
    PROTO = 7
    WATCHDOG = 8
    SEGMENT = 9


class DecodeError(ValueError):
    """A frame or message that does not decode; ``status`` says why."""

    def __init__(self, status: Status, what: str) -> None:
        super().__init__(f"{status.name.lower()}: {what}")
        self.status = status
