"""Scenario files: loading and validation."""

from __future__ import annotations

import math

import pytest

from harness.scenario import load_scenario
from sim_plant.errors import FfrInputError


def _scn(tmp_path, text: str):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return p


def test_full_scenario(tmp_path) -> None:
    p = _scn(tmp_path, """
name = "x"
seed = 9
noise = "typical"
[candle]
position = [2.30, 0.80]
[start]
x = 2.15
y = 1.17
heading_deg = 90
[timing]
firmware_period_ms = 20
plant_dt_ms = 5
[firmware]
cruise_speed_mm_s = 250
[robot_overrides]
"motor.R" = 7.0
""")
    s = load_scenario(p)
    assert (s.name, s.seed, s.room, s.candle) == ("x", 9, 4, (2.30, 0.80))
    assert s.start[2] == pytest.approx(math.pi / 2)
    assert s.timing.firmware_period_ms == 20 and s.timing.plant_dt_ms == 5
    assert s.firmware == {"cruise_speed_mm_s": 250}
    assert s.robot.motor.R == 7.0
    assert s.noise.name == "typical"
    assert load_scenario(p, seed=3).seed == 3  # the CLI's --seed wins


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("colour = 1\n", "colour"),
        ("seed = -1\n", "seed"),
        ("[candle]\nroom = 2\nposition = [2.3, 0.8]\n", "candle.position"),
        ("[candle]\nposition = [1.0, 1.0]\n", "candle"),
        ("[candle]\nroom = 12\n", "room"),
        ("[timing]\nfirmware_period_ms = 10\nplant_dt_ms = 3\n", "timing.plant_dt_ms"),
        ("[timing]\nwarp = 2\n", "timing.warp"),
        ("[robot_overrides]\n\"motor.Q\" = 1\n", "robot.motor.Q"),
        ("arena = \"nowhere.toml\"\n", "arena"),
        ("stop_on_contact = \"yes\"\n", "stop_on_contact"),
    ],
)
def test_bad_scenarios(tmp_path, text: str, field: str) -> None:
    p = _scn(tmp_path, text)
    with pytest.raises(FfrInputError) as exc:
        load_scenario(p)
    assert field in str(exc.value) and "\n" not in str(exc.value)
