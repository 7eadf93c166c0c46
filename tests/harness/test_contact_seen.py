"""`python -m harness.contact_seen`: did a ranger see the wall a failed mission touched, and how near?"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from harness import contact_seen
from tests.harness.conftest import FOLDED_CORNER_CONTACT as TOUCH
from tests.harness.conftest import NEAR_WALL_START as NEAR
from tests.harness.conftest import sweep_csv as _csv


def test_the_point_touched_and_the_corner_that_touched_it() -> None:
    # a body square (corners FR, FL, RL, RR as harness.start_pose.footprint orders them) whose
    # front-left corner is 1 mm from a wall's face at y = 0.3
    body = np.array([[0.12, 0.09], [0.12, 0.299], [-0.10, 0.299], [-0.10, 0.09]])
    wall = np.array([[-1.0, 0.3], [1.0, 0.3], [1.0, 0.32], [-1.0, 0.32]])
    point, part = contact_seen.touch_point(body, [wall])
    assert part == "FL"
    assert point == pytest.approx([0.12, 0.3])
    # the wall's corner against the body's side: no body corner near it
    post = np.array([[0.0, 0.3], [0.02, 0.3], [0.02, 0.5], [0.0, 0.5]])
    point, part = contact_seen.touch_point(body, [post])
    assert part == "side"
    assert point[1] == pytest.approx(0.3)


def test_a_corner_on_a_wall_its_ranger_read_folded_back() -> None:
    c = contact_seen.contact_of(TOUCH, 7973, "1", 0.03)
    assert c is not None and c.seen is not None and c.first is not None
    assert c.part == "FL" and c.seen.ranger == "LF"
    assert c.seen.true_mm < contact_seen.FOLD_PEAK_MM  # the fold-back side of the GP2D12's peak
    assert c.first.before_s == pytest.approx(c.t_s)  # seen from the first tick on
    assert c.seen.read_mv < 2600  # below the peak: it reads as a wall farther off than it is


def test_the_command_prints_counts_lines_and_the_span(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    ok = "ffr run --candle 1.83,1.53 --seed 3 --start random"
    src = _csv(tmp_path / "s.csv", [(7973, False, TOUCH), (3, True, ok)])
    rows = tmp_path / "rows.tsv"
    assert contact_seen.main([str(src), "--rows", str(rows), "--span", "1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("1 failed missions, 1 touched a wall; 1 of the points touched were seen")
    assert "1 by the touching corner's own ranger; 1 last at a true range below 80 mm" in out[0]
    assert out[2].split()[:5] == ["7973", "1", out[2].split()[2], "FL", "LF"]
    assert out[3].startswith("readings within the fold-back span (160 mm) over the orientation of 1 rows")
    lf = next(line.split() for line in out[4:] if line.split()[0] == "LF")
    assert int(lf[1]) > 0  # seed 7973's left front ranger: a wall within 80 mm, read within the span
    lines = rows.read_text().splitlines()
    assert lines[0].split("\t")[:5] == ["seed", "room", "contact_s", "part", "last_ranger"]
    assert lines[1].split("\t")[0] == "7973" and len(lines) == 2


def test_at_start_counts_the_first_tick_only(tmp_path: Path) -> None:
    src = _csv(tmp_path / "s.csv", [(105, False, NEAR)])
    first = contact_seen.span_counts(src, 1, at_start=True)
    whole = contact_seen.span_counts(src, 1)
    assert sum(map(sum, first.values())) <= 5  # one reading per ranger at most
    assert first["RF"][0] == 1  # seed 105 starts with its right front corner at the wall, read folded back
    assert sum(map(sum, whole.values())) > sum(map(sum, first.values()))


def test_starts_writes_each_rows_first_readings(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _csv(tmp_path / "s.csv", [(105, False, NEAR)])
    starts = tmp_path / "starts.tsv"
    assert contact_seen.main([str(src), "--span", "1", "--at-start", "--starts", str(starts)]) == 0
    assert "over the first tick of 1 rows" in capsys.readouterr().out
    head, line = (row.split("\t") for row in starts.read_text().splitlines())
    assert tuple(head) == contact_seen.STARTS_HEADER
    got = dict(zip(head, line, strict=True))
    assert (got["seed"], got["room"], got["success"]) == ("105", "1", "False")
    # the right front corner at the wall: truly nearer than the fold-back peak, read farther than it
    assert int(got["RF_true_mm"]) < contact_seen.FOLD_PEAK_MM < int(got["RF_read_mm"])


def test_bad_input_is_one_line_and_status_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _csv(tmp_path / "s.csv", [(105, False, NEAR)])
    for argv, word in (([str(src), "--near", "0"], "--near"), ([str(src), "--span", "-1"], "--span"),
                       ([str(tmp_path / "none.csv")], "none.csv"), ([str(src), "--at-start"], "--at-start"),
                       ([str(src), "--rows", str(src)], "--rows"), ([str(src), "--starts", "x.tsv"], "--starts"),
                       ([str(src), "--span", "1", "--at-start", "--starts", str(src)], "--starts"),
                       ([str(src), "--span", "1", "--at-start", "--rows", "a.tsv", "--starts", "a.tsv"], "--starts")):
        assert contact_seen.main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and word in err
    # a failed row runs again on its replay's own link: one that cannot be opened is bad input
    gone = _csv(tmp_path / "team.csv", [(105, False, f"{NEAR} --firmware /no/such/libteam.so")])
    assert contact_seen.main([str(gone)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "/no/such/libteam.so" in err
    bad = tmp_path / "bad.csv"
    bad.write_text("seed,success\n1,False\n")
    assert contact_seen.main([str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bad.csv" in err and "'room'" in err
