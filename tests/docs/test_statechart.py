"""docs/firmware.md's state diagrams are what ``python -m harness.statechart`` reads from the C
sources now, and they draw everything the firmware has: every state name the library exports,
every route op, every failure code, every room phase, each reachable from its start."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from ffr_link.library import firmware_info
from harness import statechart
from harness.statechart import BEGIN, END, Chart, ChartError, Names

REPO = Path(__file__).resolve().parents[2]
DOC = REPO / "docs" / "firmware.md"
SRC = REPO / "firmware" / "src"


def _nodes(chart: Chart) -> set[str]:
    return ({e.src for e in chart.edges} | {e.dst for e in chart.edges} | set(chart.nodes)) - {"[*]"}


def test_the_docs_diagrams_are_what_the_generator_prints_now() -> None:
    doc = DOC.read_text(encoding="utf-8")
    block = doc[doc.index(BEGIN):doc.index(END) + len(END)]
    assert block == statechart.render(), "docs/firmware.md: the state diagrams are stale: run `make statechart`"
    res = subprocess.run([sys.executable, "-m", "harness.statechart", "--check", str(DOC)], cwd=REPO,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr


def test_check_fails_on_a_stale_block_and_write_mends_it(tmp_path: Path) -> None:
    doc = tmp_path / "firmware.md"
    text = DOC.read_text(encoding="utf-8")
    stale = text.replace("    TURN_BEST --> APPROACH", "    TURN_BEST --> SCAN", 1)
    assert stale != text
    doc.write_text(stale, encoding="utf-8")
    assert statechart.main(["--check", str(doc)]) == 1
    assert statechart.main(["--write", str(doc)]) == 0
    assert doc.read_text(encoding="utf-8") == text
    assert statechart.main(["--check", str(doc)]) == 0


def test_every_state_op_and_failure_the_library_names_is_drawn() -> None:
    info = firmware_info()
    mission, orient, room = statechart.charts()
    drawn = _nodes(mission) | {note.split(":")[0].removeprefix("reports ") for note in room.nodes.values()}
    missing = [s for s in info.state_names if s not in drawn]
    assert not missing, f"states the library names but no diagram draws: {missing}"
    ops = info.names[statechart.NAMES_OPS]
    labels = [e.label for e in mission.edges if e.src == "next_step"]
    assert all(any(re.search(rf"op = (\w+ or )*{op}\b", lab) for lab in labels) for op in ops), labels
    text = "\n".join(e.label for c in (mission, room) for e in c.edges)
    fails = [f for f in info.fail_names if f]
    assert [f for f in fails if f"failed: {f}" not in text] == []


def test_every_phase_has_a_handler_and_every_node_is_reachable_from_the_start() -> None:
    mission, orient, room = statechart.charts()
    text = (SRC / "room.c").read_text(encoding="utf-8")
    phases = {p.removeprefix("RP_") for p in statechart.enum_values(text, "RP_")} - {"COUNT"}
    assert phases and phases <= _nodes(room)
    orient_phases = {p.removeprefix("PH_") for p in
                     statechart.enum_values((SRC / "home_orient.c").read_text(encoding="utf-8"), "PH_")}
    assert orient_phases and orient_phases <= _nodes(orient)
    for chart in (mission, orient, room):
        assert _nodes(chart) - chart.reachable() == set(), chart.title
        # and every chart ends somewhere
        assert any(e.dst == "[*]" for e in chart.edges), chart.title


def _copy_src(tmp_path: Path) -> Path:
    src = tmp_path / "src"
    shutil.copytree(SRC, src)
    return src


def test_a_phase_nothing_returns_is_unreachable(tmp_path: Path) -> None:
    """The reachability check can fail: VERIFY's one way in taken out of on_extinguish."""
    src = _copy_src(tmp_path)
    room_c = src / "room.c"
    text = room_c.read_text(encoding="utf-8")
    assert text.count("next = RP_VERIFY;") == 1
    room_c.write_text(text.replace("next = RP_VERIFY;", "next = RP_STAY;"), encoding="utf-8")
    names = Names.load()
    room = statechart.room_chart(src, names)
    assert "VERIFY" in _nodes(room) and "VERIFY" not in room.reachable()


def test_a_handler_table_out_of_step_with_the_phases_is_refused(tmp_path: Path) -> None:
    src = _copy_src(tmp_path)
    room_c = src / "room.c"
    text = room_c.read_text(encoding="utf-8")
    room_c.write_text(text.replace("    RP_LEAVE_OUT,\n", "    RP_LEAVE_OUT,\n    RP_NEW_PHASE,\n", 1),
                      encoding="utf-8")
    with pytest.raises(ChartError, match="16 phases, 15 handlers"):
        statechart.room_chart(src, Names.load())


def test_labels_are_the_conditions_around_the_transition() -> None:
    """A few edges whose conditions are plain in room.c and route.c, as the generator words them."""
    mission, orient, room = statechart.charts()
    assert statechart.Edge("ENTER_LINE", "ENTER_IN", "lines.edge or lines.level") in room.edges
    assert statechart.Edge("LEAVE_TURN", "LEAVE_LINE", "turn_to / ROOM_FACING_OUT") in room.edges
    assert statechart.Edge("BACK_TURN", "BACK_DRIVE", "") in room.edges
    assert statechart.Edge("TURN", "next_step", "turn_done / pc = route.pc + 1") in mission.edges
    assert statechart.Edge("ROOM", "next_step", "room_step = ROOM_LEFT and flags has FLAG_EXTINGUISHED / "
                                                 "pc = return_start[arg - 1]") in mission.edges


def test_bad_arguments_are_one_line_and_status_2(tmp_path: Path) -> None:
    for argv in (["--check", str(tmp_path / "nope.md")], ["--src", str(tmp_path / "nope")], ["--bogus"]):
        res = subprocess.run([sys.executable, "-m", "harness.statechart", *argv], cwd=REPO, capture_output=True,
                             text=True, timeout=120)
        assert res.returncode == 2 and len(res.stderr.strip().splitlines()) == 1, (argv, res.stderr)
        assert "Traceback" not in res.stderr
    no_block = tmp_path / "doc.md"
    no_block.write_text("# no markers\n", encoding="utf-8")
    res = subprocess.run([sys.executable, "-m", "harness.statechart", "--check", str(no_block)], cwd=REPO,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "statechart:begin" in res.stderr
