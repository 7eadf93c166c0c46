"""The contest's optional modes as scenario settings: furniture (--furniture N, [[furniture]]) and
arbitrary start (--start hallway, [start] area = "hallway"), each with its score factor; drawn
from their own stream of the seed, saved and replayed exactly."""

from __future__ import annotations

import csv
import json
import math
import shlex

import numpy as np
import pytest

from harness.cli import main
from harness.loop import run_mission
from harness.scenario import load_scenario, make_scenario, scenario_to_toml
from harness.scoring import ScoringRules
from sim_plant.arena import load_arena

ARENA = load_arena()


def _json(capsys, *argv: str) -> dict:
    code = main(["run", *argv, "--json", "-"])
    data = json.loads(capsys.readouterr().out)
    assert code in (0, 1)
    return data


def test_furniture_mode_in_the_result_and_the_score(capsys) -> None:
    d = _json(capsys, "--room", "1", "--furniture", "3")
    assert d["modes"] == ["furniture"] and len(d["furniture"]) == 3
    rules = ScoringRules.load()
    assert rules.mode_factors == {"arbitrary_start": 0.8, "furniture": 0.75}
    if d["outcome"] == "home":  # AT x RF x return trip x furniture + penalties
        rf = rules.room_factor[d["rooms_searched"]]
        want = d["time_to_extinguish_s"] * rf * rules.return_trip_factor * 0.75 + 50.0 * d["wall_contacts"]
        assert d["score"] == pytest.approx(want, abs=0.01)
    plain = _json(capsys, "--room", "1")
    assert plain["modes"] == [] and plain["furniture"] == []


def test_furniture_comes_from_its_own_stream(capsys) -> None:
    a = make_scenario(room=2, seed=5, furniture=2)
    b = make_scenario(room=2, seed=5, furniture=2)
    c = make_scenario(room=2, seed=6, furniture=2)
    assert a.furniture == b.furniture != c.furniture
    assert make_scenario(room=2, seed=5).start == a.start  # the start and the noise do not move
    assert [w.name for w in a.arena.walls[-2:]] == ["furniture_0", "furniture_1"]


@pytest.mark.parametrize("kwargs", [{"furniture": 3, "seed": 4}, {"start": "hallway", "seed": 9},
                                    {"start": "hallway", "furniture": 2, "arena_jitter": 0.02, "seed": 2}])
def test_a_saved_mode_scenario_replays_exactly(tmp_path, kwargs) -> None:
    scn = make_scenario(room=3, **kwargs)
    p = tmp_path / "s.toml"
    p.write_text(scenario_to_toml(scn))
    back = load_scenario(p)
    assert back.furniture == scn.furniture and back.start == scn.start and back.start_area == scn.start_area
    assert back.modes == scn.modes
    r1, t1 = run_mission(scn, record=True)
    r2, t2 = run_mission(back, record=True)
    assert np.array_equal(t1.f, t2.f) and np.array_equal(t1.i, t2.i) and r1.to_json() == r2.to_json()


def test_arbitrary_start_is_anywhere_in_a_hallway_any_heading() -> None:
    poses = [make_scenario(room=1, seed=s, start="hallway") for s in range(120)]
    assert all(ARENA.in_hallway(p.start[0], p.start[1]) and p.modes == ["arbitrary_start"] for p in poses)
    halls = {next(h.name for h in ARENA.hallways if h.polygon.min(axis=0)[0] <= p.start[0] <= h.polygon.max(axis=0)[0]
                  and h.polygon.min(axis=0)[1] <= p.start[1] <= h.polygon.max(axis=0)[1]) for p in poses}
    assert len(halls) == len(ARENA.hallways)  # every hallway gets starts
    quarters = {int(math.degrees(p.start[2]) // 90) for p in poses}
    assert quarters == {0, 1, 2, 3}


def test_a_hallway_pose_in_a_scenario_file(tmp_path) -> None:
    p = tmp_path / "s.toml"
    p.write_text("[start]\narea = 'hallway'\nx = 0.97\ny = 1.0\nheading_deg = 270\n")
    scn = load_scenario(p)
    assert scn.start[:2] == (0.97, 1.0) and scn.modes == ["arbitrary_start"]
    p.write_text("[start]\narea = 'hallway'\nx = 0.4\ny = 0.4\nheading_deg = 0\n")  # room 3
    with pytest.raises(Exception, match="start = .*in no hallway"):
        load_scenario(p)


@pytest.mark.parametrize(("text", "needle"), [
    ("furniture = 99\n", "furniture = 99"),
    ("furniture = 'lots'\n", "furniture = 'lots'"),
    ("[[furniture]]\nx = 1.0\ny = 1.0\nwidth = 0.1\ndepth = 0.1\n", "furniture[0]"),
    ("[[furniture]]\nx = 1.75\ny = 0.4\nwidth = 0.1\ndepth = 0.1\ncolour = 'oak'\n", "furniture[0].colour"),
    ("[start]\narea = 'attic'\nx = 2.11\ny = 1.17\n", "start.area = 'attic'"),
])
def test_bad_mode_settings_are_one_line_and_exit_2(tmp_path, capsys, text, needle) -> None:
    p = tmp_path / "s.toml"
    p.write_text(text)
    assert main(["run", "--scenario", str(p)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err


def test_a_sweep_in_both_modes_records_them_and_its_replays_reproduce(tmp_path, capsys) -> None:
    out = tmp_path / "r.csv"
    code = main(["sweep", "--rooms", "1,4", "--candles", "default", "--seeds", "0:3", "--furniture", "2",
                 "--start", "hallway", "--workers", "1", "--no-progress", "--out", str(out)])
    assert code == 0
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 6 and {r["furniture"] for r in rows} == {"2"}
    for r in rows[:2]:
        argv = shlex.split(r["replay"])
        assert "--furniture" in argv and "hallway" in argv
        capsys.readouterr()
        d = _json(capsys, *argv[2:])
        assert d["outcome"] == r["outcome"] and d["modes"] == ["arbitrary_start", "furniture"]
        assert [round(v, 6) for v in d["start_pose"][:2]] == [round(float(r["start_x"]), 4),
                                                              round(float(r["start_y"]), 4)]


def test_the_firmware_is_told_the_start_area_not_the_pose() -> None:
    """The mode (which a team knows on the day) goes into the contract's start_area config field;
    at home the configuration stays byte for byte the firmware's default."""
    from harness.firmware_config import START_AREA_FIELD, build_config

    robot = make_scenario(room=1).robot
    home = build_config(robot)
    assert int(home[START_AREA_FIELD]) == 0
    assert build_config(robot, start_area="home").tobytes() == home.tobytes()
    hall = build_config(robot, start_area="hallway")
    assert int(hall[START_AREA_FIELD]) == 1
    # only that field differs: no pose, no map
    diff = [n for n in home.dtype.names or () if not np.array_equal(home[n], hall[n])]
    assert diff == [START_AREA_FIELD]


def test_a_hallway_start_reaches_home_with_the_flame_out() -> None:
    """The explorer (firmware/src/explore.c) from a hallway pose, the flame in room 4: found, put out,
    home found by its circle's two lines (a start the route program from home did not finish)."""
    scn = make_scenario(room=4, seed=0, start="hallway")
    res, _ = run_mission(scn, record=False)
    assert res.outcome == "home" and res.wall_contacts == 0
