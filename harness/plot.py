"""Trajectory pictures (the paper's Fig. 15): arena, candle, path coloured by
the firmware's state, wall contacts."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, Polygon  # noqa: E402

from harness.atomic import atomic_path  # noqa: E402
from harness.loop import I_CONTACT, I_STATE, Trace  # noqa: E402
from harness.scenario import Scenario  # noqa: E402
from harness.scoring import MissionResult, seconds_text  # noqa: E402
from harness.state_colors import UNKNOWN_STATE_COLOR, state_colors  # noqa: E402


def draw_mission(ax: plt.Axes, scn: Scenario, trace: Trace, result: MissionResult | None = None) -> None:
    arena = scn.arena
    ax.set_facecolor("#202020")
    for poly in arena.wall_polys:
        ax.add_patch(Polygon(poly, closed=True, color="#d8d8d8", zorder=2))
    for poly in arena.door_polys:
        ax.add_patch(Polygon(poly, closed=True, color="white", zorder=1))
    lw = arena.line_width
    hx, hy = arena.home_center
    ax.add_patch(Circle((hx, hy), arena.home_radius, fill=False, ec="white", lw=lw * 150, zorder=1))
    ax.text(hx, hy, "H", color="white", ha="center", va="center", fontsize=9, zorder=3)
    cx, cy = scn.candle
    ax.add_patch(Circle((cx, cy), arena.candle_circle_radius, fill=False, ec="white", lw=lw * 150, zorder=1))
    ax.plot([cx], [cy], marker="*", color="gold", ms=12, zorder=4)
    for room in arena.rooms:
        c = room.polygon.mean(axis=0)
        ax.text(c[0], c[1], f"{room.id}", color="#808080", fontsize=14, ha="center", va="center", zorder=1)
    xy = trace.xy
    if len(xy) > 1:
        states = trace.i[:, I_STATE]
        change = np.flatnonzero(np.diff(states)) + 1
        starts = np.concatenate([[0], change])
        ends = np.concatenate([change, [len(states)]])
        seen: set[str] = set()
        names = trace.names_of_states()
        colors = state_colors(names)
        for s, e in zip(starts, ends, strict=True):
            name = names[states[s]] if states[s] < len(names) else "?"
            seg = xy[max(s - 1, 0):e]
            label = name if name not in seen else None
            seen.add(name)
            ax.plot(seg[:, 0], seg[:, 1], color=colors.get(name, UNKNOWN_STATE_COLOR), lw=1.6, zorder=5,
                    label=label)
        contact = trace.i[:, I_CONTACT] > 0
        hits = np.flatnonzero(np.diff(contact.astype(np.int8)) > 0) + 1
        if contact[0]:
            hits = np.concatenate([[0], hits])
        if len(hits):
            ax.plot(xy[hits, 0], xy[hits, 1], "x", color="red", ms=10, mew=2.5, zorder=6, label="contact")
        ax.plot(*xy[0], "o", color="white", ms=5, zorder=6)
    title = scn.name
    if result is not None:
        t1 = "-" if result.time_to_extinguish_s is None else f"{seconds_text(result.time_to_extinguish_s)} s"
        t2 = "-" if result.total_time_s is None else f"{seconds_text(result.total_time_s)} s"
        title = f"{scn.name}: {result.outcome}, out {t1}, home {t2}, contacts {result.wall_contacts}"
    ax.set_title(title, fontsize=9)
    ax.set_xlim(-0.02, arena.size[0] + 0.02)
    ax.set_ylim(-0.02, arena.size[1] + 0.02)
    ax.set_aspect("equal")
    ax.tick_params(labelsize=7)


def save_missions(path: str | Path, missions: Sequence[tuple[Scenario, Trace, MissionResult | None]]) -> None:
    """Write one picture with a panel per mission, atomically (no half-written file)."""
    n = len(missions)
    cols = 1 if n == 1 else 2
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.2 * cols, 6.4 * rows), squeeze=False)
    for ax, (scn, trace, res) in zip(axes.flat, missions, strict=False):
        draw_mission(ax, scn, trace, res)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    handles, labels = axes.flat[0].get_legend_handles_labels()
    if handles:
        fig.legend(handles, labels, loc="lower center", ncol=min(6, len(labels)), fontsize=8)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=110, format=Path(path).suffix.lstrip(".") or "png")
    finally:
        plt.close(fig)
