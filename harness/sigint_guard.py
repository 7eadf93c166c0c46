"""Ctrl-C held back while numba takes a ``numpy.random.Generator`` into a compiled call.

Why: numba (0.62) unboxes a Generator by calling ``ctypes.cast`` on the bit generator's
function pointers, and does not check that call's result. ``ctypes.cast`` is Python code, so a
Ctrl-C that lands there makes it return NULL with ``KeyboardInterrupt`` set, and numba reads an
attribute of NULL: the process dies of SIGSEGV instead of stopping cleanly (a served sweep
killed by Ctrl-C exited -11 instead of 130 once in CI; tests/harness/test_sigint_guard.py makes
it happen every time). Inside ``sigint_deferred()`` a SIGINT is only noted; it is raised as
``KeyboardInterrupt`` (or handed to the handler that was installed) the moment the block ends.
A mission's compiled kernel cannot be interrupted anyway, so Ctrl-C ends the command no later
than before.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType


@contextmanager
def sigint_deferred() -> Iterator[threading.Event]:
    """SIGINT noted, not acted on, inside the block; acted on at its end (main thread only: Python
    runs signal handlers there alone). A handler of SIG_IGN or SIG_DFL is left as it is: neither
    raises in Python code (a forked sweep worker ignores Ctrl-C). The block gets an event set when
    a SIGINT is noted, so a loop inside can stop early on its own terms."""
    noted = threading.Event()
    if threading.current_thread() is not threading.main_thread():
        yield noted
        return
    before = signal.getsignal(signal.SIGINT)
    if not callable(before):
        yield noted
        return
    got: list[FrameType | None] = []

    def note(_signum: int, frame: FrameType | None) -> None:
        got.append(frame)
        noted.set()

    # signal.signal runs any handler already pending first: a Ctrl-C from before the block is
    # raised here, outside it
    signal.signal(signal.SIGINT, note)
    try:
        yield noted
    finally:
        signal.signal(signal.SIGINT, before)
        if got:
            before(signal.SIGINT, got[0])
