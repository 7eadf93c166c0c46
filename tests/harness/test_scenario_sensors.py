"""Scenario files: [[ir_source]] objects and the sensor-model groups of an inline noise profile."""

from __future__ import annotations

from pathlib import Path

import pytest

from harness.scenario import IrSource, load_scenario, scenario_to_toml
from sim_plant.errors import FfrInputError

GOOD = """
name = "lamp"
[candle]
room = 1
[noise.ranger]
latency = true
period_spread = 0.0096
[noise.flame_world]
wall_reflectance = 0.3
strength_min = 0.8
strength_max = 1.2
[[ir_source]]
name = "window"
position = [0.05, 2.0]
height = 0.2
strength = 2.0
[[ir_source]]
position = [1.0, 1.0]
strength = 0.5
"""


def test_ir_sources_and_models_load_and_round_trip(tmp_path: Path) -> None:
    p = tmp_path / "s.toml"
    p.write_text(GOOD)
    scn = load_scenario(p)
    assert scn.ir_sources == (IrSource(0.05, 2.0, 0.2, 2.0, "window"),
                              IrSource(1.0, 1.0, scn.arena.flame_height, 0.5, "ir_source"))
    assert scn.ir_source_array().tolist() == [[0.05, 2.0, 0.2, 2.0], [1.0, 1.0, 0.175, 0.5]]
    assert scn.noise.ranger.latency and scn.noise.ranger.period_spread == 0.0096
    assert scn.noise.flame_world.wall_reflectance == 0.3
    q = tmp_path / "back.toml"
    q.write_text(scenario_to_toml(scn))
    back = load_scenario(q)
    assert back.ir_sources == scn.ir_sources and back.noise == scn.noise


@pytest.mark.parametrize("table,field,value", [
    ("positon = [0.05, 2.0]\nstrength = 1.0", "ir_source[0].positon", "did you mean 'position'"),
    ("position = [3.0, 1.0]\nstrength = 1.0", "ir_source[0].position", "inside the arena"),
    ("position = [1.0, 1.0]\nstrength = -1.0", "ir_source[0].strength", "must be in [0, 1000]"),
    ("position = [1.0, 1.0]", "ir_source[0].strength", "missing"),
])
def test_bad_ir_source_is_one_line_naming_the_field(tmp_path: Path, table: str, field: str,
                                                    value: str) -> None:
    p = tmp_path / "bad.toml"
    p.write_text(f"[candle]\nroom = 1\n[[ir_source]]\n{table}\n")
    with pytest.raises(FfrInputError) as e:
        load_scenario(p)
    msg = str(e.value)
    assert str(p) in msg and field in msg and value in msg and "\n" not in msg
