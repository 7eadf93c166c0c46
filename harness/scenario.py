"""Mission scenarios: which arena, robot, candle, start, seed, noise and tuning.

A scenario is a TOML file (see ``docs/scenarios.md``) or built from CLI
options; both go through ``load_scenario`` / ``make_scenario`` and are
validated with one-line errors naming the file, field and value.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from harness.events import Event, parse_events
from harness.start_pose import (
    FURNITURE_STREAM,
    JITTER_STREAM,
    START_AREAS,
    START_STREAM,
    check_start,
    draw_hallway_start,
    draw_start,
    stream,
)
from sim_plant.arena import DEFAULT_ARENA, Arena, load_arena
from sim_plant.arena_jitter import check_jitter, jitter_arena
from sim_plant.errors import FfrInputError
from sim_plant.furniture import Piece, check_furniture, draw_furniture, furnish
from sim_plant.robot import DEFAULT_ROBOT, RobotParams, load_robot, override
from sim_plant.schema import check, read_toml
from sim_plant.sensors import NoiseProfile, load_noise_profile
from sim_plant.sensors.noise import profile_from_table, profile_to_table

# a pose (x, y m, heading rad), "random" (in the home circle), "hallway" (random in a hallway: the
# arbitrary start mode), or None (the default)
StartSpec = tuple[float, float, float] | str | None
FurnitureSpec = int | list[Piece] | None  # N random pieces, the pieces, or none

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
    arena_jitter: float = 0.0  # m: ``arena`` is the file's arena jittered by this much (from the seed)
    candle_nominal: tuple[float, float] | None = None  # the candle asked for, before the jitter carried it
    start_random: bool = False  # ``start`` was drawn from the seed (docs/scenarios.md)
    start_area: str = "home"  # "hallway": the contest's arbitrary start mode
    furniture: list[Piece] = field(default_factory=list)  # standing in the rooms (walls of ``arena``)
    furniture_random: int = 0  # the pieces were drawn from the seed (this many)

    @property
    def modes(self) -> list[str]:
        """The contest's optional modes this mission runs in (their score factors: scoring.toml)."""
        return (["arbitrary_start"] if self.start_area == "hallway" else []) + (
            ["furniture"] if self.furniture else [])

    def requested_candle(self) -> tuple[float, float]:
        """The candle position as asked for (in the unjittered arena): what a saved scenario records."""
        return self.candle_nominal if self.candle_nominal is not None else self.candle
    ir_sources: tuple[IrSource, ...] = ()  # scenario [[ir_source]] objects

    def ir_source_array(self) -> np.ndarray:
        """(n, 4) x, y, z, strength: what ``SensorSuite`` takes."""
        return np.array([[q.x, q.y, q.height, q.strength] for q in self.ir_sources],
                        dtype=np.float64).reshape(len(self.ir_sources), 4)


def default_start(arena: Arena) -> tuple[float, float, float]:
    """Centre of the home circle, facing the arena file's ``[home] heading_deg`` (default +y: up the
    east hallway of the 2004 arena)."""
    return arena.home_center[0], arena.home_center[1], arena.home_heading


def make_scenario(*, arena: Arena | None = None, robot: RobotParams | None = None,
                  room: int | None = None, candle: tuple[float, float] | None = None,
                  seed: int = 0, noise: str | NoiseProfile = "none",
                  firmware: dict[str, Any] | None = None, robot_overrides: dict[str, Any] | None = None,
                  start: StartSpec = None, timing: Timing | None = None,
                  name: str | None = None, source: str = "command line",
                  stop_on_contact: bool = False, events: list[Event] | None = None,
                  arena_jitter: float = 0.0, furniture: FurnitureSpec = None,
                  start_area: str = "home", ir_sources: tuple[IrSource, ...] = ()) -> Scenario:
    """A mission. ``start``: a pose (checked: centre in the home circle, footprint clear of the walls),
    ``"random"`` (drawn from the seed's start stream) or None (the home circle's centre, facing the
    arena file's start heading).
    ``arena_jitter`` > 0: the arena's walls and doors moved within that many metres, drawn from the
    seed's jitter stream; the candle is carried with them (sim_plant/arena_jitter.py).
    ``furniture``: that many pieces drawn from the seed's furniture stream, or the pieces; they
    stand in the rooms as more walls (sim_plant/furniture.py). ``start_area`` "hallway": a pose
    given is checked against the hallways instead of the home circle (the arbitrary start mode)."""
    arena = arena or load_arena()
    robot = robot or load_robot()
    robot_file = None if robot.source == str(DEFAULT_ROBOT) else robot.source
    for key, value in (robot_overrides or {}).items():
        robot = override(robot, key, value, source)
    named = room is not None or candle is None
    if candle is not None:
        rm = arena.check_candle(candle[0], candle[1], source=source)
        room_id = rm.id
    else:
        room_id = 1 if room is None else room
        rm = arena.room(room_id)
        candle = rm.default_candle
    nominal = (float(candle[0]), float(candle[1]))
    check_jitter(arena, arena_jitter, source, "arena_jitter")
    if arena_jitter > 0.0:
        arena, warp = jitter_arena(arena, float(arena_jitter), stream(seed, JITTER_STREAM), candle=nominal)
        candle = warp.point(nominal)
    if isinstance(furniture, int):
        pieces = draw_furniture(arena, furniture, candle, stream(seed, FURNITURE_STREAM), source)
    else:
        pieces = list(furniture or [])
        check_furniture(arena, pieces, candle, source)
    arena = furnish(arena, pieces)
    if start_area not in START_AREAS:
        raise FfrInputError(source, "start.area", start_area, f"expected one of {', '.join(START_AREAS)}")
    if isinstance(start, str):
        if start not in ("random", "hallway"):
            raise FfrInputError(source, "start", start, "expected X,Y,DEG, random or hallway")
        if start == "hallway":
            start_area = "hallway"
            pose = draw_hallway_start(arena, robot, stream(seed, START_STREAM))
        elif start_area == "hallway":
            pose = draw_hallway_start(arena, robot, stream(seed, START_STREAM))
        else:
            pose = draw_start(arena, robot, stream(seed, START_STREAM))
    elif start is None:
        if start_area == "hallway":
            raise FfrInputError(source, "start.area", start_area, "needs a pose or random = true")
        pose = default_start(arena)
    else:
        pose = (float(start[0]), float(start[1]), float(start[2]))
        check_start(arena, robot, pose, source, area=start_area)
    prof = noise if isinstance(noise, NoiseProfile) else load_noise_profile(noise)
    return Scenario(
        name=name or (f"room{room_id}" if named else "candle"),
        source=source, arena=arena, robot=robot, candle=(float(candle[0]), float(candle[1])),
        room=room_id, start=pose, seed=seed, noise=prof,
        firmware=dict(firmware or {}), robot_overrides=dict(robot_overrides or {}),
        timing=timing or Timing(), stop_on_contact=stop_on_contact, events=list(events or []),
        robot_file=robot_file, arena_jitter=float(arena_jitter),
        candle_nominal=nominal if arena_jitter > 0.0 else None, start_random=start in ("random", "hallway"),
        start_area=start_area, furniture=pieces,
        furniture_random=furniture if isinstance(furniture, int) else 0,
        ir_sources=tuple(ir_sources),
    )


def load_scenario(path: str | Path, *, seed: int | None = None, start: StartSpec = None,
                  arena_jitter: float | None = None, furniture: int | None = None) -> Scenario:
    """Load a scenario file; ``seed``, ``start``, ``arena_jitter`` and ``furniture`` (from the CLI)
    override the file's. Every table is checked against ``harness/scenario_schema.ScenarioFile``
    first (keys, types, ranges, cross-field rules); what needs the arena is checked here."""
    p = Path(path)
    return scenario_from_dict(read_toml(p), str(p), p.parent, p.stem, seed=seed, start=start,
                              arena_jitter=arena_jitter, furniture=furniture)


def scenario_from_dict(data: dict[str, Any], source: str, base: Path, default_name: str = "scenario", *,
                       seed: int | None = None, start: StartSpec = None, arena_jitter: float | None = None,
                       furniture: int | None = None) -> Scenario:
    """A scenario from a scenario file's tables; relative file names are relative to ``base``."""
    from harness.scenario_schema import CandleTable, ScenarioFile

    src = source
    f: ScenarioFile = check(data, ScenarioFile, src)

    def rel(key: str) -> Path | None:
        v = getattr(f, key)
        if v is None:
            return None
        q = (base / v) if not Path(v).is_absolute() else Path(v)
        if not q.exists():
            raise FfrInputError(src, key, v, "file not found")
        return q

    arena = load_arena(rel("arena"))
    robot = load_robot(rel("robot"))
    noise: Any = f.noise
    if isinstance(data.get("noise"), dict):  # an inline profile: [noise.ir], [noise.flame], ...
        noise = profile_from_table(data["noise"], src, "noise")
    elif noise.endswith(".toml") or "#" in noise:
        noise = str(base / noise)
    else:
        try:
            noise = load_noise_profile(noise)
        except FfrInputError as exc:  # a name the profiles file lacks: this file's field is wrong
            raise FfrInputError(src, "noise", noise, exc.why) from None
    c = f.candle or CandleTable()
    room, candle = c.room, c.position
    if candle is not None:
        arena.check_candle(*candle, source=src)
    elif room is not None and room not in [rm.id for rm in arena.rooms]:
        raise FfrInputError(src, "candle.room", room, f"no such room in {arena.source} "
                                                      f"(rooms: {[rm.id for rm in arena.rooms]})")
    file_start: StartSpec = None
    start_area = "home"
    if f.start is not None:
        s = f.start
        start_area = s.area
        if s.random:
            file_start = "random"
        else:
            assert s.x is not None and s.y is not None  # the schema's rule
            heading = s.heading_deg if s.heading_deg is not None else math.degrees(arena.home_heading)
            file_start = (s.x, s.y, math.radians(heading))
    jitter = f.arena_jitter if arena_jitter is None else arena_jitter
    t = f.timing
    timing = Timing() if t is None else Timing(t.firmware_period_ms, t.plant_dt_ms, t.find_limit_s,
                                                t.return_limit_s, t.start_delay_ms)
    fw = data.get("firmware", {})  # its keys: the firmware's config layout (harness/firmware_config.py)
    ro = data.get("robot_overrides", {})
    events = parse_events(data.get("events", []), src)
    file_furniture: FurnitureSpec = f.furniture if not isinstance(f.furniture, list) else [
        Piece(q.x, q.y, q.width, q.depth, math.radians(q.heading_deg)) for q in f.furniture]
    sources = []
    for i, q in enumerate(f.ir_source or []):
        x, y = q.position
        w, h = arena.size
        if not (0.0 <= x <= w and 0.0 <= y <= h):
            raise FfrInputError(src, f"ir_source[{i}].position", [x, y],
                                f"must be inside the arena (0..{w:g}, 0..{h:g} m)")
        sources.append(IrSource(x, y, arena.flame_height if q.height is None else q.height, q.strength, q.name))
    name = f.name if f.name is not None else default_name
    return make_scenario(arena=arena, robot=robot, room=room, candle=candle,
                         seed=f.seed if seed is None else seed, noise=noise, firmware=fw,
                         robot_overrides=ro, start=file_start if start is None else start, timing=timing,
                         name=name, source=src, stop_on_contact=f.stop_on_contact, events=events,
                         arena_jitter=jitter, furniture=file_furniture if furniture is None else furniture,
                         start_area=start_area, ir_sources=tuple(sources))


# -- writing -------------------------------------------------------------------

def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"cannot write {v!r} to TOML")
        return repr(float(v))  # shortest text that reads back to the same double (numpy's too)
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
    if scn.arena_jitter > 0.0:
        lines.append(f"arena_jitter = {_toml_value(float(scn.arena_jitter))}  # walls moved, drawn from the seed")
    lines.append(f"stop_on_contact = {_toml_value(scn.stop_on_contact)}")
    table = profile_to_table(scn.noise)
    if not table:
        lines.append('noise = "none"')
    cx, cy = scn.requested_candle()
    lines += ["", "[candle]", f"position = {_toml_value([cx, cy])}"]
    if scn.start_random:
        lines += ["", "# drawn by start.random = true from the seed: the pose it drew"]
    lines += ["", "[start]", f"x = {_toml_value(float(scn.start[0]))}", f"y = {_toml_value(float(scn.start[1]))}",
              f"heading_deg = {_toml_value(_degrees_exact(float(scn.start[2])))}"]
    if scn.start_area != "home":
        lines.append(f"area = {_toml_value(scn.start_area)}")
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
    if scn.furniture_random:
        lines += ["", f"# drawn by furniture = {scn.furniture_random} from the seed: the pieces it drew"]
    for pc in scn.furniture:
        lines += ["", "[[furniture]]", f"x = {_toml_value(pc.x)}", f"y = {_toml_value(pc.y)}",
                  f"width = {_toml_value(pc.width)}", f"depth = {_toml_value(pc.depth)}",
                  f"heading_deg = {_toml_value(_degrees_exact(pc.heading))}"]
    return "\n".join(lines) + "\n"
