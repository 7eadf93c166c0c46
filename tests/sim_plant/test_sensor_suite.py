"""SensorSuite plumbing: channel layout, argument types, reset."""

from __future__ import annotations

import numpy as np
import pytest

from sim_plant.arena import load_arena
from sim_plant.candle import Candle
from sim_plant.robot import IR_NAMES, load_robot
from sim_plant.sensors import (
    CH_ENC_L,
    CH_ENC_R,
    CH_FLAME_L,
    CH_FLAME_R,
    CH_IR,
    CH_LINE,
    N_CHANNELS,
    SensorSuite,
    new_output,
)


@pytest.fixture(scope="module")
def suite():
    arena = load_arena()
    robot = load_robot()
    return SensorSuite(arena, robot, Candle(*arena.room(1).default_candle, robot, arena))


def test_channel_layout():
    assert CH_IR == (0, 1, 2, 3, 4) and len(CH_IR) == len(IR_NAMES)
    assert (CH_FLAME_L, CH_FLAME_R, CH_LINE, CH_ENC_L, CH_ENC_R, N_CHANNELS) == (5, 6, 7, 8, 9, 10)
    out = new_output()
    assert out.dtype == np.int32 and out.shape == (N_CHANNELS,)


def test_wrong_out_array_refused(suite):
    with pytest.raises(TypeError, match="int32"):
        suite.sample(0.0, 0.97, 0.5, 0.0, 0.0, 0.0, np.zeros(N_CHANNELS, dtype=np.int64))
    with pytest.raises(TypeError, match="int32"):
        suite.sample(0.0, 0.97, 0.5, 0.0, 0.0, 0.0, np.zeros(N_CHANNELS + 1, dtype=np.int32))


def test_integer_arguments_accepted(suite):
    a = new_output()
    b = new_output()
    suite.reset()
    suite.sample(1, 1, 1, 0, 2, 3, a)
    suite.reset()
    suite.sample(1.0, 1.0, 1.0, 0.0, 2.0, 3.0, b)
    assert np.array_equal(a, b)
    assert a[CH_ENC_L] == 114 and a[CH_ENC_R] == 171


def test_reset_restarts_the_ranger_schedule(suite):
    out = new_output()
    suite.reset()
    suite.sample(0.0, 0.97, 0.5, 0.0, 0.0, 0.0, out)
    first = out.copy()
    suite.sample(0.01, 0.97, 0.9, 1.0, 0.0, 0.0, out)  # CF not due yet: held
    assert out[CH_IR[0]] == first[CH_IR[0]]
    suite.reset()
    suite.sample(0.02, 0.97, 0.9, 1.0, 0.0, 0.0, out)  # after reset every ranger measures
    assert out[CH_IR[0]] != first[CH_IR[0]]
