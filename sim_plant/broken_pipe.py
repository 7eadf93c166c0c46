"""A command whose reader leaves early (``python -m ... | head -1``) ends quietly: no traceback, no
"Exception ignored" at the interpreter's exit, and the status of a process killed by SIGPIPE, as a
C tool's would be (Python ignores SIGPIPE, so the write raises BrokenPipeError instead).

Kept twice, byte for byte: sim_plant/broken_pipe.py (for sim_plant and harness) and
hil_bridge/broken_pipe.py (for hil_bridge), as neither package may import the other
(docs/architecture.md); tests/harness/test_broken_pipe.py checks that the two stay the same.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from typing import NoReturn

EXIT_BROKEN_PIPE = 128 + 13  # the shell's status of a process killed by SIGPIPE (signal 13)


def silence_stdout() -> int:
    """Point stdout at /dev/null and return EXIT_BROKEN_PIPE; call it on BrokenPipeError.

    Whatever is still buffered for the reader that left would fail again at the interpreter's exit
    flush, which prints "Exception ignored ... BrokenPipeError" and exits 120; into /dev/null it goes
    quietly."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return EXIT_BROKEN_PIPE


def exit_with(main: Callable[[], int | None]) -> NoReturn:
    """Run a command's ``main()`` and exit with its status; EXIT_BROKEN_PIPE, silently, if the reader
    of stdout left. For ``if __name__ == "__main__": exit_with(main)``."""
    try:
        try:
            status: int | str | None = main()
        except SystemExit as exc:  # argparse's --help and usage errors: their output is flushed below too
            status = exc.code
        sys.stdout.flush()  # here, not at exit: a short output stays buffered until then
    except BrokenPipeError:
        status = silence_stdout()
    sys.exit(status)
