"""What every ``ffr`` command shares: the exit codes, the one-line usage error, and the argument
types of the options several commands take (``--seed``, ``--candle``, ``--set``, ``--start``,
``--arena-jitter``). cli.py and sweep_cli.py both import it; the pytest plugin parses its
``--ffr-set`` with ``parse_setting`` too."""

from __future__ import annotations

import argparse
import json
import math
from typing import Any, NoReturn

EXIT_OK, EXIT_MISSION, EXIT_INPUT = 0, 1, 2


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # one line, not usage + error
        raise UsageError(message)


def _candle(text: str) -> tuple[float, float]:
    parts = text.split(",")
    try:
        if len(parts) != 2:
            raise ValueError
        x, y = float(parts[0]), float(parts[1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"--candle = {text!r}: expected X,Y in metres") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise argparse.ArgumentTypeError(f"--candle = {text!r}: expected finite numbers")
    return x, y


def _start(text: str) -> tuple[float, float, float] | str:
    """``X,Y,DEG`` (metres, degrees counter-clockwise from +x), ``random`` (in the home circle) or
    ``hallway`` (random in a hallway: the arbitrary start mode); returns radians."""
    if text in ("random", "hallway"):
        return text
    parts = text.split(",")
    try:
        if len(parts) != 3:
            raise ValueError
        x, y, deg = (float(v) for v in parts)
        if not all(math.isfinite(v) for v in (x, y, deg)):
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--start = {text!r}: expected X,Y,DEG (metres, degrees), random or hallway") from None
    return x, y, math.radians(deg)


def _jitter(text: str) -> float:
    from sim_plant.arena_jitter import MAX_JITTER
    try:
        v = float(text)
        if not (math.isfinite(v) and 0.0 <= v <= MAX_JITTER):
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--arena-jitter = {text!r}: expected metres in 0 .. {MAX_JITTER}") from None
    return v


def add_arena_options(sp: argparse.ArgumentParser) -> None:
    """``--start`` and ``--arena-jitter``: on every command that runs missions."""
    sp.add_argument("--start", type=_start, default=None, metavar="X,Y,DEG|random|hallway",
                    help="start pose in the home circle (m, m, degrees from +x), or random: uniform in the "
                         "home circle, any heading, drawn from the seed (default: its centre, facing +y); hallway: the "
                         "arbitrary start mode, anywhere in a hallway, any heading")
    sp.add_argument("--arena-jitter", type=_jitter, default=None, metavar="METRES",
                    help="move every wall line and door edge by up to this much, drawn from the seed "
                         "(e.g. 0.025; default 0 or the scenario's)")
    sp.add_argument("--furniture", type=_furniture, default=None, metavar="N",
                    help="the furniture mode: N pieces standing in the rooms, drawn from the seed "
                         "(docs/arena.md, Furniture)")


def _seed(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--seed = {text!r}: expected a non-negative integer") from None
    if v < 0:
        raise argparse.ArgumentTypeError(f"--seed = {text!r}: expected a non-negative integer")
    return v


def parse_setting(text: str, option: str = "--set") -> tuple[str, str, Any]:
    """``firmware.NAME=VALUE`` or ``robot.PATH=VALUE`` -> (group, name, value); the value is JSON
    where it parses (numbers, lists, true), else the text. ValueError names the option."""
    key, sep, raw = text.partition("=")
    group, dot, name = key.partition(".")
    if not sep or not dot or group not in ("firmware", "robot") or not name:
        raise ValueError(f"{option} = {text!r}: expected firmware.NAME=VALUE or robot.PATH=VALUE")
    value: Any
    try:
        value = json.loads(raw)
    except json.JSONDecodeError:
        value = raw
    return group, name, value


def _setting(text: str) -> tuple[str, str, Any]:
    try:
        return parse_setting(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _furniture(text: str) -> int:
    from sim_plant.furniture import MAX_PIECES
    try:
        v = int(text)
        if not 0 <= v <= MAX_PIECES:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(f"--furniture = {text!r}: expected a count 0 .. {MAX_PIECES}") from None
    return v


def library_of_link(link: str) -> str | None:
    """The firmware library whose config and names a link's missions use: ``ctypes:PATH``'s PATH;
    for ``ctypes:`` and every wire link the host build ($FFR_FIRMWARE_LIB, else ours): None."""
    scheme, _, rest = link.partition(":")
    return rest or None if scheme == "ctypes" else None


def firmware_link(link: str, firmware: str | None) -> str:
    """``--firmware LIB.so`` is ``--link ctypes:LIB.so``; with another link it is a usage error."""
    if not firmware or link == f"ctypes:{firmware}":  # (a sweep checks its arguments twice)
        return link
    if link != "ctypes:":
        raise UsageError(f"--firmware = {firmware!r}: runs in-process; leave --link {link} out")
    return f"ctypes:{firmware}"
