"""The warm server's process (``python -m harness.serve``, started by ``ffr server start``):
harness/server.py's loop, running harness/cli.py's commands."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from harness.cli import main as cli_main
from harness.server import DEFAULT_IDLE_S, Server
from sim_plant.broken_pipe import exit_with


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(prog="python -m harness.serve")
    p.add_argument("--serve", type=Path, required=True, help="the socket to listen on")
    p.add_argument("--idle", type=float, default=DEFAULT_IDLE_S)
    a = p.parse_args(argv)
    Server(a.serve, a.idle, cli_main).serve()
    return 0


if __name__ == "__main__":
    exit_with(lambda: main(sys.argv[1:]))
