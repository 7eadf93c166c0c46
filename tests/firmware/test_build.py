"""The installed ffr's firmware build (firmware/build.py) uses the Makefile's flags: the same
sources and flags give the same bits as a checkout's build/host/."""

from __future__ import annotations

import re
from pathlib import Path

from ffr_firmware.build import BOARD_FLAGS, CSTD, LIB_FLAGS

REPO = Path(__file__).resolve().parents[2]


def _make_var(name: str) -> list[str]:
    text = REPO.joinpath("Makefile").read_text().replace("\\\n", " ")
    m = re.search(rf"^{name}\s*:=\s*(.*)$", text, re.M)
    assert m, name
    return m.group(1).split()


def test_the_flags_are_the_makefiles() -> None:
    assert [f for f in _make_var("CSTD") if not f.startswith("-I")] == CSTD
    host = _make_var("HOST_CFLAGS")
    assert host[0] == "$(CSTD)" and host[1:] + ["-shared"] == LIB_FLAGS
    board_rule = next(ln for ln in REPO.joinpath("Makefile").read_text().splitlines()
                      if "$(CSTD)" in ln and "-Ifirmware/boards/host" in ln)
    assert all(f in board_rule.split() for f in BOARD_FLAGS)
