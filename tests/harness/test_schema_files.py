"""The schema layer against what we ship: every TOML data file, scenario, test fixture and docs example
still loads; each schema table's defaults are the model's defaults (the loaders build the model from
the checked tables, so a drifted default would change a mission); and the files that are not
UTF-8, unreadable or not TOML end in one line."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import msgspec
import pytest

from harness.scenario import Timing, load_scenario, scenario_from_dict
from harness.scenario_schema import ScenarioFile, TimingTable
from harness.scoring import SCORING_FILE, ScoringRules
from sim_plant import file_schemas as fs
from sim_plant.arena import load_arena
from sim_plant.errors import FfrInputError
from sim_plant.reality import Reality
from sim_plant.robot import (
    DEFAULT_ROBOT,
    IR_NAMES,
    Battery,
    Body,
    Encoder,
    Fans,
    Flame,
    IrPose,
    LineSensor,
    Motor,
    Sides,
    Slip,
    Track,
    load_robot,
    robot_from_dict,
)
from sim_plant.schema import check, read_toml
from sim_plant.sensors.models import FlameWorld, RangerModel
from sim_plant.sensors.noise import (
    DEFAULT_PROFILES,
    AnalogNoise,
    EncoderNoise,
    LineNoise,
    load_noise_profile,
    profiles_from_dict,
)

REPO = Path(__file__).resolve().parents[2]

# schema table -> the model dataclass the loader builds from it
PAIRS = [(fs.BodyTable, Body), (fs.TrackTable, Track), (fs.MotorTable, Motor), (fs.EncoderTable, Encoder),
         (fs.IrPoseTable, IrPose), (fs.LineSensorTable, LineSensor), (fs.FlameTable, Flame), (fs.FansTable, Fans),
         (fs.SlipTable, Slip), (fs.SidesTable, Sides), (fs.BatteryTable, Battery),
         (fs.AnalogNoiseTable, AnalogNoise), (fs.LineNoiseTable, LineNoise), (fs.EncoderNoiseTable, EncoderNoise),
         (fs.RangerTable, RangerModel), (fs.FlameWorldTable, FlameWorld), (fs.RealityTable, Reality),
         (TimingTable, Timing)]


@pytest.mark.parametrize(("table", "model"), PAIRS, ids=[t.__name__ for t, _ in PAIRS])
def test_schema_tables_declare_the_models_fields_and_defaults(table, model) -> None:
    names = [f.name for f in dataclasses.fields(model)]
    assert [f.encode_name for f in msgspec.structs.fields(table)] == names
    for f in msgspec.structs.fields(table):
        mf = next(m for m in dataclasses.fields(model) if m.name == f.name)
        if f.required:
            assert mf.default is dataclasses.MISSING, f.name
        else:
            assert f.default == mf.default, f"{table.__name__}.{f.name}: {f.default!r} != {mf.default!r}"


def test_the_rangers_are_the_robots() -> None:
    assert tuple(f.name for f in msgspec.structs.fields(fs.IrTable)) == IR_NAMES
    assert tuple(f.name for f in msgspec.structs.fields(fs.CalibrationIrTable)) == IR_NAMES


def test_every_shipped_file_loads() -> None:
    for p in sorted((REPO / "sim_plant" / "data").glob("arena_*.toml")) + [
            REPO / "tests" / "scenario" / "data" / "arena_doors_moved.toml"]:
        assert load_arena(p).rooms
    assert load_robot().source == str(DEFAULT_ROBOT)
    assert "typical" in profiles_from_dict(read_toml(DEFAULT_PROFILES), str(DEFAULT_PROFILES))
    assert ScoringRules.load(SCORING_FILE).incomplete_score > 0
    assert load_scenario(REPO / "scenarios" / "example.toml").name
    assert load_noise_profile(REPO / "scenarios" / "realistic_exact_calibration.toml").reality.enabled


def _toml_blocks(doc: str) -> list[str]:
    return re.findall(r"```toml\n(.*?)```", (REPO / "docs" / doc).read_text(encoding="utf-8"), re.S)


def test_the_docs_examples_are_valid() -> None:
    import tomllib

    (drive,) = _toml_blocks("drivetrain.md")
    robot = read_toml(DEFAULT_ROBOT) | tomllib.loads(drive)
    assert robot_from_dict(robot, "docs/drivetrain.md").slip == Slip()
    full, modes = _toml_blocks("scenarios.md")
    # the example shows every way to give the noise: a name and, instead, an inline table
    data = tomllib.loads(re.sub(r"(?m)^noise = .*$", "", full))
    del data["candle"]["room"]  # the example shows both ways to place the candle: one at a time
    check(data, ScenarioFile, "docs/scenarios.md")  # its arena and robot files are examples, not ours
    scenario_from_dict(tomllib.loads(modes), "docs/scenarios.md", REPO)


@pytest.mark.parametrize(("content", "why"), [
    (bytes(range(128, 256)), "not UTF-8"),
    (b"seed = = 1\n", "(syntax)"),
    (b"[candle]\nposition = [0.55, nan]\n", "must be a finite number"),
])
def test_unreadable_files_are_one_line(tmp_path, content, why) -> None:
    p = tmp_path / "s.toml"
    p.write_bytes(content)
    for load in (load_scenario, load_arena, load_robot):
        with pytest.raises(FfrInputError) as e:
            load(p)
        assert why in str(e.value) and "\n" not in str(e.value) and str(p) in str(e.value)
    with pytest.raises(FfrInputError, match="(file)"):
        load_scenario(tmp_path / "missing.toml")
    with pytest.raises(FfrInputError, match="(file)"):
        load_arena(tmp_path)  # a directory
