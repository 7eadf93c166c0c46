"""Shared fixtures: one real mission (room 1, the shortest) and its replay file."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

from harness.loop import Trace, run_mission
from harness.replay import ReplayData, save_replay
from harness.scenario import Scenario, make_scenario
from harness.scoring import MissionResult


@dataclass
class Replayed:
    scn: Scenario
    result: MissionResult
    trace: Trace
    data: ReplayData
    html: Path


@pytest.fixture(scope="session")
def room1(tmp_path_factory: pytest.TempPathFactory) -> Replayed:
    scn = make_scenario(room=1)
    result, trace = run_mission(scn)
    assert result.outcome == "home"
    html = tmp_path_factory.mktemp("replay") / "room1.html"
    data = save_replay(html, scn, trace, result)
    return Replayed(scn, result, trace, data, html)
