"""GP2D12 ranger: datasheet curve, fold-back, far tail, hold timing and ray geometry."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim_plant.candle import Candle
from sim_plant.sensors import (
    CH_IR,
    Gp2d12Model,
    SensorSuite,
    distance_to_mv,
    load_noise_profile,
    new_output,
)

# The GP2D12 datasheet's typical curve (as in sim_plant/sensors/gp2d12.py): cm -> V.
DATASHEET = [(10, 2.45), (12, 2.125), (14, 1.86), (16, 1.66), (18, 1.52), (20, 1.38),
             (25, 1.14), (30, 0.975), (35, 0.85), (40, 0.76), (45, 0.68), (50, 0.62),
             (60, 0.54), (70, 0.48), (80, 0.42)]


def make_suite(arena, robot, **kw):
    candle = Candle(*arena.room(1).default_candle, robot, arena)
    return SensorSuite(arena, robot, candle, **kw)


@pytest.mark.parametrize(("d_cm", "volts"), DATASHEET)
def test_datasheet_points_within_3_percent(d_cm, volts):
    mv = distance_to_mv(d_cm / 100.0)
    assert abs(mv - 1000.0 * volts) <= 0.03 * 1000.0 * volts


def test_curve_monotone_falling_from_peak_to_far():
    d = np.linspace(0.081, 3.5, 5000)
    mv = distance_to_mv(d)
    assert np.all(np.diff(mv) < 0.0)


def test_fold_back_below_10cm():
    assert distance_to_mv(0.05) < distance_to_mv(0.10)
    assert distance_to_mv(0.0) < 100.0
    assert distance_to_mv(0.02) < distance_to_mv(0.05) < distance_to_mv(0.08)
    # Ambiguous: 5 cm reads like some distance between 10 and 20 cm.
    assert distance_to_mv(0.20) < distance_to_mv(0.05) < distance_to_mv(0.10)


def test_a_wall_at_the_body_side_reads_125_mm_on_a_front_corner_ranger(robot):
    """home_orient.c's FOLD_CORNER_MAX_MM: a front corner ranger of the default robot reads a
    wall folded back (42-80 mm off it, beyond the body's side) at most ~125 mm; a wall nearer
    than 42 mm would be inside the body. Through ir_calibration.c's curve (k = 332,000 mV mm,
    offset 15 mV, d0 = 40 mm), as the firmware reads it."""
    ir = robot.ir["LF"]
    exit_m = (robot.body.width / 2.0 - ir.y) / math.sin(math.radians(ir.angle_deg))
    assert exit_m * 1000.0 == pytest.approx(42.4, abs=0.05)

    def firmware_mm(mv: float) -> float:
        return max(332000.0 / (mv - 15.0) - 40.0, 100.0)

    assert distance_to_mv(exit_m) == pytest.approx(2026.0, abs=1.0)
    assert firmware_mm(distance_to_mv(exit_m)) == pytest.approx(125.0, abs=0.5)
    # the whole fold-back branch beyond the side reads no more than that
    fold = [firmware_mm(distance_to_mv(d)) for d in np.linspace(exit_m, 0.08, 50)]
    assert max(fold) <= 125.5
    assert min(fold) == 100.0


def test_far_tail_falls_to_floor():
    assert distance_to_mv(1.0) < distance_to_mv(0.8)
    assert 250.0 <= distance_to_mv(4.0) <= 400.0
    assert distance_to_mv(4.0) < distance_to_mv(1.5) < distance_to_mv(1.0)
    # Smooth at 80 cm: no jump across the table's end.
    assert abs(distance_to_mv(0.8 + 1e-6) - distance_to_mv(0.8 - 1e-6)) < 0.01


def test_vectorised_keeps_shape_and_scalar_gives_float():
    d = np.array([[0.1, 0.2], [0.3, 0.8]])
    mv = distance_to_mv(d)
    assert mv.shape == (2, 2)
    assert mv[0, 1] == pytest.approx(1380.0)
    assert isinstance(distance_to_mv(0.2), float)


@pytest.mark.parametrize(
    ("x", "y", "theta", "name", "expected"),
    [
        # Room BR (inside x 1.22-2.42, y 0.02-0.92); CF sits 0.10 m ahead of the origin.
        (2.0, 0.5, 0.0, "CF", 2.42 - 2.10),
        (1.8, 0.5, math.pi / 2, "CF", 0.92 - 0.60),
        (1.8, 0.3, math.pi, "CF", 1.70 - 1.22),  # below the doorway (y 0.46-0.92)
        # LF at body (0.08, 0.07) looking 45° left: hits the right wall x = 2.42 first.
        (2.0, 0.5, 0.0, "LF", (2.42 - 2.08) * math.sqrt(2.0)),
    ],
)
def test_ray_geometry_known_pose(arena, robot, x, y, theta, name, expected):
    suite = make_suite(arena, robot, noise=load_noise_profile("single_ray"))  # one ray
    out = new_output()
    suite.sample(0.0, x, y, theta, 0.0, 0.0, out)
    i = ("CF", "LF", "RF", "LR", "RR").index(name)
    assert suite.ir_distance[i] == pytest.approx(expected, abs=1e-9)
    assert out[CH_IR[i]] == math.floor(distance_to_mv(expected) + 0.5)


@pytest.mark.parametrize(
    ("x", "y", "theta", "name", "perp", "incidence"),
    [   # the poses above; perpendicular distance to the wall hit and the aim's angle to its normal
        (2.0, 0.5, 0.0, "CF", 2.42 - 2.10, 0.0),
        (1.8, 0.5, math.pi / 2, "CF", 0.92 - 0.60, 0.0),
        (1.8, 0.3, math.pi, "CF", 1.70 - 1.22, 0.0),
        # lower than before: from (2.0, 0.5) the 47-degree ray would hit the top wall (a corner)
        (2.0, 0.3, 0.0, "LF", 2.42 - 2.08, math.pi / 4),
    ],
)
def test_default_beam_geometry_known_pose(arena, robot, x, y, theta, name, perp, incidence):
    """The default beam: 5 rays over +-2 degrees, ray j hits the flat wall at
    d_j = perp / cos(incidence + o_j), and the reading is 1/d = sum(d_j^-3) / sum(d_j^-2)."""
    suite = make_suite(arena, robot)
    out = new_output()
    suite.sample(0.0, x, y, theta, 0.0, 0.0, out)
    i = ("CF", "LF", "RF", "LR", "RR").index(name)
    h = math.radians(2.0)
    ds = [perp / math.cos(incidence - h + 2 * h * j / 4) for j in range(5)]
    want = sum(d ** -2 for d in ds) / sum(d ** -3 for d in ds)
    assert suite.ir_distance[i] == pytest.approx(want, abs=1e-9)
    assert min(ds) < want < max(ds) or incidence == 0.0
    assert out[CH_IR[i]] == math.floor(distance_to_mv(want) + 0.5)


def test_ranger_inside_wall_reads_contact(arena, robot):
    suite = make_suite(arena, robot)
    out = new_output()
    # CF at x = 2.43, inside the right outer wall.
    suite.sample(0.0, 2.33, 0.5, 0.0, 0.0, 0.0, out)
    assert suite.ir_distance[0] == 0.0
    assert out[CH_IR[0]] == 0


def test_output_held_between_measurements(arena, robot):
    period = Gp2d12Model().period
    suite = make_suite(arena, robot)
    out = new_output()
    dt = 0.01
    prev = None
    changes = []
    for n in range(40):
        t = n * dt
        # Drive toward the right wall of room BR: every new measurement sees a new distance.
        suite.sample(t, 1.6 + 0.003 * n, 0.5, 0.0, 0.0, 0.0, out)
        cf = int(out[CH_IR[0]])
        if prev is not None:
            changes.append(cf != prev)
        prev = cf
    # CF (phase 0) measures at the first tick at or after each k * period.
    due = [any((n - 1) * dt < k * period <= n * dt + 1e-9 for k in range(1, 20))
           for n in range(1, 40)]
    assert changes == due
    assert any(due) and not all(due)


def test_stagger_offsets_rangers(arena, robot):
    period = 0.0383
    phases = Gp2d12Model(period=period).phases(5)
    assert phases == pytest.approx([i * period / 5 for i in range(5)])
    assert Gp2d12Model(stagger=False).phases(5) == [0.0] * 5
    suite = make_suite(arena, robot)
    out = new_output()
    suite.sample(0.0, 1.6, 0.5, 0.0, 0.0, 0.0, out)
    d0 = suite.ir_distance
    suite.sample(0.01, 1.6, 0.55, 0.0, 0.0, 0.0, out)
    d1 = suite.ir_distance
    # The move changes every ranger's distance but CF's; at 10 ms only LF
    # (phase 7.66 ms) has measured again.
    assert [bool(a != b) for a, b in zip(d0, d1, strict=True)] == [False, True, False, False, False]


def test_configurable_period(arena, robot):
    suite = make_suite(arena, robot, ir_model=Gp2d12Model(period=0.01, stagger=False))
    out = new_output()
    seen = set()
    for n in range(5):
        suite.sample(n * 0.01, 1.6 + 0.01 * n, 0.5, 0.0, 0.0, 0.0, out)
        seen.add(int(out[CH_IR[0]]))
    assert len(seen) == 5


def test_default_beam_blurs_a_corner(arena, robot):
    """LF from (2.0, 0.5) aims 45 degrees at the right wall 1 cm below the room's top-right
    corner: its outer rays hit the top wall nearer, so the beam reads nearer than the one ray."""
    one = make_suite(arena, robot, noise=load_noise_profile("single_ray"))
    beam = make_suite(arena, robot)
    out = new_output()
    one.sample(0.0, 2.0, 0.5, 0.0, 0.0, 0.0, out)
    beam.sample(0.0, 2.0, 0.5, 0.0, 0.0, 0.0, out)
    d1, db = one.ir_distance[1], beam.ir_distance[1]
    assert d1 == pytest.approx((2.42 - 2.08) * math.sqrt(2.0))
    assert db < d1 - 0.002
