"""``python -m harness.bench SECTION...``: bad input is one line and exit 2 (the sections
themselves are timings: they live in ``make bench``, not in tests)."""

from __future__ import annotations

import pytest

from harness import bench


def test_an_unknown_section_is_one_line_and_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert bench.main(["missions", "nope"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'nope'" in err and "parts, missions" in err


@pytest.mark.parametrize("argv, names", [(["--seconds", "0"], "--seconds = 0.0"), (["--room", "5"], "--room")])
def test_perf_map_bad_arguments_are_one_line_and_exit_2(capsys: pytest.CaptureFixture[str], argv: list[str],
                                                        names: str) -> None:
    from harness import perf_map

    assert perf_map.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and names in err


def test_the_arena_section_runs_alone(capsys: pytest.CaptureFixture[str]) -> None:
    # its figures are timings (make bench); here only that the section is there and prints them
    assert bench.main(["arena"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("arena: the 2004 arena's checks ") and "jittered arena drawn and checked" in out
