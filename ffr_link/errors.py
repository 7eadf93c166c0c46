"""The link layer's error, at the bottom so that every module of ffr_link may raise it."""

from __future__ import annotations


class LinkError(RuntimeError):
    """The firmware side failed, went silent or answered out of turn."""
