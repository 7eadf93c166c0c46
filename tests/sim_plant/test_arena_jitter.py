"""Arena jitter, arena validation, placement rules per edition and the shipped 2001 arena."""

from __future__ import annotations

import math
import os
import re
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim_plant.arena import DEFAULT_ARENA, load_arena, validate_arena
from sim_plant.arena_jitter import MAX_JITTER, check_jitter, jitter_arena
from sim_plant.errors import CandlePlacementError, FfrInputError

ARENA_2001 = Path(DEFAULT_ARENA).parent / "arena_2001.toml"
ARENAS = {"2004": load_arena(), "2001": load_arena(ARENA_2001)}
HYP = settings(max_examples=60, deadline=None, derandomize=bool(os.environ.get("CI")))


def _coords(arena) -> np.ndarray:
    """Every coordinate the jitter moves, in a fixed order (walls, rooms, doors, candles, hallways, home)."""
    parts = [np.array([[*w.a, *w.b] for w in arena.walls]).ravel()]
    for r in arena.rooms:
        parts += [r.polygon.ravel(), np.array([*r.door[0], *r.door[1], *r.default_candle])]
    parts += [h.polygon.ravel() for h in arena.hallways]
    parts.append(np.array([*arena.home_center, *arena.size]))
    return np.concatenate(parts)


@HYP
@given(name=st.sampled_from(sorted(ARENAS)), tol=st.floats(0.0, MAX_JITTER), seed=st.integers(0, 2**32 - 1))
def test_jittered_arena_is_valid_bounded_and_deterministic(name: str, tol: float, seed: int) -> None:
    base = ARENAS[name]
    a1, warp = jitter_arena(base, tol, np.random.default_rng(seed))
    a2, _ = jitter_arena(base, tol, np.random.default_rng(seed))
    validate_arena(a1)  # closed rooms, doorways with their lines, home in a hallway, default candles legal
    assert np.array_equal(_coords(a1), _coords(a2))  # the same draw, bit for bit
    moved = np.abs(_coords(a1) - _coords(base))
    assert moved.max() <= tol + 1e-12  # nothing moves more than the tolerance
    assert [w.t for w in a1.walls] == [w.t for w in base.walls]  # walls keep their thickness
    assert a1.home_radius == base.home_radius and a1.candle_circle_radius == base.candle_circle_radius
    assert a1.placement == base.placement and a1.home_heading == base.home_heading
    for axis in (0, 1):  # the origin stays at the outer bottom-left corner; the size varies within ±tol
        assert min(min(w.a[axis], w.b[axis]) for w in a1.walls) == 0.0
        assert abs(a1.size[axis] - base.size[axis]) <= tol + 1e-12
    for r0, r1 in zip(base.rooms, a1.rooms, strict=True):  # the default candle is carried with its room
        assert warp.point(r0.default_candle) == r1.default_candle
        assert a1.check_candle(*r1.default_candle).id == r0.id


@pytest.mark.parametrize("name", sorted(ARENAS))
def test_jitter_moves_walls_and_doors_independently(name: str) -> None:
    base = ARENAS[name]
    tol = 0.025
    widths, sizes, lines = [], [], []
    for seed in range(40):
        a, _ = jitter_arena(base, tol, np.random.default_rng(seed))
        widths.append([math.dist(*r.door) for r in a.rooms])
        sizes.append(a.size)
        lines.append([w.a for w in a.walls])
    widths_a, base_w = np.array(widths), np.array([math.dist(*r.door) for r in base.rooms])
    # every door's width varies (its edges move apart and together), within ±2 tol
    assert (widths_a.std(axis=0) > tol / 10).all()
    assert (np.abs(widths_a - base_w) <= 2 * tol + 1e-12).all()
    sizes_a = np.array(sizes)
    assert sizes_a[:, 0].std() > tol / 10 and sizes_a[:, 1].std() > tol / 10
    # the jitter reaches most of its range: shifts near ±tol occur
    d = np.abs(np.array(lines) - np.array([w.a for w in base.walls])[None]).max()
    assert d > 0.8 * tol


def test_zero_jitter_is_the_arena_itself() -> None:
    base = ARENAS["2004"]
    a, warp = jitter_arena(base, 0.0, np.random.default_rng(1))
    assert a is base and warp.point((1.234, 0.5)) == (1.234, 0.5)


@pytest.mark.parametrize("tol", [-0.001, MAX_JITTER + 1e-6, math.nan, math.inf, True])
def test_jitter_out_of_range_refused(tol: float) -> None:
    with pytest.raises(FfrInputError, match="arena_jitter"):
        check_jitter(ARENAS["2004"], tol)


def test_slanted_walls_cannot_be_jittered(tmp_path: Path) -> None:
    text = ARENAS_TEXT_2004.replace('name = "br_left"\na = [1.21, 0.02]', 'name = "br_left"\na = [1.22, 0.02]')
    p = tmp_path / "slanted.toml"
    p.write_text(text, encoding="utf-8")
    arena = load_arena(p)
    with pytest.raises(FfrInputError, match="axis-parallel"):
        jitter_arena(arena, 0.01, np.random.default_rng(0))
    jitter_arena(arena, 0.0, np.random.default_rng(0))  # no jitter: any arena


def test_candle_carried_and_kept_legal() -> None:
    """A candle near the edge of the legal region: draws that would make it illegal are drawn again."""
    base = ARENAS["2004"]
    nominal = (0.60, 0.75)  # room 3, just beside the 33 cm entry zone
    base.check_candle(*nominal)
    for seed in range(30):
        a, warp = jitter_arena(base, MAX_JITTER, np.random.default_rng(seed), candle=nominal)
        assert a.check_candle(*warp.point(nominal)).id == 3


# -- validation -----------------------------------------------------------------

ARENAS_TEXT_2004 = Path(DEFAULT_ARENA).read_text(encoding="utf-8")


def _load_text(tmp_path: Path, text: str):
    p = tmp_path / "a.toml"
    p.write_text(text, encoding="utf-8")
    return load_arena(p)


def test_room_without_its_wall_refused(tmp_path: Path) -> None:
    text = ARENAS_TEXT_2004.replace('name = "br_left"\na = [1.21, 0.02]\nb = [1.21, 0.46]',
                                    'name = "br_left"\na = [1.21, 0.02]\nb = [1.21, 0.30]')
    # the first point found open walking the room's polygon (3 mm outside its west side, x = 1.22 m),
    # in plain numbers (no numpy reprs)
    with pytest.raises(FfrInputError, match=r"rooms\[3\]\.polygon = \[1\.217, 0\.41\]: room 4 is not closed"):
        _load_text(tmp_path, text)


def test_blocked_doorway_refused(tmp_path: Path) -> None:
    text = ARENAS_TEXT_2004.replace('name = "tl_bottom"\na = [0.48, 1.87]', 'name = "tl_bottom"\na = [0.02, 1.87]')
    with pytest.raises(FfrInputError, match=r"rooms\[1\]\.door.*blocked"):
        _load_text(tmp_path, text)


def test_home_in_a_room_refused(tmp_path: Path) -> None:
    text = ARENAS_TEXT_2004.replace("center = [2.11, 1.17]", "center = [1.5, 1.6]")
    with pytest.raises(FfrInputError, match=r"home\.center.*hallway"):
        _load_text(tmp_path, text)


@pytest.mark.parametrize(("old", "new", "needle"), [
    ('placement = "entry-depth"', 'placment = "door-line"', "arena.placment"),
    ("[home]\n", "[home]\nheading = 180\n", "home.heading"),
    ('name = "br_left"\n', 'name = "br_left"\nthick = 0.02\n', "walls[13].thick"),
])
def test_unknown_arena_field_refused(tmp_path: Path, old: str, new: str, needle: str) -> None:
    assert old in ARENAS_TEXT_2004
    with pytest.raises(FfrInputError, match=re.escape(needle) + ".*unknown field"):
        _load_text(tmp_path, ARENAS_TEXT_2004.replace(old, new, 1))


def test_unknown_placement_rule_refused(tmp_path: Path) -> None:
    text = ARENAS_TEXT_2004.replace('placement = "entry-depth"', 'placement = "2099"')
    with pytest.raises(FfrInputError, match=r"arena\.placement = '2099'.*entry-depth, door-line"):
        _load_text(tmp_path, text)


# -- placement rules by edition, and the 2001 arena ------------------------------------

def test_2001_arena_from_its_plan() -> None:
    a = ARENAS["2001"]
    inch = 0.0254
    assert a.size == pytest.approx((98 * inch, 98 * inch))
    assert a.home_center == pytest.approx((89.8 * inch, 46.0 * inch))
    assert math.degrees(a.home_heading) == pytest.approx(180.0)
    assert a.home_radius == pytest.approx(6 * inch) and a.candle_circle_radius == pytest.approx(6 * inch)
    targets = {1: (71.4, 65.15), 2: (23.1, 82.3), 3: (15, 39), 4: (87.1, 10.9)}  # F2, F4, F1, F3
    for rid, (x, y) in targets.items():
        assert a.room(rid).default_candle == pytest.approx((x * inch, y * inch))
    assert a.placement == "door-line"
    door = {r.id: math.dist(*r.door) / inch for r in a.rooms}
    assert door[1] == pytest.approx(70.5 - 49.375)  # the island room's 21 in door (the widest of the plans)


@pytest.mark.parametrize(("rid", "refused"), [(1, True), (2, True), (3, False), (4, False)])
def test_2001_targets_under_each_rule(rid: int, refused: bool) -> None:
    """The 2001 plan's own targets F2 (island, beside its door) and F4 (top left) break the later
    33 cm entry rule; the plan's door-line rule takes all four."""
    a = load_arena(ARENA_2001)
    xy = a.room(rid).default_candle
    assert a.check_candle(*xy).id == rid
    a.placement = "entry-depth"
    if refused:
        with pytest.raises(CandlePlacementError) as exc:
            a.check_candle(*xy)
        assert exc.value.rule == "entry-depth"
    else:
        assert a.check_candle(*xy).id == rid


def test_door_line_rule_still_keeps_the_circle_off_the_doorway_line() -> None:
    a = load_arena(ARENA_2001)
    (ax, ay), (bx, by) = a.room(1).door
    with pytest.raises(CandlePlacementError) as exc:
        a.check_candle((ax + bx) / 2, ay - 0.10)
    assert exc.value.rule == "circle-touches-doorway"


def _room_gap_by_definition(polys: np.ndarray, rm, reach: float, step: float = 0.01,
                            off: float = 0.003) -> tuple[float, float] | None:
    """The closure check as its docs define it, point by point in Python (the compiled pass must
    agree): walking each side of the room's polygon, points 1 cm apart and 3 mm outside it, the first
    in no wall and farther than `reach` from the doorway line."""
    from sim_plant.geometry import point_in_convex, point_segment_distance

    poly = rm.polygon
    (ax, ay), (bx, by) = rm.door
    for i in range(poly.shape[0]):
        p, q = poly[i], poly[(i + 1) % poly.shape[0]]
        ex, ey = q[0] - p[0], q[1] - p[1]
        length = math.hypot(ex, ey)
        m = max(2, int(length / step))
        for j in range(1, m):
            x, y = p[0] + ex * (j / m) + ey / length * off, p[1] + ey * (j / m) - ex / length * off
            if not any(point_in_convex(x, y, wp) for wp in polys) and \
                    point_segment_distance(x, y, ax, ay, bx, by) > reach:
                return x, y
    return None


@pytest.mark.parametrize("path", [DEFAULT_ARENA, str(Path(DEFAULT_ARENA).with_name("arena_2001.toml"))])
def test_the_closure_check_finds_the_point_its_definition_finds(path: str) -> None:
    # each shipped arena and three 5 cm jitters of it, with every wall left out in turn: open rooms
    # and closed ones, the same first open point to the bit
    from types import SimpleNamespace

    from sim_plant.arena import _room_gap

    base = load_arena(path)
    arenas = [base] + [jitter_arena(base, 0.05, np.random.default_rng(s))[0] for s in range(3)]
    opened = 0
    for a in arenas:
        reach = max(w.t for w in a.walls) + a.line_width
        for drop in [None, *range(len(a.walls))]:
            polys = a.wall_polys if drop is None else np.delete(a.wall_polys, drop, axis=0)
            for rm in a.rooms:
                want = _room_gap_by_definition(polys, rm, reach)
                assert _room_gap(SimpleNamespace(wall_polys=polys), rm, reach) == want
                opened += want is not None
    assert opened > 0  # some walls left out open a room: both answers are tried
