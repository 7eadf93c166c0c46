"""A slower board's tick: the firmware works from the tick times it is given.

The Cortex-M0 (nRF51, 16 MHz, soft float) cannot finish its worst step in
10 ms (docs/boards.md), so it runs a 20 ms tick (scenario ``[timing]
firmware_period_ms = 20``). These missions show the firmware keeps its
behaviour there: every room, and random legal candles with typical noise,
home with no wall touched."""

from __future__ import annotations

import numpy as np
import pytest

from harness.scenario import Timing, make_scenario
from sim_plant.arena import load_arena

M0_TICK_MS = 20
ARENA = load_arena()
RNG = np.random.default_rng(20)
RANDOM = [(room, ARENA.random_candle(room, RNG), seed) for seed, room in enumerate([1, 2, 3, 4] * 3)]


@pytest.mark.parametrize("room", [1, 2, 3, 4])
def test_every_room_at_a_20ms_tick(ffr_mission, room: int) -> None:
    res, _ = ffr_mission(make_scenario(room=room, timing=Timing(firmware_period_ms=M0_TICK_MS)), record=False)
    assert res.outcome == "home" and res.wall_contacts == 0, res.detail


@pytest.mark.parametrize(("room", "candle", "seed"), RANDOM, ids=[f"room{r}-seed{s}" for r, _, s in RANDOM])
def test_random_candles_with_typical_noise_at_a_20ms_tick(ffr_mission, room: int, candle, seed: int) -> None:
    scn = make_scenario(candle=candle, seed=seed, noise="typical", timing=Timing(firmware_period_ms=M0_TICK_MS))
    assert scn.room == room
    res, _ = ffr_mission(scn, record=False)
    assert res.outcome == "home" and res.wall_contacts == 0, res.detail
