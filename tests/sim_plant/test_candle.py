"""Candle and fans: 4 s of fan in reach and in front puts the flame out; breaks reset the timer."""

from __future__ import annotations

import math

import pytest

from sim_plant.candle import Candle

DT = 0.01


@pytest.fixture
def candle(arena, robot):
    return Candle(2.0, 0.5, robot, arena)  # middle of room BR


def pose_facing(candle, robot, gap, off_deg=0.0):
    """Robot pose with the fan outlet ``gap`` m from the flame, heading off by ``off_deg``."""
    theta = math.radians(off_deg)
    # The outlet is on the line from the flame back along the bearing to the robot.
    ox, oy = candle.x - gap, candle.y
    return ox - robot.fans.x * math.cos(theta), oy - robot.fans.x * math.sin(theta), theta


def run(candle, pose, seconds, fan_on=True, t0=0.0):
    t = t0
    for _ in range(round(seconds / DT)):
        t += DT
        candle.update(t, DT, fan_on, *pose)
    return t


def test_goes_out_after_4_s_in_reach_and_in_front(candle, robot):
    pose = pose_facing(candle, robot, 0.15)
    t = run(candle, pose, 3.99)
    assert candle.lit
    assert candle.fan_time == pytest.approx(3.99)
    t = run(candle, pose, DT, t0=t)
    assert not candle.lit
    assert candle.extinguished_at == pytest.approx(4.0)
    assert candle.extinguished_at == t


def test_extinguish_time_from_robot_params(arena, robot):
    from sim_plant.robot import override
    fast = override(robot, "fans.time_to_extinguish", 1.5)
    c = Candle(2.0, 0.5, fast, arena)
    run(c, pose_facing(c, fast, 0.1), 1.5)
    assert not c.lit and c.extinguished_at == pytest.approx(1.5)


def test_not_out_of_reach(candle, robot):
    run(candle, pose_facing(candle, robot, robot.fans.reach + 0.05), 10.0)
    assert candle.lit and candle.fan_time == 0.0


def test_not_from_behind(candle, robot):
    x, y, _ = pose_facing(candle, robot, 0.15)
    run(candle, (x, y, math.pi), 10.0)
    assert candle.lit


def test_not_outside_the_cone(candle, robot):
    # The outlet stays 0.15 m west of the flame, the robot looks 40° off it (> 30°).
    theta = math.radians(40.0)
    ox, oy = candle.x - 0.15, candle.y
    pose = (ox - robot.fans.x * math.cos(theta), oy - robot.fans.x * math.sin(theta), theta)
    run(candle, pose, 10.0)
    assert candle.lit
    assert candle.fans_reach(*pose_facing(candle, robot, 0.15, 0.0))


def test_not_with_fans_off(candle, robot):
    run(candle, pose_facing(candle, robot, 0.15), 10.0, fan_on=False)
    assert candle.lit


def test_not_through_a_wall(arena, robot):
    c = Candle(1.5, 0.85, robot, arena)  # room BR, just below its top wall (y 0.92-0.94)
    theta = -math.pi / 2
    pose = (1.5, 1.15, theta)  # hallway above; outlet at y 1.03, 0.18 m from the flame
    run(c, pose, 10.0)
    assert c.lit
    assert not c.fans_reach(*pose)


def test_timer_resets_when_fans_stop(candle, robot):
    pose = pose_facing(candle, robot, 0.15)
    t = run(candle, pose, 3.0)
    t = run(candle, pose, DT, fan_on=False, t0=t)
    assert candle.fan_time == 0.0
    t = run(candle, pose, 3.0, t0=t)
    assert candle.lit  # 6 s of fan in total, but never 4 s without a break
    run(candle, pose, 1.0, t0=t)
    assert not candle.lit
    assert candle.extinguished_at == pytest.approx(7.01)


def test_timer_resets_when_robot_turns_away(candle, robot):
    pose = pose_facing(candle, robot, 0.15)
    x, y, _ = pose
    t = run(candle, pose, 3.5)
    t = run(candle, (x, y, math.radians(90.0)), DT, t0=t)
    run(candle, pose, 3.5, t0=t)
    assert candle.lit


def test_update_after_out_is_a_no_op(candle, robot):
    pose = pose_facing(candle, robot, 0.15)
    run(candle, pose, 4.0)
    at = candle.extinguished_at
    run(candle, pose, 1.0, t0=10.0)
    assert not candle.lit and candle.extinguished_at == at
