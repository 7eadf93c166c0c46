"""`python -m harness.start_room`: how much room each start of a sweep left, and how they fared."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from harness import start_room
from harness.failure_places import replay_of
from harness.start_pose import footprint
from tests.harness.conftest import NEAR_WALL_START as NEAR
from tests.harness.conftest import sweep_csv as _csv


def test_the_gap_is_the_body_to_the_nearest_wall_as_drawn() -> None:
    scn = replay_of(NEAR)[0]
    x, y, th = scn.start
    wall = next(w for w in scn.arena.walls if w.name == "br_top")  # along y = 0.93, 2 cm thick
    face = wall.a[1] + wall.t / 2.0
    by_hand = (min(py for _, py in footprint(scn.robot, x, y, th)) - face) * 1000.0
    pose, gap, angle, axle, turn, _ = start_room.measure(NEAR)
    assert gap == pytest.approx(by_hand, abs=0.01)
    assert 0.0 < gap < 5.0
    assert angle == pytest.approx(abs(math.degrees(math.atan2(math.sin(th), math.cos(th)))), abs=0.01)
    assert axle == pytest.approx((y - face) * 1000.0, abs=0.01)  # the axle's nearest wall is the same
    assert turn == pytest.approx(math.hypot(120.0, 100.0))  # the default body: 12 cm front, 20 cm wide
    assert pose[:2] == pytest.approx((x, y))


def test_the_wall_is_placed_behind_ahead_or_beside_the_body() -> None:
    """Seed 105's axle stands 133 mm above the wall along y = 0.93: facing +y the wall is behind
    (beyond the 100 mm rear face), facing -y ahead (beyond the 120 mm front face), facing +x on
    the right, facing -x on the left. As measured, the body 17.7 degrees off that wall, beside."""
    scn = replay_of(NEAR)[0]
    x, y, th = scn.start
    sides = {h: start_room._wall_side(scn.arena, scn.robot, x, y, math.radians(h)) for h in (90, -90, 0, 180)}
    assert sides == {90: "behind", -90: "ahead", 0: "right", 180: "left"}
    assert start_room.measure(NEAR).wall == ("right" if math.cos(th) > 0.0 else "left")


def test_missions_of_one_start_are_one_start_and_bands_count_them(tmp_path: Path) -> None:
    far = "ffr run --candle 1.83,1.53 --seed 3 --start random"
    rows = [(105, False, NEAR), (105, True, NEAR.replace("1.83,1.53", "0.62,2.32")),
            (3, True, far), (3, True, far.replace("1.83,1.53", "0.62,2.32"))]
    starts = start_room.starts_of(_csv(tmp_path / "s.csv", rows))
    assert [(s.seed, s.missions, s.failed) for s in starts] == [(3, 2, 0), (105, 2, 1)]
    near = starts[1]
    assert near.must_move  # 133 mm from the wall, the corners reach 156
    text = start_room.report(starts, (10.0, 1000.0))
    lines = text.splitlines()
    assert lines[0] == "2 start poses, 4 missions, 3 succeeded (75.0 %)"
    assert lines[2].split() == ["0-10", "1", "2", "50.0%", "1"]
    assert lines[3].split()[1:] == ["1", "2", "100.0%", "0"]
    assert "must move before turning" in lines[5] and "1 starts, 2 missions, 1 succeeded (50.0 %)" in lines[5]
    assert lines[6] == "can turn in place: 1 starts, 2 missions, 2 succeeded (100.0 %)"
    side = near.wall
    assert lines[7] == ("failed starts that must move, by where the axle's nearest wall is: "
                        + ", ".join(f"{w} {int(w == side)}" for w in start_room.WALL_SIDES))
    assert lines[-1].split()[0] == "105" and lines[-1].split()[-2:] == [side, "1/2"]


def test_the_command_prints_the_table_and_writes_rows(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _csv(tmp_path / "s.csv", [(105, False, NEAR)])
    out = tmp_path / "rows.tsv"
    assert start_room.main([str(src), "--rows", str(out)]) == 0
    assert capsys.readouterr().out.startswith("1 start poses, 1 missions, 0 succeeded (0.0 %)")
    lines = out.read_text().splitlines()
    assert lines[0].split("\t") == ["seed", "x", "y", "heading_deg", "gap_mm", "angle_deg", "axle_mm", "wall",
                                    "missions", "failed"]
    assert lines[1].split("\t")[0] == "105" and len(lines) == 2


def test_along_adds_the_bands_of_the_starts_near_parallel_to_their_wall(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """Seed 105's body is 17.7 degrees off its wall, seed 3's 10.4: --along 15 keeps seed 3 alone,
    --along 20 both."""
    far = "ffr run --candle 1.83,1.53 --seed 3 --start random"
    src = _csv(tmp_path / "s.csv", [(105, False, NEAR), (3, True, far)])
    assert start_room.main([str(src), "--bins", "10", "--along", "15"]) == 0
    lines = capsys.readouterr().out.splitlines()
    k = lines.index("along a wall (the axis within 15 degrees of its nearest wall):")
    assert lines[k + 2].split() == ["0-10", "0", "0", "-", "0"]
    assert lines[k + 3].split() == ["10+", "1", "1", "100.0%", "0"]
    assert start_room.main([str(src), "--bins", "10", "--along", "20"]) == 0
    lines = capsys.readouterr().out.splitlines()
    k = lines.index("along a wall (the axis within 20 degrees of its nearest wall):")
    assert lines[k + 2].split() == ["0-10", "1", "1", "0.0%", "1"]
    assert lines[k + 3].split() == ["10+", "1", "1", "100.0%", "0"]
    assert start_room.main([str(src)]) == 0
    assert "along a wall" not in capsys.readouterr().out


def test_a_jittered_seed_is_one_start_per_arena_it_drew(tmp_path: Path) -> None:
    """A jittered arena is drawn again while the candle is not legal in it, so one seed's missions
    may start in different arenas and poses (seed 51 of the +-2.5 cm row: the third candle's arena
    is another, and its start 11 mm away): each is measured, and counted as its own start."""
    base = "ffr run --candle {} --seed 51 --noise datasheet --start random --arena-jitter 0.025"
    candles = ["1.8373310791430497,1.4374644991588414", "1.8925113314884996,1.6060535022887166",
               "0.7073598851886943,2.188553624246118"]
    replays = [base.format(c) for c in candles]
    assert replay_of(replays[0])[0].start == replay_of(replays[1])[0].start != replay_of(replays[2])[0].start
    starts = start_room.starts_of(_csv(tmp_path / "j.csv", [(51, k != 2, r) for k, r in enumerate(replays)]))
    assert [(s.missions, s.failed) for s in starts] == [(2, 0), (1, 1)]  # sorted by pose: x 2.0836, 2.0919
    assert starts[0].gap_mm == pytest.approx(start_room.measure(replays[0])[1])
    assert starts[1].gap_mm == pytest.approx(start_room.measure(replays[2])[1])
    assert starts[0].gap_mm != pytest.approx(starts[1].gap_mm, abs=1.0)


@pytest.mark.parametrize("content, argv, names", [
    ("seed,success\n1,True\n", [], ["replay"]),
    ("seed,success,replay\n1,True\n", [], ["row 2", "cells"]),
    ("seed,success,replay\nx,True,ffr run --seed 1 --start random\n", [], ["row 2", "'x'"]),
    ("seed,success,replay\n1,True,ffr run --seed 1 --start random --bogus\n", [], ["row 2", "--bogus"]),
    ("seed,success,replay\n1,True,ffr run --seed 1 --start random --arena-jitter 5\n", [],
     ["row 2", "--arena-jitter = '5'"]),
    (b"seed,success,replay\n\xff\xfe,True,x\n", [], ["s.csv", "not a CSV text"]),
    ("seed,success,replay\n", ["--bins", "10,nan"], ["--bins", "nan"]),
    ("seed,success,replay\n", ["--bins", "10,inf"], ["--bins", "inf"]),
    ("seed,success,replay\n", ["--rows", "SELF"], ["--rows", "own CSV"]),
    ("seed,success,replay\n1,True,ffr run --room 1\n", [], ["ffr run --room 1", "not a random"]),
    ("seed,success,replay\n1,True,ffr sweep\n", [], ["ffr sweep"]),
    (None, [], ["no/such.csv"]),
    ("seed,success,replay\n", ["--bins", "20,10"], ["--bins", "20,10"]),
    ("seed,success,replay\n", ["--bins", "x"], ["--bins", "'x'"]),
    ("seed,success,replay\n", ["--what"], ["--what"]),
    ("seed,success,replay\n", ["--along", "0"], ["--along", "0"]),
    ("seed,success,replay\n", ["--along", "nan"], ["--along", "nan"]),
    ("seed,success,replay\n", ["--along", "91"], ["--along", "91"]),
    ("seed,success,replay\n", ["--along", "x"], ["--along", "'x'"]),
])
def test_bad_input_gets_one_line_and_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                           content: str | bytes | None, argv: list[str], names: list[str]) -> None:
    path = tmp_path / "s.csv"
    if content is None:
        path = tmp_path / "no/such.csv"
    elif isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    argv = [str(path) if a == "SELF" else a for a in argv]
    assert start_room.main([str(path), *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(n in err for n in names), err


def test_no_rows_file_is_left_half_written_on_a_bad_csv(tmp_path: Path) -> None:
    path = tmp_path / "s.csv"
    path.write_text("seed,success\n")
    out = tmp_path / "rows.tsv"
    assert start_room.main([str(path), "--rows", str(out)]) == 2
    assert not out.exists()
