"""Flame sensors: the paper's eq. (9), the K(dθ) lobe, walls and an extinguished candle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim_plant.candle import Candle
from sim_plant.geometry import edges_soa
from sim_plant.sensors import CH_FLAME_L, CH_FLAME_R, FlameModel, SensorSuite, new_output
from sim_plant.sensors.flame_sensor import flame_intensity, flame_k, flame_sensor_fc

HALF = math.radians(60.0)
NO_WALLS = np.zeros((0, 4))


def k_expected(dtheta_deg: float) -> float:
    """The documented lobe: raised cosine reaching 0 at ±60°."""
    a = abs(dtheta_deg)
    return 0.0 if a >= 60.0 else 0.5 * (1.0 + math.cos(math.pi * a / 60.0))


def test_k_curve_shape():
    assert flame_k(0.0, HALF) == 1.0
    assert flame_k(math.radians(30.0), HALF) == pytest.approx(0.5)
    assert flame_k(math.radians(-30.0), HALF) == pytest.approx(0.5)
    assert flame_k(math.radians(60.0), HALF) == 0.0
    assert flame_k(math.radians(90.0), HALF) == 0.0
    ks = [flame_k(math.radians(a), HALF) for a in range(0, 61)]
    assert all(b < a for a, b in zip(ks, ks[1:], strict=False))


@pytest.mark.parametrize(("r", "dtheta_deg"), [(0.5, 0.0), (0.2, 0.0), (1.0, 20.0), (0.3, -45.0),
                                               (0.8, 70.0)])
def test_eq9_at_known_r_and_angle(r, dtheta_deg):
    expected = 0.0125 * k_expected(dtheta_deg) / r**2
    assert flame_intensity(r, math.radians(dtheta_deg), HALF, 0.02) == pytest.approx(expected)


def test_sensor_geometry_without_walls():
    # Sensor at body (0.05, 0.03, 0.18) aimed +12°, robot at the origin facing +x,
    # flame 0.5 m straight ahead of the sensor's position at the same height.
    fc = flame_sensor_fc(0.0, 0.0, 1.0, 0.0, 0.05, 0.03, 0.18, math.radians(12.0), 0.0,
                         0.55, 0.03, 0.18, edges_soa(NO_WALLS), HALF, 0.02)
    assert fc == pytest.approx(0.0125 * k_expected(12.0) / 0.25)
    # Rotating the robot by 90° and the flame with it gives the same light.
    fc_rot = flame_sensor_fc(0.0, 0.0, 0.0, 1.0, 0.05, 0.03, 0.18, math.radians(12.0),
                             math.pi / 2, -0.03, 0.55, 0.18, edges_soa(NO_WALLS), HALF, 0.02)
    assert fc_rot == pytest.approx(fc)


def suite_with_candle(arena, robot, cx, cy):
    candle = Candle(cx, cy, robot, arena)
    return SensorSuite(arena, robot, candle), candle


def test_on_axis_counts_near_full_scale(arena, robot):
    model = FlameModel()
    cx, cy = arena.room(4).default_candle  # (2.30, 0.14)
    suite, _ = suite_with_candle(arena, robot, cx, cy)
    out = new_output()
    # Turn the robot so the left sensor looks straight at the flame from ~20 cm.
    aim = math.radians(robot.flame.aim_deg)
    sx, sy = cx - 0.20 * math.cos(aim), cy - 0.20 * math.sin(aim)
    theta = 0.0
    x = sx - robot.flame.x * math.cos(theta) + robot.flame.y_offset * math.sin(theta)
    y = sy - robot.flame.x * math.sin(theta) - robot.flame.y_offset * math.cos(theta)
    suite.sample(0.0, x, y, theta, 0.0, 0.0, out)
    r = math.hypot(0.20, arena.flame_height - robot.flame.height)
    fc = 0.0125 / r**2
    assert suite.flame_fc[0] == pytest.approx(fc)
    assert out[CH_FLAME_L] == math.floor(model.gain * fc + 0.5) + model.dark
    assert 3500 < out[CH_FLAME_L] < 4095
    # The right sensor sees the flame 24° off its axis (aimed -12°), so less.
    assert model.dark < out[CH_FLAME_R] < out[CH_FLAME_L]


def test_wall_between_gives_dark_level(arena, robot):
    cx, cy = arena.room(4).default_candle  # room BR; its top wall is at y 0.92-0.94
    suite, _ = suite_with_candle(arena, robot, cx, cy)
    out = new_output()
    suite.sample(0.0, cx, 1.20, -math.pi / 2, 0.0, 0.0, out)  # hallway, facing the candle
    dark = FlameModel().dark
    assert out[CH_FLAME_L] == dark and out[CH_FLAME_R] == dark
    # The same geometry with no walls would see it.
    fc = flame_sensor_fc(cx, 1.20, 0.0, -1.0, 0.05, 0.03, 0.18, math.radians(12.0), -math.pi / 2,
                         cx, cy, arena.flame_height, edges_soa(NO_WALLS), HALF, 0.02)
    assert FlameModel().gain * fc > 50


def test_candle_out_gives_dark_level(arena, robot):
    cx, cy = arena.room(4).default_candle
    suite, candle = suite_with_candle(arena, robot, cx, cy)
    out = new_output()
    suite.sample(0.0, cx - 0.35, cy, 0.0, 0.0, 0.0, out)
    assert out[CH_FLAME_L] > 1000
    candle.lit = False
    suite.sample(0.01, cx - 0.35, cy, 0.0, 0.0, 0.0, out)
    assert out[CH_FLAME_L] == FlameModel().dark and out[CH_FLAME_R] == FlameModel().dark


def test_flame_behind_gives_dark_level(arena, robot):
    cx, cy = arena.room(4).default_candle
    suite, _ = suite_with_candle(arena, robot, cx, cy)
    out = new_output()
    suite.sample(0.0, cx - 0.35, cy, math.pi, 0.0, 0.0, out)
    assert out[CH_FLAME_L] == FlameModel().dark and out[CH_FLAME_R] == FlameModel().dark


def test_custom_gain_and_adc_bits(arena, robot):
    from sim_plant.robot import override
    r10 = override(robot, "flame.adc_bits", 10)
    cx, cy = arena.room(4).default_candle
    candle = Candle(cx, cy, r10, arena)
    suite = SensorSuite(arena, r10, candle, flame_model=FlameModel(gain=1e6, dark=0))
    out = new_output()
    suite.sample(0.0, cx - 0.35, cy, 0.0, 0.0, 0.0, out)
    assert out[CH_FLAME_L] == 1023  # saturates at the 10-bit full scale
