"""Truth apart from belief: the firmware is configured from the team's calibration, never from the
plant's truth (sim_plant/reality.py, harness/firmware_config.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from harness.firmware_config import build_config
from harness.loop import Mission
from harness.scenario import make_scenario, scenario_to_toml
from sim_plant.errors import FfrInputError
from sim_plant.reality import N_DRAWS, Reality, reality_from_table
from sim_plant.robot import IR_NAMES, load_robot, override
from sim_plant.sensors import load_noise_profile
from sim_plant.sensors.noise import profile_from_table, profile_to_table

ROBOT = load_robot()
REAL = load_noise_profile("realistic").reality


def _geometry(cfg):
    return (float(cfg["wheel_radius_mm"]), float(cfg["track_width_mm"]),
            [float(v) for v in cfg["ir_x_mm"]], [float(v) for v in cfg["ir_angle_deg"]])


def test_default_calibration_is_exact():
    cfg = build_config(ROBOT)
    f32 = np.float32
    assert cfg["wheel_radius_mm"] == f32(ROBOT.track.wheel_radius * 1000)
    assert cfg["track_width_mm"] == f32(ROBOT.track.track_width * 1000)
    assert cfg["encoder_ticks_per_rev"] == f32(ROBOT.encoder.ticks_per_rev)
    assert list(cfg["ir_angle_deg"]) == [f32(ROBOT.ir[n].angle_deg) for n in IR_NAMES]


def test_a_calibration_section_sets_the_config_and_not_the_plant():
    robot = override(override(ROBOT, "calibration.track_width", 0.2), "calibration.wheel_radius", 0.03)
    cfg = build_config(robot)
    assert cfg["track_width_mm"] == np.float32(200.0) and cfg["wheel_radius_mm"] == np.float32(30.0)
    assert robot.track.track_width == ROBOT.track.track_width  # the plant's truth is unchanged
    ticks = override(ROBOT, "calibration.ticks_per_rev", 720)
    assert build_config(ticks)["encoder_ticks_per_rev"] == 720 and ticks.encoder.ticks_per_rev == 360
    with pytest.raises(FfrInputError, match="calibration.ticks_per_rev"):
        override(ROBOT, "calibration.ticks_per_rev", 2.5)


@pytest.mark.parametrize("seed", range(0, 400, 7))
def test_realistic_draws_truth_and_calibration_apart_within_their_ranges(seed):
    truth = REAL.draw(ROBOT, np.random.default_rng(seed))
    sl, cal = truth.slip, truth.calibration
    assert 1.2 <= sl.track_factor <= 2.0 and 0.05 <= sl.turn_radius <= 0.30
    assert 0.2 <= sl.wall_mu <= 0.5 and 0.1 <= truth.battery.internal_resistance <= 0.5
    for v in (truth.sides.left_motor, truth.sides.right_motor):
        assert abs(v - 1) <= 0.03
    rolling = ROBOT.track.wheel_radius * 0.5 * (truth.sides.left_wheel_radius + truth.sides.right_wheel_radius)
    spun = sl.track_factor * ROBOT.track.track_width
    assert abs(cal.wheel_radius / rolling - 1) <= 0.03 + 1e-12
    assert abs(cal.track_width / spun - 1) <= 0.05 + 1e-12
    cfg = build_config(truth)
    wr, tw, irx, ira = _geometry(cfg)
    # the config is the calibration ...
    assert wr == pytest.approx(cal.wheel_radius * 1000, rel=1e-6)
    assert tw == pytest.approx(cal.track_width * 1000, rel=1e-6)
    assert ira == pytest.approx([ROBOT.ir[n].angle_deg for n in IR_NAMES], abs=1e-5)
    # ... and never the plant's truth: geometric or effective track width, true radii, true mounts
    assert not math.isclose(tw, truth.track.track_width * 1000, rel_tol=1e-4)
    assert not math.isclose(tw, spun * 1000, rel_tol=1e-9)
    assert not math.isclose(wr, rolling * 1000, rel_tol=1e-9)
    assert all(not math.isclose(a, truth.ir[n].angle_deg, rel_tol=0, abs_tol=1e-9)
               for a, n in zip(ira, IR_NAMES, strict=True))


def test_a_mission_under_realistic_runs_the_truth_and_configures_the_calibration():
    scn = make_scenario(room=1, noise="realistic", seed=21)
    m = Mission.create(scn)
    try:
        m.run(record=False)
    finally:
        m.link.close()
    truth, cfg = m.truth, m.config
    assert truth is not None and cfg is not None and truth != scn.robot
    expect = REAL.draw(scn.robot, np.random.default_rng(21))  # the seed's first draws
    assert truth == expect
    assert cfg["track_width_mm"] == np.float32(truth.calibration.track_width * 1000)
    assert cfg["track_width_mm"] != np.float32(truth.track.track_width * 1000)
    assert cfg["wheel_radius_mm"] == np.float32(truth.calibration.wheel_radius * 1000)


def test_nominal_missions_draw_nothing():
    scn = make_scenario(room=1)
    m = Mission.create(scn)
    try:
        m.run(record=False)
    finally:
        m.link.close()
    assert m.truth is scn.robot and not scn.noise.reality.enabled


def test_the_draw_takes_a_fixed_number_of_uniforms():
    a, b = np.random.default_rng(5), np.random.default_rng(5)
    REAL.draw(ROBOT, a)
    b.random(N_DRAWS)
    assert a.random() == b.random()


def test_reality_group_round_trips_and_rejects_bad_input(tmp_path):
    table = profile_to_table(load_noise_profile("realistic"))
    assert profile_from_table(table, "t").reality == REAL
    scn = make_scenario(room=2, noise="realistic", seed=3)
    assert "[noise.reality]" in scenario_to_toml(scn)
    for bad, field in (({"track_factor": [2.0, 1.5]}, "track_factor"), ({"creep": 0.1}, "creep"),
                       ({"cal_track_width": -0.1}, "cal_track_width"), ({"chi": [1, 2]}, "chi")):
        with pytest.raises(FfrInputError, match=f"reality.{field}"):
            reality_from_table("f.toml", "p.reality", bad)
    assert not Reality().enabled and REAL.enabled


def test_the_reality_command_prints_each_seeds_draw(capsys):
    from sim_plant.reality_report import main
    assert main(["0:3"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 3 and lines[1].startswith("seed     1  chi0 ")
    truth = REAL.draw(ROBOT, np.random.default_rng(1))
    assert f"chi0 {truth.slip.track_factor:.3f}" in lines[1]
    for bad in (["none", "1"], ["x:y"], ["nosuch", "1"], []):
        assert main(bad) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1


def test_the_exact_calibration_profile_is_realistic_without_calibration_error():
    from pathlib import Path
    path = Path(__file__).resolve().parents[2] / "scenarios" / "realistic_exact_calibration.toml"
    exact = load_noise_profile(str(path))
    real = load_noise_profile("realistic")
    assert exact.reality.cal_wheel_radius == exact.reality.cal_track_width == 0.0
    assert exact.ir == real.ir and exact.flame == real.flame
    for seed in (0, 7, 46):
        a = exact.reality.draw(ROBOT, np.random.default_rng(seed))
        b = real.reality.draw(ROBOT, np.random.default_rng(seed))
        assert a.slip == b.slip and a.sides == b.sides and a.battery == b.battery  # the same truth
        spun = a.slip.track_factor * ROBOT.track.track_width
        assert a.calibration.track_width == pytest.approx(spun, rel=1e-15)
        assert a.calibration.track_width != b.calibration.track_width


def test_the_sides_alike_profile_is_the_exact_one_with_identical_sides():
    from pathlib import Path

    from sim_plant.robot import Sides
    scen = Path(__file__).resolve().parents[2] / "scenarios"
    alike = load_noise_profile(str(scen / "realistic_exact_sides_alike.toml"))
    exact = load_noise_profile(str(scen / "realistic_exact_calibration.toml"))
    assert alike.ir == exact.ir and alike.flame == exact.flame
    assert alike.reality.side_motor == alike.reality.side_friction == alike.reality.side_wheel_radius == 0.0
    for seed in (0, 7, 46):
        a = alike.reality.draw(ROBOT, np.random.default_rng(seed))
        b = exact.reality.draw(ROBOT, np.random.default_rng(seed))
        assert a.sides == Sides() and b.sides != Sides()  # both sides alike; the exact profile's differ
        assert a.slip == b.slip and a.battery == b.battery  # the rest of the floor the same draw
        assert a.calibration.track_width == pytest.approx(a.slip.track_factor * ROBOT.track.track_width, rel=1e-15)
