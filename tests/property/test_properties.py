"""Property tests over whole missions (hypothesis): within the documented envelope of sensor noise,
part-to-part spread, start pose and robot spread, every legal candle is put out and the robot comes home
without touching a wall, within the contest's limits. A failing example shrinks and is written as a
scenario TOML that `ffr run --scenario` replays to the same result.

Budgets: `--ffr-profile quick` (default, `make test`) or `thorough` (`make test-thorough`).
"""

from __future__ import annotations

import json
import math

import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from harness import pytest_plugin
from harness.cli import main
from harness.events import Event
from harness.loop import run_mission
from harness.properties import (
    ENVELOPE,
    SPREAD_PARAMS,
    candles,
    check_mission,
    noise_profiles,
    realistic_scenarios,
    robot_spreads,
    scenarios,
    start_poses,
    violations,
)
from harness.scenario import load_scenario, make_scenario, scenario_to_toml
from sim_plant.arena import load_arena

PROFILE = pytest_plugin.PROFILES[pytest_plugin.active_profile]
SLOW_OK = [HealthCheck.too_slow, HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much]
ARENA = load_arena()


@settings(max_examples=200, deadline=None, derandomize=True)
@given(c=candles(ARENA), pose=start_poses(ARENA), spread=robot_spreads(), noise=noise_profiles())
def test_strategies_stay_in_their_bounds(c, pose, spread, noise) -> None:
    ARENA.check_candle(*c)  # legal by the arena's rules
    hx, hy = ARENA.home_center
    assert math.hypot(pose[0] - hx, pose[1] - hy) <= ENVELOPE.start_offset_m + 1e-12 <= ARENA.home_radius
    assert abs(math.degrees(pose[2]) - 90.0) <= ENVELOPE.start_heading_deg + 1e-9
    for k, v in spread.items():
        assert abs(v / SPREAD_PARAMS[k] - 1.0) <= ENVELOPE.robot_spread + 1e-12
    assert 0 <= noise.ir.sigma <= ENVELOPE.ir_sigma_mv and noise.ir.unit_offset_spread <= ENVELOPE.ir_unit_offset_mv
    assert noise.encoder.slip_prob <= ENVELOPE.slip_prob and noise.flame.sigma <= ENVELOPE.flame_sigma


@pytest.mark.property
@settings(**PROFILE, deadline=None, suppress_health_check=SLOW_OK)
@given(scn=scenarios())
def test_within_the_envelope_every_mission_succeeds(ffr_mission, pytestconfig, scn) -> None:
    check_mission(ffr_mission, scn, pytestconfig.getoption("--ffr-failures"),
                  "test_within_the_envelope_every_mission_succeeds")


@pytest.mark.property
def test_the_real_parts_success_rate(pytestconfig) -> None:
    """The bundled `datasheet` profile: every GP2D12 and flame sensor with its own calibration drawn
    uniformly within the datasheet's limits, plus typical noise: the real parts. docs/robustness.md
    has the measurements (99.9 % of 2,000 missions over 50 robots and more). Asserted: at least 99 %
    of 1,000 missions over 50 robots (thorough), at most one failure in 80 over 4 robots (quick),
    and every failure replayable."""
    from harness import sweep as sw

    thorough = pytest_plugin.active_profile == "thorough"
    spec = sw.SweepSpec(candles="random", n_candles=5, seeds=tuple(range(50 if thorough else 4)),
                        noise="datasheet", sweep_seed=11)
    jobs = sw.build_jobs(spec)
    rows = sw.execute(jobs) if thorough else sw.run_local_serial(jobs)
    ok = sum(1 for r in rows if r["success"])
    failures = [r["replay"] for r in rows if not r["success"]]
    if thorough:
        assert 100.0 * ok / len(rows) >= 99.0, f"{ok}/{len(rows)} succeeded; first failure: {failures[:1]}"
    else:
        assert len(rows) - ok <= 1, f"{ok}/{len(rows)} succeeded; failures: {failures}"
    assert all(f.startswith("ffr run --candle ") and "--noise datasheet" in f for f in failures)


def test_a_failing_example_shrinks_and_replays_from_its_toml(tmp_path, capsys) -> None:
    """A property that does fail (the left track slips from the start; enough slip loses the robot):
    hypothesis shrinks it, the minimal scenario is written as TOML, and `ffr run --scenario` on that
    file gives the very result of the failing run."""
    runs = []

    def run(scn, record=False):
        res = run_mission(scn, record=record)
        runs.append((scn, res[0]))
        return res

    @settings(max_examples=25, deadline=None, derandomize=True, database=None,
              phases=[Phase.generate, Phase.shrink], suppress_health_check=SLOW_OK)
    @given(fraction=st.floats(0.0, 0.6), at_s=st.floats(0.0, 20.0))
    def slipping(fraction, at_s):
        ev = [Event(at_s, "wheel.L", "slip", fraction=fraction)] if fraction > 0 else []
        check_mission(run, make_scenario(room=2, events=ev), tmp_path, "slipping")

    with pytest.raises(AssertionError) as exc:
        slipping()
    msg = str(exc.value)
    assert "-> replay: ffr run --scenario" in msg
    path = tmp_path / "slipping.toml"
    last_scn, last_res = runs[-1]  # hypothesis ends on the minimal failing example
    assert violations(last_res)
    scn = load_scenario(path)
    assert scn.events == last_scn.events and scn.events[0].fraction > 0
    # shrunk: hypothesis went on after the first failure and ended on a simpler example (an earlier
    # start, a shorter number: hypothesis prefers 0.5 to 0.26415980421647567)
    first = next(i for i, (_, r) in enumerate(runs) if violations(r))
    assert len(runs) > first + 1
    ev0, ev = runs[first][0].events[0], scn.events[0]
    assert ev.at_s <= ev0.at_s and len(repr(ev.fraction)) <= len(repr(ev0.fraction))
    assert (ev.at_s, ev.fraction) != (ev0.at_s, ev0.fraction)
    capsys.readouterr()
    code = main(["run", "--scenario", str(path), "--json", "-"])
    replay = json.loads(capsys.readouterr().out)
    assert code == 1
    want = last_res.to_json()
    assert replay | {"scenario": ""} == want | {"scenario": ""}


@settings(max_examples=6, deadline=None, derandomize=True, suppress_health_check=SLOW_OK)
@given(scn=realistic_scenarios(rooms=(1, 2)))
def test_a_realistic_mission_replays_bit_for_bit_from_its_toml(tmp_path_factory, scn) -> None:
    """Under `realistic` the drawn robot (truth and calibration) comes from the seed alone: the
    scenario file a failing property writes replays the same mission. (Success under `realistic` is
    measured in docs/robustness.md; the firmware work of issue 12 part 4 is what is to raise it.)"""
    res, tr = run_mission(scn)
    path = tmp_path_factory.mktemp("realistic") / "scn.toml"
    path.write_text(scenario_to_toml(scn), encoding="utf-8")
    again = load_scenario(path)
    assert again.noise.reality == scn.noise.reality and again.seed == scn.seed
    res2, tr2 = run_mission(again)
    assert res2.outcome == res.outcome and res2.total_time_s == res.total_time_s
    assert (tr2.f == tr.f).all() and (tr2.i == tr.i).all()
