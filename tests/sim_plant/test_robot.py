"""Robot parameter file: defaults, validation, overrides."""

from __future__ import annotations

import pytest

from sim_plant.errors import FfrInputError
from sim_plant.robot import DEFAULT_ROBOT, IR_NAMES, load_robot, override


def test_defaults_within_contest_limits() -> None:
    r = load_robot()
    assert r.body.length_front + r.body.length_rear <= 0.31
    assert r.body.width <= 0.31
    assert set(r.ir) == set(IR_NAMES)
    assert pytest.approx(6.69) == r.motor.R  # the LEGO NXT set (sim_plant/data/robot_default.toml)


def test_override_by_dotted_path_copies() -> None:
    r = load_robot()
    r2 = override(r, "ir.LF.angle_deg", 40)
    assert r2.ir["LF"].angle_deg == 40.0
    assert r.ir["LF"].angle_deg == 45.0
    assert override(r, "encoder.ticks_per_rev", 720).encoder.ticks_per_rev == 720


@pytest.mark.parametrize(
    ("path", "value", "why"),
    [
        ("motor.nope", 1.0, "no such robot parameter"),
        ("body.width", 0.4, "wider than the contest"),
        ("motor.R", "x", "must be a number"),
        ("encoder.ticks_per_rev", 1.5, "must be an integer"),
    ],
)
def test_bad_overrides(path: str, value, why: str) -> None:
    with pytest.raises(FfrInputError, match=why):
        override(load_robot(), path, value, "scn.toml")


def test_bad_robot_file(tmp_path) -> None:
    p = tmp_path / "robot.toml"
    p.write_text(DEFAULT_ROBOT.read_text().replace("R = 6.69", "R = -1.0"))
    with pytest.raises(FfrInputError) as exc:
        load_robot(p)
    assert "motor.R" in str(exc.value) and "-1.0" in str(exc.value) and str(p) in str(exc.value)
    p.write_text(DEFAULT_ROBOT.read_text().replace("[fans]", "[fans]\nturbo = 1"))
    with pytest.raises(FfrInputError, match="fans.turbo"):
        load_robot(p)
