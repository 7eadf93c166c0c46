"""Shared fixtures: the default arena and robot (read-only in tests)."""

from __future__ import annotations

import pytest

from sim_plant.arena import Arena, load_arena
from sim_plant.robot import RobotParams, load_robot


@pytest.fixture(scope="module")
def arena() -> Arena:
    return load_arena()


@pytest.fixture(scope="module")
def robot() -> RobotParams:
    return load_robot()
