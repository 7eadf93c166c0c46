"""Arena file, candle placement rules and random legal candles."""

from __future__ import annotations

import numpy as np
import pytest

from sim_plant.arena import DEFAULT_ARENA, load_arena
from sim_plant.errors import CandlePlacementError, FfrInputError


def test_default_arena_shape(arena) -> None:
    assert arena.size == (2.44, 2.44)
    assert arena.wall_height == pytest.approx(0.33)
    assert [r.id for r in arena.rooms] == [1, 2, 3, 4]
    assert arena.line_width == pytest.approx(0.025)
    # every hallway is 46 cm wide somewhere (the contest's hallway width)
    widths = [min(np.ptp(h.polygon[:, 0]), np.ptp(h.polygon[:, 1])) for h in arena.hallways]
    assert all(w == pytest.approx(0.46, abs=0.005) for w in widths)
    hx, hy = arena.home_center
    assert arena.in_hallway(hx, hy)


@pytest.mark.parametrize("room_id", [1, 2, 3, 4])
def test_default_candles_are_legal_and_in_their_room(arena, room_id: int) -> None:
    room = arena.room(room_id)
    assert arena.check_candle(*room.default_candle).id == room_id


def test_legal_candle_accepted(arena) -> None:
    assert arena.check_candle(2.30, 0.14).name == "BR"
    # just inside a doorway's room but beside the door, clear of the entry zone
    assert arena.check_candle(0.60, 0.75).name == "BL"


@pytest.mark.parametrize(
    ("xy", "rule"),
    [
        ((1.0, 1.0), "in-hallway"),          # the corridor
        ((2.2, 1.17), "in-hallway"),         # by the home circle
        ((0.73, 2.0), "outside-rooms"),      # inside the wall between room 2 and the corridor
        ((0.025, 0.5), "in-wall"),           # candle body overlapping the outer wall
        ((1.35, 0.69), "circle-touches-doorway"),  # right behind room 4's doorway line
        ((1.62, 0.69), "entry-depth"),       # 41 cm in front of room 4's door: circle within 33 cm
    ],
)
def test_illegal_candles_refused_naming_the_rule(arena, xy, rule: str) -> None:
    with pytest.raises(CandlePlacementError) as exc:
        arena.check_candle(*xy)
    assert exc.value.rule == rule
    assert rule in str(exc.value)
    assert "\n" not in str(exc.value)


def test_random_candles_are_legal_in_room_and_seeded(arena) -> None:
    for room in arena.rooms:
        pts = [arena.random_candle(room.id, np.random.default_rng(7)) for _ in range(2)]
        assert pts[0] == pts[1]  # same seed, same draw
        rng = np.random.default_rng(3)
        for _ in range(40):
            x, y = arena.random_candle(room.id, rng)
            assert arena.check_candle(x, y).id == room.id


def test_random_candles_cover_the_room(arena) -> None:
    rng = np.random.default_rng(0)
    room = arena.room(4)
    xs = np.array([arena.random_candle(4, rng) for _ in range(300)])
    lo, hi = room.polygon.min(axis=0), room.polygon.max(axis=0)
    # uniform over the legal area: spread over most of the room's extent
    assert np.ptp(xs[:, 0]) > 0.8 * (hi[0] - lo[0])
    assert np.ptp(xs[:, 1]) > 0.8 * (hi[1] - lo[1])


def _write(tmp_path, text: str):
    p = tmp_path / "arena.toml"
    p.write_text(text)
    return p


def test_bad_arena_file_names_file_field_value(tmp_path) -> None:
    src = DEFAULT_ARENA.read_text()
    p = _write(tmp_path, src.replace("wall_height = 0.33", 'wall_height = "tall"'))
    with pytest.raises(FfrInputError) as exc:
        load_arena(p)
    msg = str(exc.value)
    assert str(p) in msg and "arena.wall_height" in msg and "'tall'" in msg and "\n" not in msg


@pytest.mark.parametrize(
    ("old", "new", "field"),
    [
        ("t = 0.02\n", "t = -0.02\n", "walls[0].t"),
        ("center = [2.11, 1.17]", "center = [2.11]", "home.center"),
        ("id = 2\n", "id = 1\n", "rooms[1].id"),
        ("default_candle = [1.83, 1.53]", "default_candle = [1.45, 1.8]", "rooms[0].default_candle"),
    ],
)
def test_bad_arena_fields(tmp_path, old: str, new: str, field: str) -> None:
    src = DEFAULT_ARENA.read_text()
    assert old in src
    p = _write(tmp_path, src.replace(old, new, 1))
    with pytest.raises(FfrInputError) as exc:
        load_arena(p)
    assert field in str(exc.value)
    assert str(p) in str(exc.value)


def test_unreadable_and_malformed_files(tmp_path) -> None:
    with pytest.raises(FfrInputError, match="missing.toml"):
        load_arena(tmp_path / "missing.toml")
    p = _write(tmp_path, "[arena\nname=")
    with pytest.raises(FfrInputError, match="syntax"):
        load_arena(p)
