"""The four rooms with issue 12's sensor models (docs/sensors.md): the default (2-degree beam,
the candle's base) and every sensor model of the ``realistic`` profile, over several drawn
flames and ranger timings: home, no wall contact, the candle standing."""

from __future__ import annotations

import dataclasses

import pytest

from harness.loop import run_mission
from harness.scenario import make_scenario
from sim_plant.sensors import NoiseProfile, load_noise_profile


def _realistic_sensors() -> NoiseProfile:
    real = load_noise_profile("realistic")
    return NoiseProfile(name="realistic-sensors", ranger=real.ranger, flame_world=real.flame_world)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("room", [1, 2, 3, 4])
def test_realistic_sensor_models_go_home(room: int, seed: int) -> None:
    scn = make_scenario(room=room, seed=seed, noise=_realistic_sensors())
    assert scn.arena.candle_base_radius > 0.0
    res, _ = run_mission(scn, record=False)
    assert (res.outcome, res.wall_contacts, res.candle_knocked) == ("home", 0, False), res.detail


def test_the_realistic_draws_differ_by_seed() -> None:
    a, _ = run_mission(make_scenario(room=1, seed=0, noise=_realistic_sensors()), record=False)
    b, _ = run_mission(make_scenario(room=1, seed=1, noise=_realistic_sensors()), record=False)
    assert a.total_time_s != b.total_time_s
    default = dataclasses.replace(make_scenario(room=1, seed=0), noise=NoiseProfile())
    c, _ = run_mission(default, record=False)
    assert c.total_time_s != a.total_time_s
