"""harness.failure_places: a failed sweep row run again, its route step and state where it went wrong."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest

from harness.failure_places import NEEDED, main

ROW = {"room": "1", "candle_x": "1.83", "candle_y": "1.53", "seed": "0", "success": "False",
       "outcome": "home", "detail": "", "replay": "ffr run --candle 1.83,1.53 --seed 0"}


def _csv(path: Path, rows: list[dict[str, str]], fields: tuple[str, ...] = NEEDED) -> Path:
    with path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(fields), extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    return path


def test_a_row_is_run_again_and_placed_at_its_end(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the nominal room-1 mission touches no wall: its place is the end, the route's HOME step, DONE
    ok = dict(ROW, success="True", seed="1")
    out = tmp_path / "rows.tsv"
    assert main([str(_csv(tmp_path / "s.csv", [ROW, ok])), "--rows", str(out)]) == 0
    text = capsys.readouterr().out
    assert "1 failed missions (of 1 failed rows" in text
    assert "1\t1\t27\tDONE\t" in text  # default route: step 27 is HOME(LEFT) from room 1
    fields = out.read_text().strip().split("\t")
    assert fields[:6] == ["1", "0", "1.83,1.53", "27", "DONE", "-"]


def test_motion_at_names_how_the_wheels_were_driven() -> None:
    import numpy as np

    from harness.failure_places import motion_at

    t = np.arange(0.0, 1.0, 0.01)
    cases = {(300, -300): "turn in place", (300, 300): "straight forward", (-300, -280): "straight back",
             (400, 150): "arc forward", (-100, -400): "arc back", (0, 0): "standing"}
    for (left, right), name in cases.items():
        pwm = np.zeros((len(t), 2), dtype=np.int32)
        pwm[60:] = (left, right)  # the last 0.4 s: the window before the last tick sees only these
        assert motion_at(pwm, t, len(t) - 1) == name
        # and the window ends at the tick asked for: before the change, standing
        assert motion_at(pwm, t, 50) == "standing"


def test_motion_groups_and_rows_name_the_motion(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the nominal room-1 mission ends as it drives straight into the home circle, far from its start
    out = tmp_path / "rows.tsv"
    assert main([str(_csv(tmp_path / "s.csv", [ROW])), "--motion", "--rows", str(out)]) == 0
    text = capsys.readouterr().out
    assert "contact or detail\tmotion" in text
    assert "1\t1\t27\tDONE\t\tstraight forward, moved" in text
    assert out.read_text().strip().split("\t")[-1] == "straight forward, moved"


def test_skipped_seeds_are_left_out(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([str(_csv(tmp_path / "s.csv", [ROW])), "--skip-seeds", "0"]) == 0
    assert "0 failed missions (of 1 failed rows; seeds left out: 0)" in capsys.readouterr().out


def test_bad_input_is_one_line_and_status_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    bad = _csv(tmp_path / "bad.csv", [ROW], fields=("room", "seed"))
    assert main([str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "bad.csv" in err and "'candle_x'" in err
    assert main([str(tmp_path / "none.csv")]) == 2
    assert "none.csv" in capsys.readouterr().err
    assert main([str(bad), "--skip-seeds", "x"]) == 2
    assert "--skip-seeds" in capsys.readouterr().err



def test_a_row_of_any_sweep_is_run_again_as_the_sweep_ran_it() -> None:
    # a random start, a jittered arena and furniture: the row's scenario is the sweep's own, read
    # back from the row's replay command
    from harness.failure_places import scenario_of
    from harness.scenario import make_scenario
    from harness.sweep import SweepSpec, build_jobs, run_job

    job = build_jobs(SweepSpec(rooms=(3,), candles="default", seeds=(5,), start="random", arena_jitter=0.05,
                               furniture=2))[0]
    row = {k: str(v) for k, v in run_job(job).items()}
    scn = scenario_of(row)
    ref = make_scenario(candle=tuple(job["candle"]), seed=5, start="random", arena_jitter=0.05, furniture=2)
    assert scn.start == ref.start and abs(scn.start[0] - float(row["start_x"])) < 1e-12
    assert scn.arena.walls == ref.arena.walls and scn.furniture == ref.furniture and len(scn.furniture) == 2
    assert scn.arena_jitter == 0.05 and scn.candle == ref.candle


def test_a_row_whose_replay_is_not_ffr_run_is_one_line_and_status_2(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    bad = _csv(tmp_path / "bad.csv", [dict(ROW, replay="rm -rf /")])
    assert main([str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "replay" in err and "rm -rf" in err


def test_a_rows_file_that_cannot_be_written_is_one_line_before_any_run(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    src = _csv(tmp_path / "s.csv", [ROW])
    for rows, why in ((tmp_path, "is a directory"), (src, "own CSV")):
        assert main([str(src), "--rows", str(rows)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--rows" in err and why in err
    assert src.read_text().startswith("room,")  # the sweep's CSV untouched
    assert main([str(src), "--no-such-flag"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_a_row_runs_on_its_own_firmware_link(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                             monkeypatch: pytest.MonkeyPatch) -> None:
    # a sweep of a team's library (--firmware) is placed with that library, not the one the harness
    # loads by default: a library that is not there is the row's own link failing, one line, exit 2
    gone = tmp_path / "libteam.so"
    bad = _csv(tmp_path / "team.csv", [dict(ROW, replay=f"{ROW['replay']} --firmware {gone}")])
    assert main([str(bad)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and str(gone) in err and "team.csv" in err
    # and the link reaches the run as the replay names it
    import harness.loop
    from ffr_link.library import library_path
    from harness.failure_places import place_of

    links: list[str] = []
    real = harness.loop.run_mission

    def spy(scn: object, link: str = "ctypes:", **kw: object) -> object:
        links.append(link)
        return real(scn, link, **kw)  # type: ignore[arg-type]

    monkeypatch.setattr(harness.loop, "run_mission", spy)
    ours = library_path()
    named = place_of(dict(ROW, replay=f"{ROW['replay']} --firmware {ours}"))
    plain = place_of(ROW)
    assert links == [f"ctypes:{ours}", "ctypes:"]
    assert (named.step, named.state, named.pose) == (plain.step, plain.state, plain.pose)

