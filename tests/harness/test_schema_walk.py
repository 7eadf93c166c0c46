"""Every field of every input file kind, walked from the schema declarations (not a hand list):
each gets a value of the wrong type, a value out of its declared range (where one is declared) and
a misspelt name, and each must be refused with one line naming the file, the table path and the
value (a misspelt name also with "did you mean" the field). The bulk goes through the loaders'
``*_from_dict`` functions (fast); a sample of each kind through the real CLI (exit 2, one line on
stderr, nothing written)."""

from __future__ import annotations

import copy
import json
import re
import typing
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import msgspec
import pytest

from harness.cli import main
from harness.scenario import scenario_from_dict
from harness.scenario_schema import ScenarioFile, ScoringFile
from harness.scoring import SCORING_FILE, ScoringRules
from sim_plant.arena import DEFAULT_ARENA, arena_from_dict
from sim_plant.errors import FfrInputError
from sim_plant.file_schemas import ArenaFile, NoiseFile, RobotFile
from sim_plant.robot import DEFAULT_ROBOT, robot_from_dict
from sim_plant.schema import read_toml
from sim_plant.sensors.noise import profiles_from_dict

REPO = Path(__file__).resolve().parents[2]

# -- one complete, valid document per file kind: every table the schema declares is present ------

PROFILE = {
    "description": "every group",
    "ir": {"sigma": 12.0, "bias": 1.0, "quant_step": 4.9, "dropout_prob": 0.01, "dropout_mode": "hold",
           "spike_prob": 0.01, "spike_amp": 300.0, "unit_gain_spread": 0.1, "unit_offset_spread": 50.0,
           "unit_pivot": 400.0},
    "flame": {"sigma": 3.0},
    "line": {"flip_prob": 0.01},
    "encoder": {"slip_prob": 0.01, "slip_fraction": 0.3},
    "ranger": {"beam_half_angle_deg": 2.0, "beam_rays": 5, "latency": True, "period_spread": 0.0096,
               "random_phase": True},
    "flame_world": {"strength_min": 0.8, "strength_max": 1.2, "flicker_amp": 0.1, "flicker_hz": 1.5,
                    "wall_reflectance": 0.2, "afterglow_s": 0.5},
    "reality": {"track_factor": [1.0, 1.3], "turn_radius": [0.05, 0.2], "creep": [0.0, 0.1],
                "floor_mu": [0.5, 0.8], "scrub_mu": [0.0, 0.3], "wall_mu": [0.0, 0.4],
                "internal_resistance": [0.0, 0.5], "fan_current": [0.0, 1.0], "motor_spread": 0.05,
                "side_motor": 0.02, "side_friction": 0.1, "side_wheel_radius": 0.01, "ir_mount_mm": 2.0,
                "ir_mount_deg": 2.0, "cal_wheel_radius": 0.01, "cal_track_width": 0.02},
}


def _robot_doc() -> dict[str, Any]:
    data = read_toml(DEFAULT_ROBOT)
    data.setdefault("slip", {"track_factor": 1.1})
    data.setdefault("sides", {"left_motor": 1.01})
    data.setdefault("battery", {"internal_resistance": 0.2})
    data["calibration"] = {"wheel_radius": 0.028, "track_width": 0.16, "ticks_per_rev": 360,
                           "ir": {"LF": {"x": 0.06, "y": 0.05, "angle_deg": 45.0}}}
    return data


SCENARIO = {
    "name": "walk", "seed": 3, "noise": PROFILE, "arena_jitter": 0.0, "stop_on_contact": False,
    "candle": {"position": [0.55, 1.20]},
    "start": {"x": 2.11, "y": 1.17, "heading_deg": 90.0, "area": "home"},
    "timing": {"firmware_period_ms": 10, "plant_dt_ms": 1.0, "find_limit_s": 300.0, "return_limit_s": 120.0,
               "start_delay_ms": 0},
    "firmware": {"cruise_speed_mm_s": 250}, "robot_overrides": {"motor.R": 6.5},
    "events": [{"at_s": 3.0, "sensor": "ir.RF", "fault": "dead", "duration_s": 2.0, "value": 0}],
    "furniture": [{"x": 1.76, "y": 1.85, "width": 0.15, "depth": 0.15, "heading_deg": 90.0}],
    "ir_source": [{"name": "lamp", "position": [1.0, 1.0], "height": 0.2, "strength": 0.5}],
}


def _load_scenario(data: dict[str, Any], src: str) -> object:
    return scenario_from_dict(data, src, REPO)


# kind -> (schema, its file name, a valid document, the loader from a dict)
KINDS: dict[str, tuple[Any, str, Callable[[], dict[str, Any]], Callable[[dict[str, Any], str], object]]] = {
    "arena": (ArenaFile, "arena.toml", lambda: read_toml(DEFAULT_ARENA), arena_from_dict),
    "robot": (RobotFile, "robot.toml", _robot_doc, robot_from_dict),
    "noise": (NoiseFile, "noise.toml", lambda: {"p": copy.deepcopy(PROFILE)}, profiles_from_dict),
    "scenario": (ScenarioFile, "scenario.toml", lambda: copy.deepcopy(SCENARIO), _load_scenario),
    "scoring": (ScoringFile, "scoring.toml", lambda: read_toml(SCORING_FILE), ScoringRules.from_dict),
}


# -- walking the declarations ------------------------------------------------------------------------

def _unwrap(tp: Any) -> tuple[Any, list[Any]]:
    metas: list[Any] = []
    while typing.get_origin(tp) is typing.Annotated:
        tp, *extra = typing.get_args(tp)
        metas += extra
    return tp, metas


def _members(tp: Any) -> list[Any]:
    """The types a union (also one inside Annotated) is made of, None left out."""
    bare, _ = _unwrap(tp)
    if typing.get_origin(bare) in (typing.Union, type(int | str)):
        return [m for a in typing.get_args(bare) if a is not type(None) for m in _members(a)]
    return [tp]


def _is_struct(tp: Any) -> bool:
    return isinstance(tp, type) and issubclass(tp, msgspec.Struct)


def _structs(tp: Any, seen: set[type]) -> set[type]:
    """Every struct type reachable from a declaration."""
    for m in _members(tp):
        bare, _ = _unwrap(m)
        if _is_struct(bare):
            if bare not in seen:
                seen.add(bare)
                for f in msgspec.structs.fields(bare):
                    _structs(f.type, seen)
        else:
            for a in typing.get_args(bare):
                _structs(a, seen)
    return seen


Path_ = list[str | int]


def _fields(tp: Any, value: Any, path: Path_, visited: set[type]) -> Iterator[tuple[Path_, Any]]:
    """(path, declared type) of every field of every table present in ``value``."""
    for m in _members(tp):
        bare, _ = _unwrap(m)
        origin = typing.get_origin(bare)
        if _is_struct(bare) and isinstance(value, dict):
            visited.add(bare)
            for f in msgspec.structs.fields(bare):
                yield [*path, f.encode_name], f.type
                if f.encode_name in value:
                    yield from _fields(f.type, value[f.encode_name], [*path, f.encode_name], visited)
            return
        if origin is list and isinstance(value, list) and value and isinstance(value[0], dict):
            yield from _fields(typing.get_args(bare)[0], value[0], [*path, 0], visited)
            return
        if origin is dict and isinstance(value, dict) and value:
            key = next(iter(value))
            yield from _fields(typing.get_args(bare)[1], value[key], [*path, key], visited)
            return


def _accepts(tp: Any, value: Any) -> bool:
    try:
        msgspec.convert(value, tp, strict=True)
    except msgspec.ValidationError:
        return False
    return True


def _wrong_type(tp: Any) -> Any:
    return next(v for v in ("wrong", 1.5, True, [1], {"q": 1}) if not _accepts(tp, v))


def _bounds(tp: Any) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for m in _members(tp)[:1]:
        bare, metas = _unwrap(m)
        for meta in metas:
            for k in ("ge", "gt", "le", "lt", "min_length"):
                if getattr(meta, k, None) is not None:
                    out[k] = getattr(meta, k)
        out["int"] = bare is int
    return out


def _out_of_range(tp: Any, current: Any) -> Any | None:
    """A value of the right type outside the declared range, or None if none is declared."""
    b = _bounds(tp)
    bare = _unwrap(_members(tp)[0])[0]
    if typing.get_origin(bare) is tuple:  # a [lo, hi] range: its ends are bounded
        end = typing.get_args(bare)[0]
        bad = _out_of_range(end, None)
        ok = current[1] if isinstance(current, list) else 0.0
        return None if bad is None else [bad, ok]
    if "min_length" in b:
        return list(current or [])[: b["min_length"] - 1]
    step = 1 if b["int"] else 0.5
    if "ge" in b:
        return b["ge"] - step
    if "gt" in b:
        return b["gt"] if b["int"] else float(b["gt"])
    if "le" in b:
        return b["le"] + step
    if "lt" in b:
        return b["lt"] if b["int"] else float(b["lt"])
    return None


def _fmt(path: Path_) -> str:
    s = ""
    for p in path:
        s += f"[{p}]" if isinstance(p, int) else (f".{p}" if s else str(p))
    return s


def _set(doc: Any, path: Path_, value: Any) -> None:
    for p in path[:-1]:
        doc = doc[p]
    doc[path[-1]] = value


def _get(doc: Any, path: Path_) -> Any:
    for p in path:
        try:
            doc = doc[p]
        except (KeyError, IndexError):
            return None
    return doc


def _misspelt(name: str) -> str:
    return name + "_"  # a stray key: position_ (difflib: nearest to position, LR_ to LR, not RR)


def _cases() -> list[tuple[str, str, dict[str, Any], str, str | None]]:
    """(kind, case id, document, expected path, expected "did you mean" or None)."""
    out = []
    for kind, (schema, _fname, make, _load) in KINDS.items():
        doc = make()
        visited: set[type] = set()
        for path, tp in _fields(schema, doc, [], visited):
            where = _fmt(path)
            bad = copy.deepcopy(doc)
            _set(bad, path, _wrong_type(tp))
            out.append((kind, f"{kind}:{where}:type", bad, where, None))
            rng = _out_of_range(tp, _get(doc, path))
            if rng is not None:
                bad = copy.deepcopy(doc)
                _set(bad, path, rng)
                out.append((kind, f"{kind}:{where}:range", bad, where, None))
            bad = copy.deepcopy(doc)
            parent = _get(bad, path[:-1])
            name = str(path[-1])
            parent[_misspelt(name)] = parent.pop(name) if name in parent else 1
            out.append((kind, f"{kind}:{where}:name", bad, _fmt([*path[:-1], _misspelt(name)]), name))
        missing = _structs(schema, set()) - visited
        assert not missing, f"{kind}: the walk's document lacks tables of {sorted(t.__name__ for t in missing)}"
    return out


CASES = _cases()


def test_every_kind_is_walked_and_each_valid_document_loads() -> None:
    for kind, (_schema, fname, make, load) in KINDS.items():
        load(make(), fname)  # the unmutated document is valid: each case's error is its own mutation
        assert sum(1 for c in CASES if c[0] == kind) >= 9, kind
    assert len(CASES) > 300


@pytest.mark.parametrize(("kind", "case", "doc", "where", "meant"), CASES, ids=[c[1] for c in CASES])
def test_each_field_refuses_wrong_values_with_one_line(kind, case, doc, where, meant) -> None:
    schema, fname, _make, load = KINDS[kind]
    with pytest.raises(FfrInputError) as e:
        load(doc, fname)
    msg = str(e.value)
    assert "\n" not in msg
    value = _get(doc, _path_of(where))
    assert msg.startswith(f"{fname}: {where} = {value!r}: "), msg
    if meant is not None:
        assert f"did you mean {meant!r}?" in msg, msg


def _path_of(where: str) -> Path_:
    out: Path_ = []
    for name, idx in re.findall(r"([^.\[\]]+)|\[(\d+)\]", where):
        out.append(int(idx) if idx else name)
    return out


def _toml(v: Any) -> str:
    """Our documents as TOML: one line per top-level key, tables inline."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    return "{" + ", ".join(f"{json.dumps(k)} = {_toml(x)}" for k, x in v.items()) + "}"


# a sample through the command line: every 15th case of each kind
SAMPLE = [c for kind in KINDS for c in [c for c in CASES if c[0] == kind][::15]]
OPTION = {"arena": ["run", "--arena"], "robot": ["run", "--robot"], "scenario": ["run", "--scenario"]}


CLI_CASES = [c for c in SAMPLE if c[0] in OPTION or c[0] == "noise"]


@pytest.mark.parametrize(("kind", "case", "doc", "where", "meant"), CLI_CASES, ids=[c[1] for c in CLI_CASES])
def test_a_sample_through_the_cli(tmp_path, capsys, kind, case, doc, where, meant) -> None:
    fname = KINDS[kind][1]
    path = tmp_path / fname
    path.write_text("".join(f"{json.dumps(k)} = {_toml(v)}\n" for k, v in doc.items()))
    argv = ["run", "--noise", f"{path}#p"] if kind == "noise" else [*OPTION[kind], str(path)]
    before = {p.name for p in tmp_path.iterdir()}
    code = main([*argv, "--json", str(tmp_path / "out.json")])
    out, err = capsys.readouterr()
    assert code == 2, err
    assert err.count("\n") == 1 and err.startswith("ffr: error: ") and out == "", err
    value = _get(doc, _path_of(where))
    assert f"{fname}: {where} = {value!r}: " in err, err
    assert {p.name for p in tmp_path.iterdir()} == before
