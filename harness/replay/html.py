"""Write a replay as one self-contained HTML file.

The page is Plotly (plotly.js inlined from the pinned ``plotly`` Python
package, so nothing is fetched at viewing time), the mission's numbers as one
JSON block, and our small player script (``replay.js``) that moves the robot,
beams, fans and flame and the charts' cursor. See docs/replay.md.
"""

from __future__ import annotations

import json
import re
from importlib import resources
from pathlib import Path

from harness.atomic import write_text_atomic
from harness.loop import Trace
from harness.replay.data import DEFAULT_CHART_HZ, DEFAULT_FPS, ReplayData, build_replay
from harness.scenario import Scenario
from harness.scoring import MissionResult

_MARK_JS_LIB = "/*FFR:PLOTLY_JS*/"
_MARK_DATA = "/*FFR:DATA*/"
_MARK_PLAYER = "/*FFR:PLAYER_JS*/"
_MARK_CSS = "/*FFR:CSS*/"
_MARK_TITLE = "FFR:TITLE"


def _asset(name: str) -> str:
    return (resources.files("harness.replay") / name).read_text(encoding="utf-8")


def plotly_js() -> str:
    """plotly.js as shipped in the pinned Python package (no network)."""
    from plotly.offline import get_plotlyjs

    js = get_plotlyjs()
    if "</script" in js.lower():  # would end our inline <script> early
        raise RuntimeError("plotly.js contains '</script': cannot be inlined")
    return js


def _json_for_script(obj: object) -> str:
    # "</script" or "<!--" inside a <script> block would end or confuse it; "\u003c" is the same JSON string.
    text = json.dumps(obj, separators=(",", ":"), allow_nan=False, ensure_ascii=True)
    return text.replace("<", "\\u003c")


def _escape_html(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;").replace('"', "&quot;")


def render_html(data: ReplayData) -> str:
    """The whole page as text; the same data gives the same bytes."""
    m = data.meta
    title = f"ffr replay: {m['scenario']} ({m['outcome']})"
    parts = {
        _MARK_TITLE: _escape_html(title),
        _MARK_CSS: _asset("replay.css"),
        _MARK_PLAYER: _asset("replay.js"),
        _MARK_DATA: _json_for_script(data.to_json()),
        _MARK_JS_LIB: plotly_js(),
    }
    # One pass over the template, so text put in (a scenario name, say) is never scanned for markers.
    pattern = "|".join(re.escape(k) for k in parts)
    return re.sub(pattern, lambda mt: parts[mt.group(0)], _asset("template.html"))


def write_html(path: str | Path, text: str) -> None:
    # a replay is for sharing: readable by all, whatever the umask
    write_text_atomic(path, text, mode=0o644)


def save_replay(path: str | Path, scn: Scenario, trace: Trace, result: MissionResult,
                fps: float = DEFAULT_FPS, chart_hz: float = DEFAULT_CHART_HZ) -> ReplayData:
    """Build and write one mission's replay; returns the data that was embedded."""
    data = build_replay(scn, trace, result, fps=fps, chart_hz=chart_hz)
    write_html(path, render_html(data))
    return data
