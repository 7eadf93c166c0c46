"""The wall follower's scenario tests, through ffr's pytest plugin.

    ffr build --src . --out build
    pytest tests/test_missions.py --ffr-firmware build/libwall_follower.so

The ``ffr_mission`` fixture runs each mission over the session's link (``--ffr-firmware`` for the
in-process library, ``--ffr-link host-board:serial`` or ``qemu:mps2-an386`` for a board running
the same firmware), records its metrics as JUnit properties (``--junitxml``) and, when a test
fails, prints the ``ffr run`` command that replays it (the scenario file goes to
``--ffr-failures DIR``, default ``out/ffr-failures``).

What this firmware promises (README.md): rooms 2, 3 and 4, whose doors open onto the outer
walls, at least 90 % of legal candle positions under typical sensor noise (measured: 90 of 90, README.md);
room 1, the island room, never (its door faces the inner ring the follower does not take): the
mission ends with the firmware's own failure, "no flame found", without touching a wall.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from harness.scenario import load_scenario, make_scenario
from sim_plant.arena import load_arena

HERE = Path(__file__).resolve().parent.parent
SCENARIOS = sorted(p for p in (HERE / "scenarios").glob("*.toml") if p.stem != "room1_island")
REACHABLE = (2, 3, 4)
EXPECTED_RATE = 0.90  # of legal candles in the reachable rooms, typical noise
CANDLES = 30  # drawn per run of the rate test (10 a room)


@pytest.mark.parametrize("path", SCENARIOS, ids=[p.stem for p in SCENARIOS])
def test_scenario_home_without_touching_a_wall(ffr_mission, path: Path) -> None:
    res, trace = ffr_mission(load_scenario(path))
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0 and not res.candle_knocked
    assert res.time_to_extinguish_s is not None and res.time_to_extinguish_s <= 300.0
    assert res.total_time_s is not None and res.total_time_s - res.time_to_extinguish_s <= 120.0
    fans = trace.t[trace.actuators[:, 2] > 0]
    assert len(fans) > 0 and fans.min() < res.time_to_extinguish_s  # the fans put it out
    assert tuple(trace.actuators[-1, :2]) == (0, 0)  # and it ends stopped


def test_room1_is_out_of_reach_and_says_so(ffr_mission) -> None:
    res, _ = ffr_mission(load_scenario(HERE / "scenarios" / "room1_island.toml"), record=False)
    assert res.outcome == "error" and "no flame found" in res.detail, (res.outcome, res.detail)
    assert res.wall_contacts == 0


def test_success_rate_over_legal_candles(ffr_mission) -> None:
    """Build for the class: candles drawn uniformly over every legal spot of the reachable rooms
    (one seeded stream), each mission with its own noise seed."""
    arena = load_arena()
    rng = np.random.default_rng(16)
    outcomes = []
    for k in range(CANDLES):
        room = REACHABLE[k % len(REACHABLE)]
        x, y = arena.random_candle(room, rng)
        res, _ = ffr_mission(make_scenario(candle=(float(x), float(y)), seed=k, noise="typical"), record=False)
        outcomes.append(res.outcome)
    home = outcomes.count("home")
    assert home >= EXPECTED_RATE * CANDLES, f"home in {home} of {CANDLES}: {outcomes}"
