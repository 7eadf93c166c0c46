"""What the replay shows, as plain numbers: animation frames, chart samples, the scene.

Everything here is numpy and JSON-ready Python, with no browser and no
plotting library, so it is unit-tested on its own. ``build_replay`` turns a
scenario, its trace and its result into a ``ReplayData`` that ``html.py``
serialises.

Two rates: the 3D animation is downsampled to ``fps`` frames per simulated
second (the browser interpolates the pose between frames), the charts keep
``chart_hz`` samples per second. Both always keep the first and last tick, so
the replay ends exactly where the mission did.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from harness.loop import I_CONTACT, I_FAN, I_PWM_L, I_PWM_R, I_SENS, I_STATE, Trace
from harness.scenario import Scenario
from harness.scoring import TIME_DECIMALS, MissionResult, seconds_text
from harness.state_colors import state_colors
from sim_plant.robot import IR_NAMES, RobotParams
from sim_plant.sensors.channels import CH_ENC_L, CH_ENC_R, CH_FLAME_L, CH_FLAME_R, CH_IR, CH_LINE
from sim_plant.sensors.gp2d12 import D_FAR, D_PEAK, distance_to_mv

DEFAULT_FPS = 15.0
DEFAULT_CHART_HZ = 25.0


# Inverse of the GP2D12 curve on its far branch (8 cm .. 80 cm), by table:
# the model's curve is monotone there, so interpolation is exact to the grid.
_INV_D = np.linspace(D_PEAK, D_FAR, 1441)  # 0.5 mm steps
_INV_MV = np.asarray(distance_to_mv(_INV_D))[::-1].copy()  # ascending mV
_INV_D_ASC = _INV_D[::-1].copy()
MV_AT_FAR = float(_INV_MV[0])  # weaker readings: no wall within 80 cm


def ir_length(mv: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(beam length m, in range) for GP2D12 readings in mV.

    The length is what the reading says, on the far branch of the curve (the
    firmware's reading too: below 10 cm the sensor folds back). A reading
    weaker than the 80 cm output means "no wall in range": length 80 cm, flag
    False, drawn faint.
    """
    v = np.asarray(mv, dtype=np.float64)
    length = np.interp(v, _INV_MV, _INV_D_ASC)  # clamps at both ends
    return length, v >= MV_AT_FAR


def frame_indices(t: np.ndarray, rate_hz: float) -> np.ndarray:
    """Indices of the ticks at or just after k / rate_hz, k = 0, 1, ...; always the first and last tick."""
    n = len(t)
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    if not (math.isfinite(rate_hz) and rate_hz > 0):
        raise ValueError(f"rate must be > 0, got {rate_hz!r}")
    t0, t1 = float(t[0]), float(t[-1])
    k = np.arange(int(math.floor((t1 - t0) * rate_hz + 1e-9)) + 1)
    targets = t0 + k / rate_hz
    idx = np.searchsorted(t, targets - 1e-9, side="left")
    idx = np.unique(np.concatenate([[0], np.clip(idx, 0, n - 1), [n - 1]]))
    return idx.astype(np.int64)


def fan_on_time(t: np.ndarray, fan: np.ndarray) -> np.ndarray:
    """Seconds the fans have run up to each tick (drives the blades' angle)."""
    if len(t) == 0:
        return np.zeros(0)
    dt = np.diff(t, prepend=t[0])
    on_before = np.concatenate([[0], (fan[:-1] != 0).astype(np.float64)])
    return np.cumsum(dt * on_before)


def _r(a: np.ndarray, nd: int) -> list[Any]:
    """Rounded floats as a list (smaller file; same numbers every run)."""
    return [round(float(v), nd) for v in a]


def _ints(a: np.ndarray) -> list[int]:
    return [int(v) for v in a]


@dataclass
class ReplayData:
    """Everything the page needs; ``to_json`` is what is embedded."""

    meta: dict[str, Any]
    scene: dict[str, Any]
    robot: dict[str, Any]
    frames: dict[str, Any]
    charts: dict[str, Any]
    states: list[str] = field(default_factory=list)  # the firmware's state names (index = code)

    @property
    def n_frames(self) -> int:
        return len(self.frames["t"])

    def to_json(self) -> dict[str, Any]:
        return {"meta": self.meta, "scene": self.scene, "robot": self.robot, "frames": self.frames,
                "charts": self.charts, "states": self.states, "state_colors": state_colors(self.states)}


# -- meshes (body frame or arena frame, z up) --------------------------------

@dataclass
class Mesh:
    """Triangles with one colour per face, as Plotly's mesh3d wants them."""

    x: list[float] = field(default_factory=list)
    y: list[float] = field(default_factory=list)
    z: list[float] = field(default_factory=list)
    i: list[int] = field(default_factory=list)
    j: list[int] = field(default_factory=list)
    k: list[int] = field(default_factory=list)
    facecolor: list[str] = field(default_factory=list)

    def prism(self, outline: list[tuple[float, float]], z0: float, z1: float, color: str,
              plane: str = "xy", offset: float = 0.0, depth: float = 0.0) -> None:
        """Extrude a convex outline. plane "xy": outline in x, y, from z0 to z1.
        plane "xz": outline in x, z, from y = offset - depth/2 to offset + depth/2 (z0, z1 unused)."""
        base = len(self.x)
        n = len(outline)
        for lo in (True, False):
            for a, b in outline:
                if plane == "xy":
                    self._v(a, b, z0 if lo else z1)
                else:
                    self._v(a, offset + (-depth / 2 if lo else depth / 2), b)
        for m in range(1, n - 1):  # caps (fans from vertex 0)
            self._f(base, base + m, base + m + 1, color)
            self._f(base + n, base + n + m + 1, base + n + m, color)
        for m in range(n):  # sides
            a, b = base + m, base + (m + 1) % n
            self._f(a, b, b + n, color)
            self._f(a, b + n, a + n, color)

    def box(self, x0: float, x1: float, y0: float, y1: float, z0: float, z1: float, color: str) -> None:
        self.prism([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], z0, z1, color)

    def _v(self, x: float, y: float, z: float) -> None:
        self.x.append(round(x, 4))
        self.y.append(round(y, 4))
        self.z.append(round(z, 4))

    def _f(self, a: int, b: int, c: int, color: str) -> None:
        self.i.append(a)
        self.j.append(b)
        self.k.append(c)
        self.facecolor.append(color)

    def to_json(self) -> dict[str, Any]:
        return {"x": self.x, "y": self.y, "z": self.z, "i": self.i, "j": self.j, "k": self.k,
                "facecolor": self.facecolor}


def _circle(cx: float, cy: float, r: float, n: int) -> list[tuple[float, float]]:
    return [(cx + r * math.cos(2 * math.pi * m / n), cy + r * math.sin(2 * math.pi * m / n)) for m in range(n)]


def _stadium(x_rear: float, x_front: float, r: float, z_mid: float, n: int = 8) -> list[tuple[float, float]]:
    """A track's side outline in (x, z): two half circles of radius r joined, convex."""
    pts = []
    for m in range(n + 1):  # front half circle, bottom to top
        a = -math.pi / 2 + math.pi * m / n
        pts.append((x_front - r + r * math.cos(a), z_mid + r * math.sin(a)))
    for m in range(n + 1):  # rear half circle, top to bottom
        a = math.pi / 2 + math.pi * m / n
        pts.append((x_rear + r + r * math.cos(a), z_mid + r * math.sin(a)))
    return pts


TRACK_WIDTH_M = 0.03  # m, belt width (drawn; not a model parameter)


def robot_model(robot: RobotParams) -> dict[str, Any]:
    """The tracked vehicle in its body frame (x forward, y left, z up) and the moving parts' anchors."""
    b = robot.body
    tr = robot.track
    front, rear, half_w = b.length_front, -b.length_rear, b.width / 2.0
    r_track = min(tr.wheel_radius + 0.006, 0.35 * b.height)  # belt around the sprocket
    track_y = tr.track_width / 2.0
    mesh = Mesh()
    # Tracks on both sides: the belt, as a stadium prism.
    outline = _stadium(rear, front, r_track, r_track)
    for side in (1, -1):
        mesh.prism(outline, 0, 0, "#2b2b2b", plane="xz", offset=side * track_y, depth=TRACK_WIDTH_M)
    # Hull between the tracks, deck over everything, a darker sensor mast at the front.
    inner = track_y - TRACK_WIDTH_M / 2 - 0.003
    z_deck = 2 * r_track + 0.01
    mesh.box(rear + 0.01, front - 0.01, -inner, inner, 0.015, z_deck, "#b03a2e")
    mesh.box(rear, front, -half_w, half_w, z_deck, z_deck + 0.02, "#c0392b")
    top = b.height
    mesh.box(rear + 0.02, front - 0.05, -0.05, 0.05, z_deck + 0.02, top - 0.03, "#7b241c")
    # Flame sensors: two small dark blocks on the top, near the front.
    fl = robot.flame
    for side in (1, -1):
        mesh.box(fl.x - 0.01, fl.x + 0.01, side * fl.y_offset - 0.008, side * fl.y_offset + 0.008,
                 top - 0.03, top - 0.015, "#111111")
    # Rangers: small boxes at their poses.
    ir = []
    for name in IR_NAMES:
        p = robot.ir[name]
        # the robot file has no ranger height: draw beams at the rangers' boxes on the deck
        ir.append({"name": name, "x": p.x, "y": p.y, "z": round(z_deck + 0.0275, 4),
                   "angle": math.radians(p.angle_deg)})
        mesh.box(p.x - 0.01, p.x + 0.01, p.y - 0.01, p.y + 0.01, z_deck + 0.02, z_deck + 0.035, "#f1c40f")
    # Two fans at the front face, blowing forward; the browser spins their blades.
    fan_r = min(0.035, half_w / 2 - 0.01)
    fans = [{"x": robot.fans.x + 0.005, "y": side * (half_w / 2), "z": top - 0.03 - fan_r, "r": fan_r}
            for side in (1, -1)]
    for f in fans:
        mesh.box(f["x"] - 0.03, f["x"] - 0.005, f["y"] - 0.012, f["y"] + 0.012, z_deck + 0.02, f["z"],
                 "#555555")  # fan post
    tracks = [{"y": side * track_y, "x_rear": rear, "x_front": front, "r": r_track,
               "half_width": TRACK_WIDTH_M / 2 + 0.002} for side in (1, -1)]
    return {
        "mesh": mesh.to_json(),
        "ir": ir,
        "fans": fans,
        "tracks": tracks,  # left, right
        "wheel_radius": tr.wheel_radius,
        "ticks_per_rev": robot.encoder.ticks_per_rev,
        "fan_rev_per_s": 3.0,  # drawn speed: slow enough to see at 15-60 fps
        "front": front,
    }


def scene_model(scn: Scenario) -> dict[str, Any]:
    """The arena in 3D: walls extruded to their height, floor, doorway lines, circles, candle."""
    arena = scn.arena
    walls = Mesh()
    for poly in arena.wall_polys:
        walls.prism([(float(p[0]), float(p[1])) for p in poly], 0.0, arena.wall_height, "#e8e8e8")
    doors = Mesh()
    for poly in arena.door_polys:
        doors.prism([(float(p[0]), float(p[1])) for p in poly], 0.0, 0.003, "#ffffff")
    # The wall tops' outlines make the maze readable from above.
    edges: list[list[float | None]] = [[], [], []]
    for poly in arena.wall_polys:
        for p in [*poly, poly[0]]:
            edges[0].append(round(float(p[0]), 4))
            edges[1].append(round(float(p[1]), 4))
            edges[2].append(round(arena.wall_height, 4))
        for c in edges:
            c.append(None)
    cx, cy = scn.candle
    candle = Mesh()
    wick_z = max(arena.flame_height - 0.02, 0.02)
    candle.prism(_circle(cx, cy, arena.candle_radius, 16), 0.0, wick_z, "#f5f0e1")
    rooms = [{"id": r.id, "x": round(float(r.polygon[:, 0].mean()), 3), "y": round(float(r.polygon[:, 1].mean()), 3)}
             for r in arena.rooms]
    return {
        "size": list(arena.size),
        "wall_height": arena.wall_height,
        "walls": walls.to_json(),
        "wall_edges": {"x": edges[0], "y": edges[1], "z": edges[2]},
        "doors": doors.to_json(),
        "home": {"x": arena.home_center[0], "y": arena.home_center[1], "r": arena.home_radius},
        "candle_circle": {"x": cx, "y": cy, "r": arena.candle_circle_radius},
        "candle": candle.to_json(),
        "flame": {"x": cx, "y": cy, "z0": wick_z, "z1": arena.flame_height + 0.05, "r": 0.02},
        "line_width": arena.line_width,
        "rooms": rooms,
    }


def build_replay(scn: Scenario, trace: Trace, result: MissionResult, fps: float = DEFAULT_FPS,
                 chart_hz: float = DEFAULT_CHART_HZ) -> ReplayData:
    """Downsample a mission's trace into animation frames and chart samples."""
    if len(trace.t) == 0:
        raise ValueError("the mission recorded no tick (run it with record=True)")
    t = trace.t
    ti = trace.i
    fi = frame_indices(t, fps)
    ci = frame_indices(t, chart_hz)
    ir_mv = ti[:, [I_SENS + c for c in CH_IR]]
    length, in_range = ir_length(ir_mv[fi])
    fan = ti[:, I_FAN]
    fan_t = fan_on_time(t, fan)
    ext = result.time_to_extinguish_s
    lit = np.ones(len(fi), dtype=bool) if ext is None else t[fi] < ext
    frames = {
        "t": _r(t[fi], 3),
        "x": _r(trace.f[fi, 1], 4),
        "y": _r(trace.f[fi, 2], 4),
        "theta": _r(trace.f[fi, 3], 4),
        "ir_len": [_r(length[:, c], 3) for c in range(len(IR_NAMES))],
        "ir_ok": [_ints(in_range[:, c]) for c in range(len(IR_NAMES))],
        "ir_mv": [_ints(ir_mv[fi, c]) for c in range(len(IR_NAMES))],
        "fan": _ints(fan[fi] != 0),
        "fan_t": _r(fan_t[fi], 3),
        "state": _ints(ti[fi, I_STATE]),
        "pwm_l": _ints(ti[fi, I_PWM_L]),
        "pwm_r": _ints(ti[fi, I_PWM_R]),
        "flame_l": _ints(ti[fi, I_SENS + CH_FLAME_L]),
        "flame_r": _ints(ti[fi, I_SENS + CH_FLAME_R]),
        "line": _ints(ti[fi, I_SENS + CH_LINE]),
        "enc_l": _ints(ti[fi, I_SENS + CH_ENC_L]),
        "enc_r": _ints(ti[fi, I_SENS + CH_ENC_R]),
        "contact": _ints(ti[fi, I_CONTACT]),
        "lit": _ints(lit),
    }
    charts = {
        "t": _r(t[ci], 3),
        "ir_mv": {name: _ints(ir_mv[ci, c]) for c, name in enumerate(IR_NAMES)},
        "flame": {"L": _ints(ti[ci, I_SENS + CH_FLAME_L]), "R": _ints(ti[ci, I_SENS + CH_FLAME_R])},
        "pwm": {"L": _ints(ti[ci, I_PWM_L]), "R": _ints(ti[ci, I_PWM_R])},
        "fan": _ints(fan[ci] != 0),
        "line": _ints(ti[ci, I_SENS + CH_LINE]),
        "contact": _ints(ti[ci, I_CONTACT]),
        "state": _ints(ti[ci, I_STATE]),
    }
    path = _state_paths(trace)
    meta = {
        "scenario": scn.name,
        "room": scn.room,
        "seed": scn.seed,
        "candle": [round(scn.candle[0], 4), round(scn.candle[1], 4)],
        "outcome": result.outcome,
        "detail": result.detail,
        "time_to_extinguish_s": None if ext is None else round(float(ext), TIME_DECIMALS),
        "total_time_s": None if result.total_time_s is None else round(float(result.total_time_s), TIME_DECIMALS),
        # the header's figures as every other output prints them (JavaScript's toFixed rounds a
        # tie, 40.25, up where Python gives 40.2)
        "flame_out_text": seconds_text(ext),
        "home_text": seconds_text(result.total_time_s),
        "wall_contacts": int(result.wall_contacts),
        "t_end": round(float(t[-1]), 3),
        "fps": fps,
        "chart_hz": chart_hz,
        "path": path,
        "ir_names": list(IR_NAMES),
        "ir_far_m": D_FAR,
    }
    return ReplayData(meta=meta, scene=scene_model(scn), robot=robot_model(scn.robot), frames=frames,
                      charts=charts, states=list(trace.names_of_states()))


def _state_paths(trace: Trace, min_step: float = 0.01) -> dict[str, dict[str, list[float | None]]]:
    """The path on the floor, one polyline set per firmware state (gaps as None), thinned to
    points at least ``min_step`` apart so long missions stay small."""
    xy = trace.xy
    states = trace.state
    keep = [0]
    last = xy[0]
    for n in range(1, len(xy)):
        if states[n] != states[keep[-1]] or n == len(xy) - 1 or np.hypot(*(xy[n] - last)) >= min_step:
            keep.append(n)
            last = xy[n]
    out: dict[str, dict[str, list[float | None]]] = {}
    names = trace.names_of_states()
    prev_state = None
    for a, b in zip(keep[:-1], keep[1:], strict=True):
        s = int(states[b])
        name = names[s] if s < len(names) else f"state {s}"
        seg = out.setdefault(name, {"x": [], "y": []})
        if prev_state != s and seg["x"]:
            seg["x"].append(None)
            seg["y"].append(None)
        if prev_state != s:
            seg["x"].append(round(float(xy[a, 0]), 4))
            seg["y"].append(round(float(xy[a, 1]), 4))
        seg["x"].append(round(float(xy[b, 0]), 4))
        seg["y"].append(round(float(xy[b, 1]), 4))
        prev_state = s
    return out
