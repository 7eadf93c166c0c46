"""Scenarios written as TOML read back to the same mission: bit-identical trace, same result."""

from __future__ import annotations

import dataclasses
import json
import math

from harness.cli import main
from harness.events import parse_events
from harness.loop import run_mission
from harness.scenario import load_scenario, make_scenario, scenario_to_toml
from sim_plant.sensors import load_noise_profile


def _odd_scenario():
    typ = load_noise_profile("datasheet")
    noise = dataclasses.replace(typ, name="custom", ir=dataclasses.replace(typ.ir, sigma=7.123456789, bias=-3.5))
    ev = parse_events([{"at_s": 12.5, "sensor": "ir.LR", "fault": "noisy", "sigma": 40.0, "duration_s": 3.0},
                       {"at_s": 5.0, "sensor": "wheel.R", "fault": "slip", "fraction": 0.1, "duration_s": 2.0}],
                      "test")
    scn = make_scenario(candle=(0.1234567891234, 1.2109876543), seed=123456789, noise=noise,
                        firmware={"cruise_speed_mm_s": 300.5, "fan_attempts": 2},
                        robot_overrides={"motor.R": 6.9876543210123, "ir.LF.angle_deg": 44.1},
                        start=(2.1134, 1.1687, math.radians(91.3)), events=ev, name="odd one")
    scn.timing.find_limit_s = 200.0
    return scn


def test_round_trip_is_bit_identical(tmp_path) -> None:
    scn = _odd_scenario()
    p = tmp_path / "odd.toml"
    p.write_text(scenario_to_toml(scn, comment="a test"))
    back = load_scenario(p)
    assert back.candle == scn.candle and back.start == scn.start and back.seed == scn.seed
    assert back.noise.ir == scn.noise.ir and back.noise.flame == scn.noise.flame
    assert back.events == scn.events and back.firmware == scn.firmware and back.robot == scn.robot
    assert back.timing == scn.timing
    r1, t1 = run_mission(scn)
    r2, t2 = run_mission(back)
    assert t1.f.tobytes() == t2.f.tobytes() and t1.i.tobytes() == t2.i.tobytes()
    assert r1.to_json() | {"scenario": ""} == r2.to_json() | {"scenario": ""}


def test_ffr_run_scenario_replays_the_written_file(tmp_path, capsys) -> None:
    scn = _odd_scenario()
    p = tmp_path / "odd.toml"
    p.write_text(scenario_to_toml(scn))
    res, _ = run_mission(scn, record=False)
    code = main(["run", "--scenario", str(p), "--json", "-"])
    assert code == (0 if res.outcome == "home" else 1)
    assert json.loads(capsys.readouterr().out) == res.to_json()
