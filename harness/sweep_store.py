"""A sweep's rows on disk while it runs, and ``ffr sweep --resume``.

Rows are appended to the ``--out`` CSV as each chunk of missions comes back: the header first, then whole
rows, flushed after every chunk, so Ctrl-C, a dead worker or a lost scheduler keeps every finished mission
and the file is a valid CSV at every moment. Beside it, ``FILE.sweep.json`` records the sweep's identity (the
arguments that decide its missions, a digest of the mission list, digests of the files it reads), so that
``--resume FILE`` continues only the sweep that made FILE. A mission's row is keyed by its ``id``, its place
in the sweep's mission list, and checked against its ``replay`` command (candle, seed, noise, settings).
When every mission is in, the file is rewritten in mission order (atomically): byte for byte the file of a
sweep that was never interrupted.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any, TextIO

from harness.atomic import write_bytes_atomic, write_text_atomic

SIDECAR_SUFFIX = ".sweep.json"
FORMAT = "ffr-sweep-rows/1"
_INT_FIELDS = {"id", "room", "seed", "wall_contacts", "jitter_seed"}
_STR_FIELDS = {"noise", "outcome", "detail", "replay"}


class ResumeError(ValueError):
    """FILE cannot be resumed by this sweep (one line, for ``--resume``)."""


def sidecar_path(out: str | Path) -> Path:
    return Path(f"{out}{SIDECAR_SUFFIX}")


def jobs_digest(jobs: Sequence[dict[str, Any]]) -> str:
    """The mission list's fingerprint: any change to a candle, seed or setting changes it."""
    text = json.dumps(list(jobs), sort_keys=True, default=list)
    return hashlib.sha256(text.encode()).hexdigest()


def file_digest(path: str | Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _csv_text(records: Sequence[Sequence[Any]]) -> str:
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")  # the dialect of sweep.write_results' DictWriter
    w.writerows(records)
    return out.getvalue()


class RowStream:
    """Rows appended to a CSV as they arrive: whole rows, one write and a flush per batch."""

    def __init__(self, path: Path, cols: list[str], fh: TextIO) -> None:
        self.path, self.cols, self._fh = path, cols, fh

    @classmethod
    def create(cls, path: str | Path, cols: list[str], identity: dict[str, Any]) -> RowStream:
        """A new file (replacing any old one): the identity sidecar first, then the header."""
        p = Path(path)
        p.parent.mkdir(parents=True, exist_ok=True)
        write_text_atomic(sidecar_path(p), json.dumps({"format": FORMAT} | identity, indent=1) + "\n")
        fh = open(p, "w", encoding="utf-8", newline="")  # noqa: SIM115 - open for the sweep's lifetime
        fh.write(_csv_text([cols]))
        fh.flush()
        return cls(p, cols, fh)

    @classmethod
    def append(cls, path: str | Path, cols: list[str]) -> RowStream:
        """Continue a file ``load_for_resume`` accepted; a row cut short by a killed process is dropped."""
        p = Path(path)
        with open(p, "r+b") as fh:
            data = fh.read()
            if not data.endswith(b"\n"):
                fh.truncate(data.rfind(b"\n") + 1)
        fh2 = open(p, "a", encoding="utf-8", newline="")  # noqa: SIM115 - open for the sweep's lifetime
        if p.stat().st_size == 0:
            fh2.write(_csv_text([cols]))
            fh2.flush()
        return cls(p, cols, fh2)

    def write(self, rows: Sequence[dict[str, Any]]) -> None:
        # one write per batch, so a killed process leaves whole rows (at most the last one cut, see append)
        self._fh.write(_csv_text([["" if r.get(c) is None else r.get(c) for c in self.cols] for r in rows]))
        self._fh.flush()

    def close(self) -> None:
        self._fh.close()

    def on_disk(self) -> int:
        """Missions whose rows are in the file, counted there, so the report after a Ctrl-C (which may land
        between a batch's write and any count kept here) agrees with the file."""
        self.close()  # flushes what was written before the interruption
        return len({rec[0] for rec in _records(self.path)[1:]})


def _records(path: Path) -> list[list[str]]:
    data = path.read_text(encoding="utf-8")
    if data and not data.endswith("\n"):
        data = data[: data.rfind("\n") + 1]  # a row cut short by a killed process: run again
    return list(csv.reader(io.StringIO(data, newline="")))


def load_for_resume(path: str | Path, identity: dict[str, Any], replays: Sequence[str],
                    cols: list[str]) -> list[dict[str, str]]:
    """The rows FILE holds, checked to belong to this sweep (``ResumeError`` otherwise).

    ``replays`` is the ``replay`` command of every mission, by id: a row must carry its mission's.
    """
    p = Path(path)
    if not p.is_file():
        raise ResumeError(f"--resume = {str(path)!r}: no such file")
    side = sidecar_path(p)
    try:
        stored = json.loads(side.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise ResumeError(f"--resume = {str(path)!r}: no {side.name} beside it, so not a file an "
                          "ffr sweep streamed its rows to") from None
    except (OSError, ValueError) as exc:
        raise ResumeError(f"--resume = {str(path)!r}: unreadable {side.name} ({exc})") from None
    if not isinstance(stored, dict) or stored.get("format") != FORMAT:
        raise ResumeError(f"--resume = {str(path)!r}: {side.name} is not an ffr sweep record ({FORMAT})")
    ours = json.loads(json.dumps(identity))  # tuples to lists, as stored
    for key, val in ours.items():
        if stored.get(key) != val:
            why = _difference(key, stored.get(key), val)
            raise ResumeError(f"--resume = {str(path)!r}: made by a different sweep ({why})")
    recs = _records(p)
    if not recs:
        return []
    if recs[0] != cols:
        raise ResumeError(f"--resume = {str(path)!r}: its columns are not this sweep's")
    rows: dict[int, dict[str, str]] = {}
    for lineno, rec in enumerate(recs[1:], start=2):
        ok = len(rec) == len(cols) and rec[0].isdigit() and int(rec[0]) < len(replays)
        if not ok or rec[-1] != replays[int(rec[0])]:
            raise ResumeError(f"--resume = {str(path)!r}: line {lineno} is not a mission of this sweep")
        rows.setdefault(int(rec[0]), dict(zip(cols, rec, strict=True)))  # a mission twice: the first row
    return list(rows.values())


def _difference(key: str, theirs: Any, ours: Any) -> str:
    if key.startswith("-"):
        return f"{key} {json.dumps(theirs)} there, {json.dumps(ours)} here"
    if key == "files":
        return "a file it reads has changed since: " + ", ".join(
            sorted(k for k in set(theirs or {}) | set(ours) if (theirs or {}).get(k) != ours.get(k)))
    return "its missions differ"


def finish(path: str | Path) -> None:
    """Every mission in: rewrite the rows in mission order (atomically), as a sweep without interruption."""
    recs = _records(Path(path))
    by_id: dict[int, list[str]] = {}
    for rec in recs[1:]:
        by_id.setdefault(int(rec[0]), rec)
    write_bytes_atomic(path, _csv_text([recs[0], *(by_id[k] for k in sorted(by_id))]).encode())


def typed_row(rec: dict[str, str]) -> dict[str, Any]:
    """A row read back from the CSV with the types ``sweep.run_job`` gives it (for the summary and plot)."""
    row: dict[str, Any] = {}
    for k, v in rec.items():
        if k == "success":
            row[k] = v == "True"
        elif k in _STR_FIELDS:
            row[k] = v
        elif v == "":
            row[k] = None
        elif k in _INT_FIELDS:
            row[k] = int(v)
        else:
            row[k] = float(v)
    return row
