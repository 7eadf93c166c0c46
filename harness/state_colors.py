"""One colour per firmware state, for every picture of a mission: the 2D plot (harness/plot.py)
and the 3D replay (harness/replay/) read alike. The state names are the firmware's own
(``ffr_names``, docs/contract.md): our firmware's states have the colours below (matplotlib's tab10
hues where they fit); a state this table does not know gets the next colour of a fixed palette, in
the order of the firmware's state codes, so a firmware's pictures look the same every time."""

from __future__ import annotations

from collections.abc import Sequence

STATE_COLORS: dict[str, str] = {
    "IDLE": "#aaaaaa", "FOLLOW": "#1f77b4", "TURN": "#9467bd", "FORWARD": "#17becf", "ENTER": "#2ca02c",
    "SCAN": "#bcbd22", "APPROACH": "#ff7f0e", "EXTINGUISH": "#d62728", "VERIFY": "#8c564b",
    "TO_DOOR": "#e377c2", "EXIT": "#7f7f7f", "HOMING": "#393b79", "DONE": "#ffffff", "FAILED": "#ff0000",
    "ORIENT": "#f7b6d2",
}
# For states of other firmwares (tab20's lighter hues and a few more, none of them above).
PALETTE: tuple[str, ...] = (
    "#aec7e8", "#ffbb78", "#98df8a", "#ff9896", "#c5b0d5", "#c49c94", "#dbdb8d", "#9edae5",
    "#637939", "#8c6d31", "#843c39", "#7b4173", "#5254a3", "#e7ba52", "#6b6ecf", "#cedb9c",
)
UNKNOWN_STATE_COLOR = "#ffffff"  # a state code beyond the firmware's names


def state_colors(names: Sequence[str]) -> dict[str, str]:
    """Name -> colour for a firmware's state names (index = state code): ours from STATE_COLORS,
    the rest from PALETTE in code order (cycling past its end)."""
    out: dict[str, str] = {}
    k = 0
    for name in names:
        if name in out:
            continue
        if name in STATE_COLORS:
            out[name] = STATE_COLORS[name]
        else:
            out[name] = PALETTE[k % len(PALETTE)]
            k += 1
    return out
