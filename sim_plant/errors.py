"""Errors raised on bad input files: one line naming the file, field and value."""

from __future__ import annotations


class FfrInputError(ValueError):
    """A user-supplied file or argument is invalid.

    str() is the one-line message the CLI prints: ``file: field = value: why``.
    """

    def __init__(self, source: str, field: str, value: object, why: str) -> None:
        self.source = source
        self.field = field
        self.value = value
        self.why = why
        super().__init__(f"{source}: {field} = {value!r}: {why}")


class CandlePlacementError(FfrInputError):
    """A candle position breaks one of the contest's placement rules.

    ``rule`` is a short stable identifier (e.g. ``"in-hallway"``) tests key on.
    """

    def __init__(self, source: str, field: str, value: object, rule: str, why: str) -> None:
        self.rule = rule
        super().__init__(source, field, value, f"rule '{rule}': {why}")
