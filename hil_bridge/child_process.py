"""Boards that run as child processes (the host board program, QEMU): how one
ended, in words for the link's error, and stopping one for good."""

from __future__ import annotations

import contextlib
import signal
import subprocess
from collections.abc import Callable, Sequence


def describe_exit(proc: subprocess.Popen[bytes], label: str, wait_s: float = 0.0) -> str | None:
    """None while running; else '<label> killed by SIGKILL' or '<label> exited with status N'."""
    rc = proc.poll()
    if rc is None and wait_s > 0:
        with contextlib.suppress(subprocess.TimeoutExpired):
            rc = proc.wait(timeout=wait_s)
    if rc is None:
        return None
    if rc < 0:
        try:
            name = signal.Signals(-rc).name
        except ValueError:
            name = f"signal {-rc}"
        return f"{label} killed by {name}"
    return f"{label} exited with status {rc}"


def stop_process(proc: subprocess.Popen[bytes], steps: Sequence[Callable[[], None]], wait_s: float) -> None:
    """Try each step (e.g. close its stdin, terminate, kill) until it has exited."""
    for step in steps:
        if proc.poll() is not None:
            return
        step()
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=wait_s)
