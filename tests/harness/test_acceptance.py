"""The acceptance runner (``python -m harness.acceptance``): goals judged from each command's JSON."""

from __future__ import annotations

from typing import Any

import pytest

from harness import acceptance as acc


def _sweep_json(n: int, ok: int) -> dict[str, Any]:
    return {"missions": n, "succeeded": ok, "success_rate_pct": 100.0 * ok / n, "failures": []}


def _table1_json(times: list[float | None], contacts: int = 0) -> list[dict[str, Any]]:
    return [{"time_to_extinguish_s": t, "outcome": "home", "wall_contacts": contacts} for t in times]


ROW = next(r for r in acc.ROWS if r.key == "realistic")


def test_a_sweep_at_the_goal_is_met_and_one_mission_short_is_not() -> None:
    _, at = acc.measure(ROW, None, None, lambda argv: _sweep_json(2000, 1980))
    _, short = acc.measure(ROW, None, None, lambda argv: _sweep_json(2000, 1979))
    assert at.met is True and at.text == "1,980 = 99.0 %"
    assert short.met is False


def test_table1_is_met_within_ten_percent_of_the_times_before_and_without_contact() -> None:
    lim = [b * 1.10 for b in acc.TIMES_BEFORE_S]
    _, ok = acc.measure(acc.TABLE1, None, None, lambda argv: _table1_json(lim))
    _, slow = acc.measure(acc.TABLE1, None, None, lambda argv: _table1_json([lim[0] + 0.05, *lim[1:]]))
    _, touched = acc.measure(acc.TABLE1, None, None, lambda argv: _table1_json(lim, contacts=1))
    _, unlit = acc.measure(acc.TABLE1, None, None, lambda argv: _table1_json([None, *lim[1:]]))
    assert ok.met is True
    assert slow.met is False and touched.met is False and unlit.met is False


def test_each_firmware_runs_the_rows_own_command_with_its_library() -> None:
    seen: list[list[str]] = []

    def runner(argv: list[str]) -> Any:
        seen.append(argv)
        return _table1_json(list(acc.TIMES_BEFORE_S)) if argv[0] == "table1" else _sweep_json(10, 10)

    text, records = acc.table([ROW, acc.TABLE1], [("a", "/x/a.so"), ("b", None)], 2, runner)
    assert seen[0] == [*ROW.argv, "--no-progress", "--workers", "2", "--firmware", "/x/a.so"]
    assert seen[1] == [*ROW.argv, "--no-progress", "--workers", "2"]
    assert seen[2] == ["table1", "--link", "ctypes:/x/a.so"]
    assert seen[3] == ["table1"]
    assert [r["firmware"] for r in records] == ["a", "b", "a", "b"]
    assert ("`ffr sweep --noise realistic -n 10 --seeds 0:50` | 10 | 10 = 100.0 % | 10 = 100.0 % "
            "| >= 99 % (12) | MET |") in text


@pytest.mark.parametrize("argv, names", [
    (["--rows", "realistic,nope"], ["--rows", "nope"]),
    (["--firmware", "before"], ["--firmware", "before"]),
    (["--firmware", "b=/no/such/lib.so"], ["--firmware", "/no/such/lib.so"]),
    (["--workers", "0"], ["--workers", "0"]),
    (["--json", "/dev/null/x.json"], ["--json", "/dev/null/x.json"]),
])
def test_bad_arguments_get_one_line_naming_them_and_exit_2(capsys: pytest.CaptureFixture[str], argv: list[str],
                                                           names: list[str]) -> None:
    def runner(argv: list[str]) -> Any:
        raise AssertionError("nothing runs on bad input")

    assert acc.main(argv, runner) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(n in err for n in names), err


def test_the_runner_runs_the_real_command_and_reads_its_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert acc.main(["--rows", "table1", "--json", "-"]) == 0
    out = capsys.readouterr().out
    assert '"row": "table1"' in out and '"missions": 4' in out


def test_held_out_rows_run_only_when_asked_and_have_no_goal() -> None:
    default = acc._rows(None)
    assert not set(default) & set(acc.HELD_OUT)
    assert acc._rows("held-out") == list(acc.HELD_OUT)
    assert acc._rows("combined") == list(acc.COMBINED)
    assert acc._rows("all") == [*default, *acc.HELD_OUT, *acc.COMBINED]
    keys = [r.key for r in acc._rows("all")]
    assert len(keys) == len(set(keys))
    assert all(r.goal_pct is None for r in (*acc.HELD_OUT, *acc.COMBINED))
    _, cell = acc.measure(acc.HELD_OUT[0], None, None, lambda argv: _sweep_json(2000, 1))
    assert cell.met is None


def test_a_combined_row_runs_options_no_goal_row_runs_together() -> None:
    # each combined row's options (flags with their values) are in no single goal row
    def opts(argv: tuple[str, ...]) -> set[tuple[str, str]]:
        return {(a, argv[i + 1]) for i, a in enumerate(argv[:-1])
                if a.startswith("--") and a not in ("--seeds",)}

    for c in acc.COMBINED:
        assert c.argv[0] == "sweep" and "--seeds" in c.argv
        assert not any(opts(c.argv) <= opts(g.argv) for g in acc.ROWS), c.key


@pytest.mark.parametrize("goal, held", [("realistic", "realistic-held"), ("jitter", "jitter-held"),
                                        ("start", "start-held"), ("hallway", "hallway-held"),
                                        ("furniture", "furniture-held")])
def test_a_held_out_row_is_its_goal_rows_command_on_other_seeds(goal: str, held: str) -> None:
    g, h = acc._rows(goal)[0], acc._rows(held)[0]

    def seeds(argv: tuple[str, ...]) -> set[int]:
        lo, hi = argv[argv.index("--seeds") + 1].split(":")
        return set(range(int(lo), int(hi)))

    def rest(argv: tuple[str, ...]) -> tuple[str, ...]:
        i = argv.index("--seeds")
        return argv[:i] + argv[i + 2:]

    assert rest(g.argv) == rest(h.argv) and not seeds(g.argv) & seeds(h.argv)
