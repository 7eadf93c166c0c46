"""Mission scenarios: which arena, robot, candle, start, seed, noise and tuning.

A scenario is a TOML file (see ``docs/scenarios.md``) or built from CLI
options; both go through ``load_scenario`` / ``make_scenario`` and are
validated with one-line errors naming the file, field and value.
"""

from __future__ import annotations

import difflib
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from harness.events import Event, parse_events
from sim_plant.arena import DEFAULT_ARENA, Arena, _Reader, load_arena, read_toml
from sim_plant.errors import FfrInputError
from sim_plant.robot import DEFAULT_ROBOT, RobotParams, load_robot, override
from sim_plant.sensors import NoiseProfile, load_noise_profile
from sim_plant.sensors.noise import profile_from_table, profile_to_table

_TOP_KEYS = {"name", "seed", "noise", "arena", "robot", "candle", "start", "timing", "firmware",
             "robot_overrides", "events", "stop_on_contact", "ir_source"}


@dataclass(frozen=True)
class IrSource:
    """An infrared source besides the flame (a sunlit window, a lamp): a point the flame
    sensors see like a flame of ``strength`` times the paper's eq. (9) flame, not flickering,
    not reflected, never going out (docs/sensors.md)."""

    x: float
    y: float
    height: float
    strength: float
    name: str = "ir_source"


@dataclass
class Timing:
    firmware_period_ms: int = 10
    plant_dt_ms: float = 1.0
    find_limit_s: float = 300.0     # the contest's 5 min to find the candle
    return_limit_s: float = 120.0   # and 2 min to return
    start_delay_ms: int = 0


@dataclass
class Scenario:
    name: str
    source: str
    arena: Arena
    robot: RobotParams
    candle: tuple[float, float]
    room: int
    start: tuple[float, float, float]  # x, y (m), heading (rad)
    seed: int = 0
    noise: NoiseProfile = field(default_factory=lambda: load_noise_profile("none"))
    firmware: dict[str, Any] = field(default_factory=dict)
    robot_overrides: dict[str, Any] = field(default_factory=dict)
    timing: Timing = field(default_factory=Timing)
    stop_on_contact: bool = False
    events: list[Event] = field(default_factory=list)
    robot_file: str | None = None  # the robot file before robot_overrides (None: the default)
    ir_sources: tuple[IrSource, ...] = ()  # scenario [[ir_source]] objects

    def ir_source_array(self) -> np.ndarray:
        """(n, 4) x, y, z, strength: what ``SensorSuite`` takes."""
        return np.array([[q.x, q.y, q.height, q.strength] for q in self.ir_sources],
                        dtype=np.float64).reshape(len(self.ir_sources), 4)


def default_start(arena: Arena) -> tuple[float, float, float]:
    """Centre of the home circle, facing +y (up the east hallway of the 2004 arena)."""
    return arena.home_center[0], arena.home_center[1], math.pi / 2


def make_scenario(*, arena: Arena | None = None, robot: RobotParams | None = None,
                  room: int | None = None, candle: tuple[float, float] | None = None,
                  seed: int = 0, noise: str | NoiseProfile = "none",
                  firmware: dict[str, Any] | None = None, robot_overrides: dict[str, Any] | None = None,
                  start: tuple[float, float, float] | None = None, timing: Timing | None = None,
                  name: str | None = None, source: str = "command line",
                  stop_on_contact: bool = False, events: list[Event] | None = None,
                  ir_sources: tuple[IrSource, ...] = ()) -> Scenario:
    arena = arena or load_arena()
    robot = robot or load_robot()
    robot_file = None if robot.source == str(DEFAULT_ROBOT) else robot.source
    for key, value in (robot_overrides or {}).items():
        robot = override(robot, key, value, source)
    if candle is not None:
        rm = arena.check_candle(candle[0], candle[1], source=source)
        room_id = rm.id
    else:
        room_id = 1 if room is None else room
        rm = arena.room(room_id)
        candle = rm.default_candle
    prof = noise if isinstance(noise, NoiseProfile) else load_noise_profile(noise)
    return Scenario(
        name=name or (f"room{room_id}" if room is not None or candle is None else "candle"),
        source=source, arena=arena, robot=robot, candle=(float(candle[0]), float(candle[1])),
        room=room_id, start=start or default_start(arena), seed=seed, noise=prof,
        firmware=dict(firmware or {}), robot_overrides=dict(robot_overrides or {}),
        timing=timing or Timing(), stop_on_contact=stop_on_contact, events=list(events or []),
        robot_file=robot_file, ir_sources=tuple(ir_sources),
    )


def _ir_sources(r: _Reader, arena: Arena) -> tuple[IrSource, ...]:
    out = []
    for i, t in enumerate(r.tables("ir_source")):
        name = f"ir_source[{i}]"
        _known_only(t, name, {"name", "position", "height", "strength"})
        x, y = t.point("position")
        w, h = arena.size
        if not (0.0 <= x <= w and 0.0 <= y <= h):
            raise FfrInputError(r.source, f"{name}.position", [x, y],
                                f"must be inside the arena (0..{w:g}, 0..{h:g} m)")
        out.append(IrSource(x, y, t.number("height", arena.flame_height, lo=0.0, hi=5.0),
                            t.number("strength", lo=0.0, hi=1000.0), t.string("name", "ir_source")))
    return tuple(out)


def _timing(r: _Reader) -> Timing:
    t = Timing()
    period = r.get("firmware_period_ms", t.firmware_period_ms)
    if isinstance(period, bool) or not isinstance(period, int) or not 1 <= period <= 1000:
        raise FfrInputError(r.source, "timing.firmware_period_ms", period, "must be an integer 1..1000")
    plant = r.number("plant_dt_ms", t.plant_dt_ms, positive=True)
    if abs(period / plant - round(period / plant)) > 1e-9:
        raise FfrInputError(r.source, "timing.plant_dt_ms", plant,
                            "must divide the firmware period into whole plant steps")
    delay = r.get("start_delay_ms", 0)
    if isinstance(delay, bool) or not isinstance(delay, int) or delay < 0:
        raise FfrInputError(r.source, "timing.start_delay_ms", delay, "must be an integer >= 0")
    unknown = set(r.table) - {"firmware_period_ms", "plant_dt_ms", "find_limit_s", "return_limit_s",
                              "start_delay_ms"}
    if unknown:
        k = sorted(unknown)[0]
        raise FfrInputError(r.source, f"timing.{k}", r.table[k], "unknown field")
    return Timing(period, plant, r.number("find_limit_s", t.find_limit_s, positive=True),
                  r.number("return_limit_s", t.return_limit_s, positive=True), delay)


def _known_only(tab: _Reader, name: str, known: set[str]) -> None:
    """A table's keys are all known: a typo (``positon``) must never quietly change the experiment."""
    unknown = sorted(set(tab.table) - known)
    if unknown:
        k = unknown[0]
        near = difflib.get_close_matches(k, sorted(known), n=1)
        hint = f"did you mean {near[0]!r}? " if near else ""
        raise FfrInputError(tab.source, f"{name}.{k}", tab.table[k],
                            f"unknown field ({hint}known: {', '.join(sorted(known))})")


def load_scenario(path: str | Path, *, seed: int | None = None) -> Scenario:
    """Load a scenario file; ``seed`` (from the CLI) overrides the file's."""
    p = Path(path)
    src = str(p)
    data = read_toml(p)
    r = _Reader(src, data)
    unknown = set(data) - _TOP_KEYS
    if unknown:
        k = sorted(unknown)[0]
        raise FfrInputError(src, k, data[k], f"unknown field (known: {', '.join(sorted(_TOP_KEYS))})")
    base = p.parent

    def rel(key: str) -> Path | None:
        v = data.get(key)
        if v is None:
            return None
        if not isinstance(v, str):
            raise FfrInputError(src, key, v, "must be a file path")
        q = (base / v) if not Path(v).is_absolute() else Path(v)
        if not q.exists():
            raise FfrInputError(src, key, v, "file not found")
        return q

    arena = load_arena(rel("arena"))
    robot = load_robot(rel("robot"))
    file_seed = r.get("seed", 0)
    if isinstance(file_seed, bool) or not isinstance(file_seed, int) or file_seed < 0:
        raise FfrInputError(src, "seed", file_seed, "must be an integer >= 0")
    noise: Any = r.get("noise", "none")
    if isinstance(noise, dict):  # an inline profile: [noise.ir], [noise.flame], ...
        noise = profile_from_table(noise, src, "noise")
    elif not isinstance(noise, str):
        raise FfrInputError(src, "noise", noise, "must be a profile name or file, or a table")
    elif noise.endswith(".toml") or "#" in noise:
        noise = str(base / noise)
    candle_tab = r.sub("candle") if "candle" in data else _Reader(src, {}, "candle.")
    _known_only(candle_tab, "candle", {"room", "position"})
    room = candle_tab.get("room", None)
    pos = candle_tab.table.get("position")
    if room is not None and pos is not None:
        raise FfrInputError(src, "candle.position", pos, "give either candle.room or candle.position")
    if room is not None and (isinstance(room, bool) or not isinstance(room, int)):
        raise FfrInputError(src, "candle.room", room, "must be a room number")
    candle = candle_tab.point("position") if pos is not None else None
    if candle is not None:
        arena.check_candle(*candle, source=src)
    elif room is not None:
        arena.room(room)  # raises with the known ids
    start = None
    if "start" in data:
        s = r.sub("start")
        _known_only(s, "start", {"x", "y", "heading_deg"})
        start = (s.number("x"), s.number("y"), math.radians(s.number("heading_deg", 90.0)))
    timing = _timing(r.sub("timing")) if "timing" in data else Timing()
    fw = r.sub("firmware").table if "firmware" in data else {}
    ro = r.sub("robot_overrides").table if "robot_overrides" in data else {}
    stop = r.get("stop_on_contact", False)
    if not isinstance(stop, bool):
        raise FfrInputError(src, "stop_on_contact", stop, "must be true or false")
    events = parse_events(data.get("events", []), src)
    sources = _ir_sources(r, arena) if "ir_source" in data else ()
    name = r.string("name", p.stem)
    return make_scenario(arena=arena, robot=robot, room=room, candle=candle,
                         seed=file_seed if seed is None else seed, noise=noise, firmware=fw,
                         robot_overrides=ro, start=start, timing=timing, name=name, source=src,
                         stop_on_contact=stop, events=events, ir_sources=sources)


# -- writing -------------------------------------------------------------------

def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"cannot write {v!r} to TOML")
        return repr(v)  # shortest text that reads back to the same double
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _toml_key(k: str) -> str:
    return k if re.fullmatch(r"[A-Za-z0-9_-]+", k) else json.dumps(k)


def _toml_table(lines: list[str], header: str, table: dict[str, Any]) -> None:
    plain = {k: v for k, v in table.items() if not isinstance(v, dict)}
    subs = {k: v for k, v in table.items() if isinstance(v, dict)}
    if plain or not subs:
        lines += ["", f"[{header}]"] + [f"{_toml_key(k)} = {_toml_value(v)}" for k, v in plain.items()]
    for k, v in subs.items():
        _toml_table(lines, f"{header}.{_toml_key(k)}", v)


def _degrees_exact(rad: float) -> float:
    """Degrees that ``math.radians`` turns back into exactly ``rad`` (for a bit-identical replay)."""
    deg = math.degrees(rad)
    for direction in (math.inf, -math.inf):
        d = deg
        for _ in range(8):
            if math.radians(d) == rad:
                return d
            d = math.nextafter(d, direction)
    return deg


def scenario_to_toml(scn: Scenario, comment: str = "") -> str:
    """The scenario as a scenario file that ``load_scenario`` reads back to the same mission."""
    lines = [f"# {c}" for c in comment.splitlines()] if comment else []
    lines.append(f"name = {_toml_value(scn.name)}")
    lines.append(f"seed = {scn.seed}")
    if scn.arena.source != str(DEFAULT_ARENA):
        lines.append(f"arena = {_toml_value(str(Path(scn.arena.source).resolve()))}")
    if scn.robot_file:
        lines.append(f"robot = {_toml_value(str(Path(scn.robot_file).resolve()))}")
    lines.append(f"stop_on_contact = {_toml_value(scn.stop_on_contact)}")
    table = profile_to_table(scn.noise)
    if not table:
        lines.append('noise = "none"')
    lines += ["", "[candle]", f"position = {_toml_value([scn.candle[0], scn.candle[1]])}"]
    lines += ["", "[start]", f"x = {_toml_value(float(scn.start[0]))}", f"y = {_toml_value(float(scn.start[1]))}",
              f"heading_deg = {_toml_value(_degrees_exact(float(scn.start[2])))}"]
    tm = scn.timing
    lines += ["", "[timing]", f"firmware_period_ms = {tm.firmware_period_ms}",
              f"plant_dt_ms = {_toml_value(float(tm.plant_dt_ms))}",
              f"find_limit_s = {_toml_value(float(tm.find_limit_s))}",
              f"return_limit_s = {_toml_value(float(tm.return_limit_s))}",
              f"start_delay_ms = {tm.start_delay_ms}"]
    if table:
        _toml_table(lines, "noise", table)
    if scn.firmware:
        _toml_table(lines, "firmware", dict(scn.firmware))
    if scn.robot_overrides:
        _toml_table(lines, "robot_overrides", dict(scn.robot_overrides))
    for q in scn.ir_sources:
        lines += ["", "[[ir_source]]", f"name = {_toml_value(q.name)}",
                  f"position = {_toml_value([q.x, q.y])}", f"height = {_toml_value(q.height)}",
                  f"strength = {_toml_value(q.strength)}"]
    for ev in scn.events:
        lines += ["", "[[events]]"] + [f"{k} = {_toml_value(v)}" for k, v in ev.to_table().items()]
    return "\n".join(lines) + "\n"
