"""harness.sweep_diff: two sweeps of the same missions matched mission by mission."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from harness.sweep import ROW_FIELDS
from harness.sweep_diff import main


def _row(i: int, seed: int, room: int, ok: bool, candle: str = "1.83,1.53") -> dict[str, str]:
    cx, cy = candle.split(",")
    return {"id": str(i), "room": str(room), "candle_x": cx, "candle_y": cy, "seed": str(seed), "noise": "datasheet",
            "start_x": "2.11", "start_y": "1.17", "start_heading_deg": "90.0", "arena_jitter": "0.025",
            "jitter_seed": str(seed), "furniture": "0", "outcome": "home" if ok else "collision",
            "success": str(ok), "detail": "" if ok else "pushed against a wall for 5 s",
            "replay": f"ffr run --candle {candle} --seed {seed}"}


def _csv(path: Path, rows: list[dict[str, str]], fields: list[str] = ROW_FIELDS) -> Path:
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    return path


BEFORE = [_row(0, 7, 1, True), _row(1, 7, 2, False), _row(2, 7, 3, False), _row(3, 8, 1, False), _row(4, 9, 1, True)]
# the same missions in another order and other row numbers: 7/room 1 lost, 7/rooms 2-3 and 8 won
AFTER = [_row(10, 9, 1, True), _row(11, 8, 1, True), _row(12, 7, 3, True), _row(13, 7, 2, True),
         _row(14, 7, 1, False)]


def test_missions_are_matched_by_what_defines_them(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    rows = tmp_path / "changed.tsv"
    assert main([str(_csv(tmp_path / "a.csv", BEFORE)), str(_csv(tmp_path / "b.csv", AFTER)),
                 "--rows", str(rows)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("before: 5 missions, 2 succeeded (40.0 %)")
    assert out[1].startswith("after:  5 missions, 4 succeeded (80.0 %)")
    assert out[2:] == ["in both: 5 missions; won 3, lost 1", "won:  7x2 8", "lost: 7"]
    lines = [ln.split("\t") for ln in rows.read_text().splitlines()]
    assert sorted((f[0], f[1], f[2]) for f in lines) == [("lost", "1", "7"), ("won", "1", "8"), ("won", "2", "7"),
                                                         ("won", "3", "7")]
    lost = next(f for f in lines if f[0] == "lost")
    assert lost[3:8] == ["1.83,1.53", "home", "", "collision", "pushed against a wall for 5 s"]
    assert lost[8] == "ffr run --candle 1.83,1.53 --seed 7"


def test_a_mission_in_one_sweep_only_is_counted_and_named(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    # another candle is another mission, even with the same seed and room
    after = AFTER[:4] + [_row(14, 7, 1, False, candle="0.5,0.5")]
    assert main([str(_csv(tmp_path / "a.csv", BEFORE)), str(_csv(tmp_path / "b.csv", after))]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[2] == "in both: 4 missions; won 3, lost 0"
    assert out[5] == "only in before: 1 missions (room, candle, seed: 1 1.83 1.53 7)"
    assert out[6] == "only in after: 1 missions (room, candle, seed: 1 0.5 0.5 7)"


def test_bad_input_is_one_line_and_status_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    good = _csv(tmp_path / "a.csv", BEFORE)
    twice = _csv(tmp_path / "twice.csv", BEFORE + [_row(5, 9, 1, False)])
    assert main([str(good), str(twice)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "twice.csv: line 7" in err and "seed 9" in err
    fewer = _csv(tmp_path / "fewer.csv", AFTER, fields=[f for f in ROW_FIELDS if f != "start_x"])
    assert main([str(good), str(fewer)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "fewer.csv" in err and "two CSVs of one sweep" in err
    no_replay = _csv(tmp_path / "noreplay.csv", AFTER, fields=ROW_FIELDS[:-1])
    assert main([str(good), str(no_replay)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "noreplay.csv" in err and "'replay'" in err
    assert main([str(good), str(tmp_path / "none.csv")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "none.csv" in err
    assert main([str(good), str(good), "--rows", str(good)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--rows" in err and "own CSV" in err
    assert good.read_text().startswith("id,room")  # not overwritten
