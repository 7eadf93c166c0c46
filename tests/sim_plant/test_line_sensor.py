"""Line sensor: white on doorway lines and both circle rings, black elsewhere; spot footprint."""

from __future__ import annotations

import math

import pytest

from sim_plant.candle import Candle
from sim_plant.sensors import CH_LINE, SensorSuite, new_output
from sim_plant.sensors.line_sensor import band_fraction


@pytest.fixture(scope="module")
def suite(arena, robot):
    candle = Candle(*arena.room(4).default_candle, robot, arena)
    return SensorSuite(arena, robot, candle)


def read_at(suite, robot, px, py, theta=0.3):
    """Line bit with the sensor's spot centred on (px, py)."""
    ls = robot.line_sensor
    x = px - ls.x * math.cos(theta) + ls.y * math.sin(theta)
    y = py - ls.x * math.sin(theta) - ls.y * math.cos(theta)
    out = new_output()
    suite.sample(0.0, x, y, theta, 0.0, 0.0, out)
    return int(out[CH_LINE])


@pytest.mark.parametrize("room_id", [1, 2, 3, 4])
def test_white_on_each_doorway_line(arena, robot, suite, room_id):
    (ax, ay), (bx, by) = arena.room(room_id).door
    assert read_at(suite, robot, (ax + bx) / 2, (ay + by) / 2) == 1
    assert read_at(suite, robot, ax + 0.2 * (bx - ax), ay + 0.2 * (by - ay)) == 1


def test_white_on_home_ring(arena, robot, suite):
    hx, hy = arena.home_center
    r = arena.home_radius
    for ang in (0.0, 1.0, 2.5, 4.0):
        assert read_at(suite, robot, hx + r * math.cos(ang), hy + r * math.sin(ang)) == 1


def test_white_on_candle_ring(arena, robot, suite):
    cx, cy = suite.candle.x, suite.candle.y
    r = arena.candle_circle_radius
    assert read_at(suite, robot, cx, cy + r) == 1
    assert read_at(suite, robot, cx - r, cy) == 1


@pytest.mark.parametrize(
    "where",
    ["room_centres", "hallway", "home_centre", "candle_centre", "just_off_door"],
)
def test_black_floor(arena, robot, suite, where):
    if where == "room_centres":
        pts = [tuple(r.polygon.mean(axis=0)) for r in arena.rooms]
    elif where == "hallway":
        pts = [(0.97, 1.60), (1.58, 1.17)]
    elif where == "home_centre":
        pts = [arena.home_center]
    elif where == "candle_centre":
        pts = [(suite.candle.x, suite.candle.y)]
    else:
        (ax, ay), (bx, by) = arena.room(4).door  # vertical line at x = 1.21
        pts = [((ax + bx) / 2 + 0.03, (ay + by) / 2), ((ax + bx) / 2 - 0.03, (ay + by) / 2)]
    for px, py in pts:
        assert read_at(suite, robot, px, py) == 0, (where, px, py)


def test_spot_fraction_threshold_at_line_edge(arena, robot, suite):
    (ax, ay), (bx, by) = arena.room(4).door
    xm, ym = (ax + bx) / 2, (ay + by) / 2
    hw = arena.line_width / 2
    rho = robot.line_sensor.spot_radius
    # Spot centre on the edge: half white (white_fraction 0.5 -> reads 1, just).
    assert band_fraction(hw, hw, rho) == pytest.approx(0.5)
    assert band_fraction(0.0, hw, rho) == pytest.approx(1.0)
    assert band_fraction(hw + rho, hw, rho) == 0.0
    assert read_at(suite, robot, xm + hw - 0.4 * rho, ym) == 1
    assert 0.5 < suite.line_fraction < 1.0
    assert read_at(suite, robot, xm + hw + 0.4 * rho, ym) == 0
    assert 0.0 < suite.line_fraction < 0.5


def test_spot_model_white_fraction_setting(arena, robot):
    from sim_plant.robot import override
    strict = override(robot, "line_sensor.white_fraction", 0.9)
    s = SensorSuite(arena, strict, Candle(*arena.room(4).default_candle, strict, arena))
    (ax, ay), (bx, by) = arena.room(4).door
    xm, ym = (ax + bx) / 2, (ay + by) / 2
    hw = arena.line_width / 2
    rho = robot.line_sensor.spot_radius
    # Spot centre 0.4 spot radii inside the line's edge: ~75 % white, under the 90 % needed.
    assert read_at(s, strict, xm + hw - 0.4 * rho, ym) == 0
    assert read_at(s, strict, xm, ym) == 1
