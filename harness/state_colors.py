"""One colour per firmware state, for every picture of a mission: the 2D plot (harness/plot.py)
and the 3D replay (harness/replay/) read alike. Matplotlib's tab10 hues where they fit."""

from __future__ import annotations

STATE_COLORS: dict[str, str] = {
    "IDLE": "#aaaaaa", "FOLLOW": "#1f77b4", "TURN": "#9467bd", "FORWARD": "#17becf", "ENTER": "#2ca02c",
    "SCAN": "#bcbd22", "APPROACH": "#ff7f0e", "EXTINGUISH": "#d62728", "VERIFY": "#8c564b",
    "TO_DOOR": "#e377c2", "EXIT": "#7f7f7f", "HOMING": "#393b79", "DONE": "#ffffff", "FAILED": "#ff0000",
    "ORIENT": "#f7b6d2",
}
UNKNOWN_STATE_COLOR = "#ffffff"  # a library with states of its own (docs/architecture.md, ABI check)
