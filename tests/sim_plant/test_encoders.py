"""Wheel encoders: cumulative counts = floor(phi * ticks_per_rev / 2π)."""

from __future__ import annotations

import math

import pytest

from sim_plant.arena import load_arena
from sim_plant.candle import Candle
from sim_plant.robot import load_robot
from sim_plant.sensors import CH_ENC_L, CH_ENC_R, SensorSuite, new_output
from sim_plant.sensors.encoders import encoder_counts

TPR = 360
TICK = 2.0 * math.pi / TPR


@pytest.mark.parametrize("n", [0, 1, 2, 359, 360, 1000, -1, -2, -360, -721])
def test_counts_mid_tick(n):
    assert encoder_counts((n + 0.5) * TICK, TPR) == n


def test_counts_at_zero_and_tiny_negative():
    assert encoder_counts(0.0, TPR) == 0
    assert encoder_counts(-1e-9, TPR) == -1  # floor, not truncation toward zero
    assert encoder_counts(0.999 * TICK, TPR) == 0


def test_suite_writes_both_wheels():
    arena = load_arena()
    robot = load_robot()
    suite = SensorSuite(arena, robot, Candle(*arena.room(1).default_candle, robot, arena))
    out = new_output()
    suite.sample(0.0, 0.97, 0.5, 0.0, 0.0, 0.0, out)
    assert out[CH_ENC_L] == 0 and out[CH_ENC_R] == 0
    suite.sample(0.01, 0.97, 0.5, 0.0, -3.0, 7.5, out)
    tpr = robot.encoder.ticks_per_rev
    assert out[CH_ENC_L] == math.floor(-3.0 * tpr / (2 * math.pi))  # -172
    assert out[CH_ENC_R] == math.floor(7.5 * tpr / (2 * math.pi))  # 429
    assert out[CH_ENC_L] == -172 and out[CH_ENC_R] == 429
