"""A link that started its own board (host board program, CAN board thread, QEMU): the board's end
is the link's "gone", and closing the link stops the board, whatever the transport between them."""

from __future__ import annotations

from typing import Protocol


class Board(Protocol):
    def gone(self, wait_s: float = 0.0) -> str | None: ...

    def stop(self) -> None: ...


class OwnsItsBoard:
    """Mix in before the transport's link class: ``class X(OwnsItsBoard, SerialLink)``."""

    board: Board

    def _gone(self, wait_s: float = 0.0) -> str | None:
        return self.board.gone(wait_s)

    def close(self) -> None:
        try:
            super().close()  # type: ignore[misc]  # the transport's close, next in the MRO
        finally:
            self._release_board()

    def _release_board(self) -> None:
        """Stop the board; a board with more to release (a bus, a log, a profile) extends this."""
        self.board.stop()
