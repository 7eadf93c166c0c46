"""harness.reality_ablation: one sweep per part of a noise profile made ideal."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import pytest

from harness import reality_ablation as ra
from sim_plant.sensors import load_noise_profile


def test_each_part_made_ideal_changes_its_fields_only() -> None:
    prof = ra.builtin_profile("realistic")
    for ab in ra.ABLATIONS:
        out = ra.ablated(prof, ab)
        assert out is not None, ab.key  # the realistic profile has every part
        for group, field, value in ab.fields:
            if field == "*":
                assert group not in out
            else:
                assert out[group][field] == value and prof[group][field] != value
        touched = {g for g, _, _ in ab.fields}
        for group in prof:
            if group not in touched:
                assert out.get(group) == prof[group], (ab.key, group)


def test_a_part_the_profile_lacks_is_no_row() -> None:
    # the datasheet profile has parts but no drawn robot: its reality rows change nothing
    prof = ra.builtin_profile("datasheet")
    keys = {ab.key: ra.ablated(prof, ab) for ab in ra.ABLATIONS}
    assert keys["reality"] is None and keys["turn-slip"] is None
    assert keys["parts"] is not None


def test_written_profiles_load_as_noise_files(tmp_path: Path) -> None:
    prof = ra.builtin_profile("realistic")
    for ab in ra.ABLATIONS:
        path = tmp_path / f"{ab.key}.toml"
        path.write_text(ra.profile_toml("realistic", ra.ablated(prof, ab) or {}))
        with path.open("rb") as fh:
            assert tomllib.load(fh)["realistic"] == ra.ablated(prof, ab)
        load_noise_profile(str(path))  # the sweep's own check passes


def test_the_table_runs_one_sweep_per_row_and_counts_against_the_first() -> None:
    seen: list[list[str]] = []
    counts = iter([150, 160, 140])

    def runner(argv: list[str]) -> dict[str, Any]:
        seen.append(argv)
        noise = Path(argv[argv.index("--noise") + 1])
        with noise.open("rb") as fh:
            assert "realistic" in tomllib.load(fh)  # written while the sweep runs
        return {"missions": 200, "succeeded": next(counts)}

    chosen = [a for a in ra.ABLATIONS if a.key in ("parts", "reality")]
    text = ra.table("realistic", ra.builtin_profile("realistic"), chosen, ["-n", "1"], runner)
    assert len(seen) == 3 and all(a[:3] == ["sweep", "-n", "1"] for a in seen)
    lines = text.splitlines()
    assert "| 200 | 150 = 75.0 % |  |" in lines[2]
    assert lines[3].endswith("| 200 | 160 = 80.0 % | +10 |")
    assert lines[4].endswith("| 200 | 140 = 70.0 % | -10 |")


@pytest.mark.parametrize("argv, words", [
    (["--only", "bogus"], "--only = 'bogus'"),
    (["--profile", "nope"], "--profile = 'nope'"),
    (["--", "--noise", "none"], "sweep option --noise"),
    (["--", "--json=x.json"], "sweep option --json"),
])
def test_bad_input_is_one_line_and_status_2(argv: list[str], words: str,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    assert ra.main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0] and err[0].startswith(ra.PROG)


def test_a_bad_sweep_option_is_the_sweeps_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    assert ra.main(["--only", "parts", "--", "-n", "1", "--seeds", "x"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(ra.PROG) and "--seeds = 'x'" in err[0]
