"""--start X,Y,DEG | random and --arena-jitter: drawn from the seed, checked, saved and replayed exactly."""

from __future__ import annotations

import csv
import json
import math
import os
import shlex
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings

from harness import sweep as sw
from harness.cli import main
from harness.loop import run_mission
from harness.properties import any_start_poses
from harness.scenario import default_start, load_scenario, make_scenario, scenario_to_toml
from harness.start_pose import JITTER_STREAM, START_STREAM, draw_start, start_problem, stream
from sim_plant.arena import DEFAULT_ARENA, load_arena
from sim_plant.errors import FfrInputError
from sim_plant.robot import load_robot

ARENA = load_arena()
ARENA_2001 = load_arena(Path(DEFAULT_ARENA).parent / "arena_2001.toml")
ROBOT = load_robot()


def test_streams_are_apart_from_the_noise_stream() -> None:
    noise = np.random.default_rng(7).uniform(size=4)
    assert not np.array_equal(stream(7, START_STREAM).uniform(size=4), noise)
    assert not np.array_equal(stream(7, JITTER_STREAM).uniform(size=4), noise)
    assert not np.array_equal(stream(7, START_STREAM).uniform(size=4), stream(7, JITTER_STREAM).uniform(size=4))
    assert np.array_equal(stream(7, START_STREAM).uniform(size=4), stream(7, START_STREAM).uniform(size=4))


@pytest.mark.parametrize("arena", [ARENA, ARENA_2001], ids=["2004", "2001"])
def test_random_starts_cover_the_home_circle_and_every_heading(arena) -> None:
    """Seeded sweep of 1,500 draws: every pose allowed; centres uniform over the disc's area (a quarter of
    them within half the radius, as for a uniform disc, up to the footprint's cut near a wall); headings in
    every 30-degree sector."""
    poses = np.array([draw_start(arena, ROBOT, stream(s, START_STREAM)) for s in range(1500)])
    assert all(start_problem(arena, ROBOT, tuple(p)) is None for p in poses)
    r = np.hypot(poses[:, 0] - arena.home_center[0], poses[:, 1] - arena.home_center[1])
    assert r.max() <= arena.home_radius
    inner = np.mean(r <= arena.home_radius / 2)
    assert 0.2 < inner < 0.35
    sectors = np.bincount((np.degrees(poses[:, 2]) // 30).astype(int), minlength=12)
    assert len(sectors) == 12 and sectors.min() > 1500 / 12 * 0.6
    assert ((poses[:, 2] >= 0) & (poses[:, 2] < 2 * math.pi)).all()


@settings(max_examples=200, deadline=None, derandomize=bool(os.environ.get("CI")))
@given(pose=any_start_poses(ARENA_2001))
def test_any_start_poses_strategy_draws_allowed_poses(pose: tuple[float, float, float]) -> None:
    assert start_problem(ARENA_2001, ROBOT, pose) is None and 0.0 <= pose[2] < 2 * math.pi
    make_scenario(arena=ARENA_2001, room=1, start=pose)  # accepted as an explicit start


def test_explicit_start_checked() -> None:
    hx, hy = ARENA.home_center
    make_scenario(start=(hx + 0.05, hy, math.radians(200)))  # in the circle, clear of the walls
    with pytest.raises(FfrInputError, match="home circle"):
        make_scenario(start=(hx + 0.16, hy, 0.0))
    with pytest.raises(FfrInputError, match="touches wall 'br_top'"):
        make_scenario(start=(hx, hy - 0.14, 0.0))  # its footprint reaches into the wall below


def test_default_start_unchanged_and_follows_the_arena_file() -> None:
    assert default_start(ARENA) == (2.11, 1.17, math.pi / 2)
    assert make_scenario(room=1).start == (2.11, 1.17, math.pi / 2)
    assert default_start(ARENA_2001)[2] == math.pi  # the 2001 plan's home faces 180 degrees


def test_random_start_leaves_the_noise_stream_alone() -> None:
    """The same mission with ``start="random"`` and with the pose it drew given explicitly: bit-identical
    (the drawn start did not take numbers from the noise stream)."""
    a = make_scenario(room=4, seed=11, noise="typical", start="random")
    assert a.start_random and start_problem(ARENA, ROBOT, a.start) is None
    b = make_scenario(room=4, seed=11, noise="typical", start=a.start)
    ra, ta = run_mission(a, record=True)
    rb, tb = run_mission(b, record=True)
    assert ra.to_json() == rb.to_json()
    assert np.array_equal(ta.f, tb.f) and np.array_equal(ta.i, tb.i)  # the sensors saw the same noise


def test_jitter_is_drawn_from_the_seed_and_carries_the_candle() -> None:
    a = make_scenario(candle=(0.60, 0.75), seed=3, arena_jitter=0.025)
    b = make_scenario(candle=(0.60, 0.75), seed=3, arena_jitter=0.025)
    c = make_scenario(candle=(0.60, 0.75), seed=4, arena_jitter=0.025)
    assert a.arena.jitter == 0.025 and a.requested_candle() == (0.60, 0.75)
    assert np.array_equal(a.arena.wall_polys, b.arena.wall_polys) and a.candle == b.candle
    assert not np.array_equal(a.arena.wall_polys, c.arena.wall_polys)
    assert math.dist(a.candle, (0.60, 0.75)) <= 0.025 * math.sqrt(2)
    assert a.arena.check_candle(*a.candle).id == 3
    assert a.start == default_start(a.arena)  # the home circle's centre of the jittered arena


def test_saved_random_jittered_scenario_replays_exactly(tmp_path: Path) -> None:
    scn = make_scenario(room=2, seed=5, noise="datasheet", start="random", arena_jitter=0.05, name="j")
    text = scenario_to_toml(scn)
    assert "arena_jitter = 0.05" in text and "random" not in text.split("[start]")[1]  # the pose it drew
    p = tmp_path / "j.toml"
    p.write_text(text, encoding="utf-8")
    back = load_scenario(p)
    assert back.start == scn.start and back.candle == scn.candle
    assert np.array_equal(back.arena.wall_polys, scn.arena.wall_polys)
    assert run_mission(back)[0].to_json() == run_mission(scn)[0].to_json()


def test_scenario_file_start_random_and_jitter(tmp_path: Path) -> None:
    p = tmp_path / "s.toml"
    p.write_text("seed = 9\narena_jitter = 0.02\n[candle]\nroom = 3\n[start]\nrandom = true\n", encoding="utf-8")
    scn = load_scenario(p)
    ref = make_scenario(room=3, seed=9, start="random", arena_jitter=0.02)
    assert scn.start == ref.start and scn.candle == ref.candle and scn.arena_jitter == 0.02
    assert load_scenario(p, seed=10).start != scn.start  # the CLI's seed draws another


@pytest.mark.parametrize(("text", "needle"), [
    ("[start]\nrandom = true\nx = 2.1\n", "start.x"),
    ("[start]\nrandom = \"yes\"\n", "start.random"),
    ("arena_jitter = 0.2\n", "arena_jitter = 0.2"),
    ("arena_jitter = -0.01\n", "arena_jitter"),
    ("[start]\nx = 0.5\ny = 0.5\n", "home circle"),
])
def test_bad_start_or_jitter_in_a_file_is_one_line_exit_2(tmp_path: Path, capsys, text: str, needle: str) -> None:
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    assert main(["run", "--scenario", str(p)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err and str(p) in err and "Traceback" not in err


@pytest.mark.parametrize(("argv", "needle"), [
    (["run", "--start", "0.5,0.5,0"], "home circle"),
    (["table1", "--start", "2.11,1.03,0"], "touches wall"),
    (["run", "--start", "1,2"], "--start = '1,2'"),
    (["run", "--start", "rand"], "--start = 'rand'"),
    (["run", "--arena-jitter", "0.06"], "--arena-jitter = '0.06'"),
    (["sweep", "--arena-jitter", "nan"], "--arena-jitter = 'nan'"),
    (["sweep", "--start", "9,9,0", "--no-progress"], "home circle"),
])
def test_bad_start_or_jitter_on_the_command_line(capsys, argv: list[str], needle: str) -> None:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err and "Traceback" not in err


def test_run_reports_its_start_and_jitter(capsys) -> None:
    assert main(["run", "--room", "1", "--seed", "2", "--start", "random", "--arena-jitter", "0.025",
                 "--json", "-"]) in (0, 1)
    d = json.loads(capsys.readouterr().out)
    scn = make_scenario(room=1, seed=2, start="random", arena_jitter=0.025)
    assert d["start_pose"] == [round(scn.start[0], 4), round(scn.start[1], 4), round(math.degrees(scn.start[2]), 2)]
    assert d["arena_jitter"] == 0.025 and d["candle"] == [round(scn.candle[0], 4), round(scn.candle[1], 4)]


def test_sweep_rows_record_the_start_and_jitter_and_replay_exactly(tmp_path: Path, capsys) -> None:
    spec = sw.SweepSpec(rooms=(1, 4), candles="random", n_candles=1, seeds=(0, 1), start="random",
                        arena_jitter=0.025)
    rows = sw.run_local_serial(sw.build_jobs(spec))
    assert len(rows) == 4 and {r["jitter_seed"] for r in rows} == {0, 1}
    assert len({(r["start_x"], r["start_y"], r["start_heading_deg"]) for r in rows}) == 2  # one per seed
    for r in rows[:2]:
        assert "--start random" in r["replay"] and "--arena-jitter 0.025" in r["replay"]
        out = tmp_path / f"{r['id']}.json"
        main([*shlex.split(r["replay"])[1:], "--json", str(out)])
        d = json.loads(out.read_text())
        assert d["outcome"] == r["outcome"] and d["path_length_m"] == round(r["path_length_m"], 3)
        assert d["start_pose"][:2] == [round(r["start_x"], 4), round(r["start_y"], 4)]
    capsys.readouterr()
    csv_out = tmp_path / "s.csv"
    code = main(["sweep", "--rooms", "1", "-n", "2", "--seeds", "0:2", "--start", "random", "--arena-jitter",
                 "0.025", "--workers", "1", "--no-progress", "--out", str(csv_out)])
    text = capsys.readouterr().out
    assert code == 0 and "4 missions:" in text
    recs = list(csv.DictReader(csv_out.open()))
    assert {k for k in ("start_x", "start_y", "start_heading_deg", "arena_jitter", "jitter_seed")} <= set(recs[0])
    assert all(r["arena_jitter"] == "0.025" and r["jitter_seed"] == r["seed"] for r in recs)
