"""Preloaded into the worker processes of the local cluster ``ffr sweep`` starts (``LocalCluster(preload=)``)."""

from __future__ import annotations

import signal
from typing import Any


def dask_setup(worker: Any) -> None:
    # Ctrl-C in a terminal reaches every process of the group; the sweep's own process handles it (it keeps
    # the finished rows and stops this cluster), so its workers ignore it instead of printing tracebacks
    signal.signal(signal.SIGINT, signal.SIG_IGN)
