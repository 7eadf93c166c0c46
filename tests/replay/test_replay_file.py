"""The replay file: self-contained, deterministic, written atomically; the CLI options that write it."""

from __future__ import annotations

import json
import re
import stat

import pytest

import harness.atomic as atomic
import harness.replay.html as replay_html
from harness.cli import main
from harness.replay import build_replay, render_html, save_replay


def _embedded(page: str) -> dict:
    m = re.search(r'<script type="application/json" id="ffr-data">(.*?)</script>', page, re.S)
    assert m, "no embedded data block"
    return json.loads(m.group(1))


def test_one_self_contained_file(room1) -> None:
    page = room1.html.read_text(encoding="utf-8")
    # nothing loaded from elsewhere: no external scripts, styles, frames or images
    assert not re.search(r"<script[^>]+src=", page, re.I)
    assert not re.search(r"<link[^>]+href=", page, re.I)
    assert not re.search(r"<(img|iframe)[^>]+src=", page, re.I)
    assert "/*FFR:" not in page and "FFR:TITLE" not in page  # every marker replaced
    # plotly.js is inlined, the player and the data too
    from plotly.offline import get_plotlyjs_version
    assert f"plotly.js v{get_plotlyjs_version()}" in page
    assert "window.ffrReplay" in page
    assert _embedded(page) == json.loads(json.dumps(room1.data.to_json()))
    # a reasonable size: plotly.js (~4.8 MB) plus well under a megabyte of mission
    size = room1.html.stat().st_size
    assert 4_500_000 < size < 6_000_000
    assert size - len(replay_html.plotly_js()) < 600_000


def test_same_mission_same_bytes(room1, tmp_path) -> None:
    again = tmp_path / "again.html"
    save_replay(again, room1.scn, room1.trace, room1.result)
    assert again.read_bytes() == room1.html.read_bytes()


def test_text_from_the_scenario_cannot_break_out_of_the_page(room1) -> None:
    data = build_replay(room1.scn, room1.trace, room1.result)
    plain = render_html(data)
    data.meta["scenario"] = "</script><script>alert(1)</script><!-- /*FFR:DATA*/"
    page = render_html(data)
    assert page.lower().count("<script") == page.lower().count("</script") == 3
    assert "<script>alert(1)" not in page and "<!--" not in page
    assert _embedded(page)["meta"]["scenario"] == data.meta["scenario"]
    # the marker in the name was not expanded again (that would add the data a second time)
    assert len(page) - len(plain) < 1000


def test_write_is_atomic(room1, tmp_path, monkeypatch) -> None:
    target = tmp_path / "r.html"
    target.write_text("old")

    def boom(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(atomic.os, "replace", boom)
    with pytest.raises(OSError):
        save_replay(target, room1.scn, room1.trace, room1.result)
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.html"]  # no temporary left behind


def test_written_file_is_readable_by_others(room1) -> None:
    assert stat.S_IMODE(room1.html.stat().st_mode) == 0o644


def test_ffr_run_replay(tmp_path, capsys) -> None:
    out = tmp_path / "sub" / "room2.html"
    assert main(["run", "--room", "2", "--replay", str(out)]) == 0
    data = _embedded(out.read_text(encoding="utf-8"))
    assert data["meta"]["room"] == 2 and data["meta"]["outcome"] == "home"
    assert data["meta"]["time_to_extinguish_s"] is not None
    assert "room2: home" in capsys.readouterr().out


def test_ffr_table1_replay_dir(tmp_path, capsys) -> None:
    assert main(["table1", "--replay-dir", str(tmp_path / "out")]) == 0
    files = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert files == [f"replay_room{n}.html" for n in (1, 2, 3, 4)]
    for n in (1, 2, 3, 4):
        meta = _embedded((tmp_path / "out" / f"replay_room{n}.html").read_text(encoding="utf-8"))["meta"]
        assert meta["room"] == n


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["run", "--replay", "{tmp}/r.png"], "ending in .html"),
        (["run", "--replay", "{tmp}"], "ending in .html"),
        (["run", "--replay", "{tmp}/dir.html"], "is a directory"),
        (["run", "--replay", "{tmp}/afile/r.html"], "is not a directory"),
        (["table1", "--replay-dir", "{tmp}/afile"], "not a directory"),
        (["run", "--room", "9", "--replay", "{tmp}/r.html"], "room = 9"),
    ],
)
def test_bad_replay_target_one_line_exit_2_nothing_written(tmp_path, capsys, argv, needle) -> None:
    (tmp_path / "dir.html").mkdir()
    (tmp_path / "afile").write_text("x")
    before = sorted(tmp_path.rglob("*"))
    assert main([a.replace("{tmp}", str(tmp_path)) for a in argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ffr: error:") and needle in err
    assert sorted(tmp_path.rglob("*")) == before


def test_write_failure_is_one_line_exit_2(tmp_path, capsys, monkeypatch) -> None:
    def full(src, dst):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(atomic.os, "replace", full)
    out = tmp_path / "r.html"
    assert main(["run", "--room", "1", "--replay", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No space left on device" in err and str(out) in err
    assert list(tmp_path.iterdir()) == []


def test_unwritable_folder_is_refused_before_running(tmp_path, capsys, monkeypatch) -> None:
    # (as root every folder is writable, so pretend: the check asks os.access)
    monkeypatch.setattr(atomic.os, "access", lambda path, mode: False)
    assert main(["run", "--replay", str(tmp_path / "r.html")]) == 2
    err = capsys.readouterr().err
    assert "cannot write in" in err and str(tmp_path) in err
    assert list(tmp_path.iterdir()) == []


def test_mission_without_a_tick_gives_no_replay_and_one_line(tmp_path, capsys, monkeypatch) -> None:
    import numpy as np

    import harness.loop
    from harness.loop import N_F, N_I, Trace
    from harness.scoring import MissionResult

    def dead_link(scn, link, record=True, rules=None):
        res = MissionResult(outcome="error", room=scn.room, candle=scn.candle, time_to_extinguish_s=None,
                            total_time_s=None, wall_contacts=0, min_wall_clearance_m=0.0, path_length_m=0.0,
                            seed=0, detail="link: no answer")
        return res, Trace(np.zeros((0, N_F)), np.zeros((0, N_I), np.int32))

    monkeypatch.setattr(harness.loop, "run_mission", dead_link)
    out = tmp_path / "r.html"
    assert main(["run", "--room", "1", "--replay", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no tick" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []
