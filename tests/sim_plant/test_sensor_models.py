"""Issue 12's sensor and world models (sim_plant/sensors/models.py), each against a hand
calculation written here: the GP2D12's beam, latency and per-part timing; the candle's base
as a ranger target and an obstacle; the flame's strength, flicker, reflections, afterglow and
other infrared sources."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from sim_plant.arena import Arena, load_arena
from sim_plant.candle import Candle
from sim_plant.geometry import edges_soa
from sim_plant.robot import IR_NAMES, load_robot
from sim_plant.sensors import NoiseProfile, SensorSuite, new_output
from sim_plant.sensors.flame_sensor import INTENSITY_COEFF, flame_k, point_fc, reflected_fc
from sim_plant.sensors.gp2d12 import MEASUREMENT_PERIOD, beam_distance, ir_ray_distance, ray_circle
from sim_plant.sensors.models import (
    GP2D12_PERIOD_SPREAD,
    FlameWorld,
    RangerModel,
    draw_flame,
    draw_ranger_timing,
    flicker,
)

NO_POLYS = np.zeros((0, 4, 2))


def _wall_edges(*segs: tuple[float, float, float, float]) -> np.ndarray:
    return np.array(segs, dtype=np.float64)


# -- GP2D12 beam -----------------------------------------------------------------

@pytest.mark.parametrize("d", [0.12, 0.3, 0.55, 0.8])
def test_one_ray_beam_is_the_old_single_ray(arena: Arena, d: float) -> None:
    for (px, py, a) in [(0.3, 0.5, 0.0), (1.0, 1.0, 2.1), (2.0, 0.3, -0.7)]:
        dx, dy = math.cos(a), math.sin(a)
        old = ir_ray_distance(px, py, dx, dy, arena.wall_edges, arena.wall_polys, 4.0)
        assert beam_distance(px, py, dx, dy, 0.0, 5, arena.wall_edges, arena.wall_polys, 4.0,
                             0.0, 0.0, 0.0) == old
        assert beam_distance(px, py, dx, dy, 0.05, 1, arena.wall_edges, arena.wall_polys, 4.0,
                             0.0, 0.0, 0.0) == old


@pytest.mark.parametrize("half_deg", [0.5, 2.0, 5.0, 10.0])
@pytest.mark.parametrize("n", [2, 3, 5, 9])
def test_beam_on_a_flat_wall(half_deg: float, n: int) -> None:
    """A wall across the aim at D: ray j at offset o_j hits at D / cos o_j, and the
    detector's centroid is 1/d = sum(cos^3 o_j) / sum(cos^2 o_j) / D (hand calculation)."""
    D = 0.4
    edges = _wall_edges((D, -5.0, D, 5.0))
    h = math.radians(half_deg)
    offs = [-h + 2 * h * j / (n - 1) for j in range(n)]
    want = D * sum(math.cos(o) ** 2 for o in offs) / sum(math.cos(o) ** 3 for o in offs)
    got = beam_distance(0.0, 0.0, 1.0, 0.0, h, n, edges, NO_POLYS, 4.0, 0.0, 0.0, 0.0)
    assert got == pytest.approx(want, rel=1e-12)
    assert D < got <= D / math.cos(h) * (1 + 1e-12)


@pytest.mark.parametrize("frac", [1, 2, 3, 4])
def test_beam_on_a_door_jamb_blurs_between_near_and_far(frac: int) -> None:
    """Rays split between a jamb at d1 and the far wall at d2 (5 rays, ``frac`` on the jamb):
    the reading is 1/d = (k/d1^3 + (5-k)/d2^3) / (k/d1^2 + (5-k)/d2^2), weighted to the near one.
    The rays' own lengths are the hit points' x / cos(offset); with a tiny half-angle the
    offsets are negligible and the formula is checked to 1e-5."""
    d1, d2 = 0.25, 0.70
    h = math.radians(0.01)
    # a jamb below the axis (rays with negative offset hit it)
    offs = [-h + 2 * h * j / 4 for j in range(5)]
    y_cut = 0.5 * (d1 * math.tan(offs[frac - 1]) + d1 * math.tan(offs[frac]))
    edges = _wall_edges((d1, -1.0, d1, y_cut), (d2, -1.0, d2, 1.0))
    got = beam_distance(0.0, 0.0, 1.0, 0.0, h, 5, edges, NO_POLYS, 4.0, 0.0, 0.0, 0.0)
    k = frac
    want = (k / d1**2 + (5 - k) / d2**2) / (k / d1**3 + (5 - k) / d2**3)
    assert got == pytest.approx(want, rel=1e-5)
    assert d1 < got < d2


def test_ray_circle_hand_cases() -> None:
    # straight at a disc of radius 0.04 centred 0.5 m ahead: hits at 0.46
    assert ray_circle(0.0, 0.0, 1.0, 0.0, 0.5, 0.0, 0.04, 4.0) == pytest.approx(0.46)
    # offset by y = 0.03: t = 0.5 - sqrt(0.04^2 - 0.03^2)
    assert ray_circle(0.0, 0.0, 1.0, 0.0, 0.5, 0.03, 0.04, 4.0) == pytest.approx(0.5 - math.sqrt(7e-4))
    assert ray_circle(0.0, 0.0, 1.0, 0.0, 0.5, 0.05, 0.04, 4.0) == 4.0  # misses
    assert ray_circle(0.0, 0.0, -1.0, 0.0, 0.5, 0.0, 0.04, 4.0) == 4.0  # behind
    assert ray_circle(0.49, 0.0, 1.0, 0.0, 0.5, 0.0, 0.04, 4.0) == 0.0  # inside


def test_candle_base_is_a_ranger_target_nearer_than_the_wall() -> None:
    edges = _wall_edges((1.0, -1.0, 1.0, 1.0))
    d = beam_distance(0.0, 0.0, 1.0, 0.0, 0.0, 1, edges, NO_POLYS, 4.0, 0.6, 0.0, 0.04)
    assert d == pytest.approx(0.56)
    assert beam_distance(0.0, 0.0, 1.0, 0.0, 0.0, 1, edges, NO_POLYS, 4.0, 0.6, 0.0, 0.0) == 1.0


# -- GP2D12 timing ------------------------------------------------------------------

def _suite(noise: NoiseProfile, seed: int = 0, arena: Arena | None = None,
           candle_xy: tuple[float, float] | None = None,
           sources: np.ndarray | None = None) -> SensorSuite:
    arena = arena or load_arena()
    robot = load_robot()
    xy = candle_xy or arena.room(1).default_candle
    return SensorSuite(arena, robot, Candle(*xy, robot, arena), noise, np.random.default_rng(seed),
                       ir_sources=sources)


@pytest.mark.parametrize("seed", range(20))
def test_per_part_period_and_phase_within_the_datasheet(seed: int) -> None:
    prof = NoiseProfile(ranger=RangerModel(period_spread=GP2D12_PERIOD_SPREAD, random_phase=True))
    s = _suite(prof, seed)
    per, ph = s.ir_periods, s.ir_phases
    assert np.all(per >= 0.0383 - 0.0096) and np.all(per <= 0.0383 + 0.0096)
    assert np.all(ph >= 0.0) and np.all(ph < per)
    assert len(set(per.tolist())) == len(IR_NAMES)  # each part its own


def test_period_draws_are_uniform_over_the_whole_range() -> None:
    rng = np.random.default_rng(3)
    m = RangerModel(period_spread=GP2D12_PERIOD_SPREAD)
    per = np.concatenate([draw_ranger_timing(m, MEASUREMENT_PERIOD, [0.0] * 5, rng)[0]
                          for _ in range(2000)])
    assert per.min() < 0.0383 - 0.0096 + 0.0005 and per.max() > 0.0383 + 0.0096 - 0.0005
    assert abs(per.mean() - 0.0383) < 0.0005


def test_no_model_draws_nothing() -> None:
    rng = np.random.default_rng(1)
    before = rng.bit_generator.state
    draw_ranger_timing(RangerModel(beam_half_angle_deg=2.0, latency=True), 0.0383, [0.0] * 5, rng)
    draw_flame(FlameWorld(wall_reflectance=0.5, afterglow_s=0.3), rng)
    assert rng.bit_generator.state == before


def _ir_cf_readings(s: SensorSuite, poses: list[tuple[float, float, float]]) -> list[int]:
    out = new_output()
    got = []
    for k, (x, y, th) in enumerate(poses):
        s.sample(k * 0.01, x, y, th, 0.0, 0.0, out)
        got.append(int(out[0]))
    return got


def test_latency_shows_each_measurement_one_period_late() -> None:
    """A robot facing a wall jumps closer once: without latency the CF reading changes at the
    first measurement after the jump; with latency, one measurement later (and then holds)."""
    arena = load_arena()
    # room-free spot in the east hallway, facing the right outer wall (x inside = 2.42)
    poses = [(2.0, 1.17, 0.0)] * 5 + [(2.2, 1.17, 0.0)] * 20
    per = 0.04  # with 10 ms ticks: measurements at ticks 0, 4, 8, 12, ...
    from sim_plant.sensors.gp2d12 import Gp2d12Model
    plain = SensorSuite(arena, load_robot(), Candle(*arena.room(1).default_candle, load_robot(), arena),
                        NoiseProfile(ranger=RangerModel(latency=False)),
                        ir_model=Gp2d12Model(period=per, stagger=False))
    late = SensorSuite(arena, load_robot(), Candle(*arena.room(1).default_candle, load_robot(), arena),
                       NoiseProfile(ranger=RangerModel(latency=True)),
                       ir_model=Gp2d12Model(period=per, stagger=False))
    a = _ir_cf_readings(plain, poses)
    b = _ir_cf_readings(late, poses)
    far, near = a[0], a[-1]
    assert near > far
    # the jump happens at tick 5; the next measurement is tick 8, the one after tick 12
    assert a[:8] == [far] * 8 and a[8:] == [near] * (len(a) - 8)
    assert b[:12] == [far] * 12 and b[12:] == [near] * (len(b) - 12)


# -- the candle as an obstacle ------------------------------------------------------------

def _arena_with_base(r: float) -> Arena:
    return dataclasses.replace(load_arena(), candle_base_radius=r)


def test_footprint_touch_knocks_the_candle_over() -> None:
    """Robot at the origin facing +x, front face at 0.12 m, half width 0.10 m, base r 0.04:
    a candle 0.1599 m ahead on the axis touches (0.12 + 0.04), 0.1601 m does not; a candle
    off the front corner touches when its distance to the corner (0.12, 0.10) is <= r."""
    robot = load_robot()
    arena = _arena_with_base(0.04)
    f, _, hw, _ = robot.footprint()
    assert (f, hw) == (0.12, 0.10)
    assert Candle(0.1599, 0.0, robot, arena).touches(0.0, 0.0, 0.0)
    assert not Candle(0.1601, 0.0, robot, arena).touches(0.0, 0.0, 0.0)
    c = 0.04 / math.sqrt(2.0)
    assert Candle(0.12 + c - 1e-9, 0.10 + c - 1e-9, robot, arena).touches(0.0, 0.0, 0.0)
    assert not Candle(0.12 + c + 1e-4, 0.10 + c + 1e-4, robot, arena).touches(0.0, 0.0, 0.0)
    # the same candle seen from a robot turned by 90 degrees and moved: body frame again
    assert Candle(1.0, 1.1599, robot, arena).touches(1.0, 1.0, math.pi / 2)
    assert not Candle(1.0, 1.1601, robot, arena).touches(1.0, 1.0, math.pi / 2)
    assert not _knock(Candle(0.13, 0.0, robot, _arena_with_base(0.0)))  # no base: never


def _knock(c: Candle) -> bool:
    c.update(0.01, 0.01, False, 0.0, 0.0, 0.0)
    return c.knocked


@pytest.mark.parametrize("lit", [True, False])
def test_knocked_whether_lit_or_out(lit: bool) -> None:
    c = Candle(0.15, 0.0, load_robot(), _arena_with_base(0.04))  # 0.03 m into the base
    c.lit = lit
    assert _knock(c)


# -- flame -----------------------------------------------------------------------

def test_flicker_formula_and_bounds() -> None:
    for amp in (0.0, 0.1, 0.3):
        v = np.array([flicker(t, amp, 1.5, 0.3, 1.1) for t in np.linspace(0, 20, 4001)])
        assert np.all(v >= 1 - amp - 1e-12) and np.all(v <= 1 + amp + 1e-12)
        if amp:
            assert v.max() - v.min() > amp  # it does vary
    t = 0.37
    w = 2 * math.pi * 1.5 * t
    assert flicker(t, 0.2, 1.5, 0.3, 1.1) == pytest.approx(
        1 + 0.2 * (0.6 * math.sin(w + 0.3) + 0.4 * math.sin(2.7 * w + 1.1)))


@pytest.mark.parametrize("seed", range(30))
def test_strength_drawn_within_the_range(seed: int) -> None:
    s, p1, p2 = draw_flame(FlameWorld(strength_min=0.6, strength_max=1.4, flicker_amp=0.1),
                           np.random.default_rng(seed))
    assert 0.6 <= s <= 1.4 and 0 <= p1 < 2 * math.pi and 0 <= p2 < 2 * math.pi


def test_image_source_reflection_hand_calculation() -> None:
    """One wall face along y = 0 (outward normal +y: the edge runs from +x to -x, counter-
    clockwise around a wall below), sensor at (0, 0.2) aimed at -y... the hand calculation:
    source at (0.4, 0.1) mirrors to (0.4, -0.1); sensor-to-image vector (0.4, -0.3), length
    0.5 (3-4-5), angle off an aim of atan2(-0.3, 0.4): 0 -> K = 1; I = 0.0125 / 0.25."""
    edges = _wall_edges((5.0, 0.0, -5.0, 0.0))
    aim = math.atan2(-0.3, 0.4)
    got = reflected_fc(0.0, 0.2, 0.18, aim, 0.4, 0.1, 0.18, edges, math.radians(60), 0.02)
    assert got == pytest.approx(INTENSITY_COEFF / 0.25)
    # aimed 30 degrees away: K = 0.5
    got30 = reflected_fc(0.0, 0.2, 0.18, aim + math.radians(30), 0.4, 0.1, 0.18, edges,
                         math.radians(60), 0.02)
    assert got30 == pytest.approx(0.5 * INTENSITY_COEFF / 0.25)
    # a face seen from behind reflects nothing; a blocking wall in a leg removes it
    back = _wall_edges((-5.0, 0.0, 5.0, 0.0))
    assert reflected_fc(0.0, 0.2, 0.18, aim, 0.4, 0.1, 0.18, back, math.radians(60), 0.02) == 0.0
    blocked = np.vstack([edges, _wall_edges((0.1, -1.0, 0.1, 1.0))])
    assert reflected_fc(0.0, 0.2, 0.18, aim, 0.4, 0.1, 0.18, blocked, math.radians(60), 0.02) == 0.0
    # the direct light of the same source, for the same sensor: K(dθ) / r^2
    d_aim = math.atan2(-0.1, 0.4)
    assert point_fc(0.0, 0.2, 0.18, d_aim, 0.4, 0.1, 0.18, edges_soa(edges), math.radians(60),
                    0.02) == \
        pytest.approx(INTENSITY_COEFF * flame_k(0.0, math.radians(60)) / 0.17)


def _flame_reading(s: SensorSuite, t: float, pose: tuple[float, float, float]) -> tuple[float, float]:
    out = new_output()
    s.sample(t, *pose, 0.0, 0.0, out)
    return s.flame_fc


def test_reflectance_adds_light_in_proportion() -> None:
    """In the arena with the candle in room 1's corner, a robot in that room: the reflected
    part scales linearly with the reflectance (fc(ρ) - fc(0) = ρ (fc(1) - fc(0)))."""
    arena = load_arena()
    cx, cy = arena.room(1).default_candle
    pose = (cx - 0.35, cy + 0.05, 0.0)
    vals = [_flame_reading(_suite(NoiseProfile(flame_world=FlameWorld(wall_reflectance=r))), 0.0,
                           pose) for r in (0.0, 0.3, 1.0)]
    base, mid, full = (np.array(v) for v in vals)
    assert np.all(full > base)
    assert np.allclose(mid - base, 0.3 * (full - base), rtol=1e-12)


def test_afterglow_decays_exponentially_then_is_gone() -> None:
    arena = load_arena()
    cx, cy = arena.room(1).default_candle
    pose = (cx - 0.3, cy, 0.0)
    tau = 0.5
    s = _suite(NoiseProfile(flame_world=FlameWorld(afterglow_s=tau)))
    lit = _flame_reading(s, 0.0, pose)[0]
    assert lit > 0
    s.candle.lit = False
    assert _flame_reading(s, 1.0, pose)[0] == pytest.approx(lit)  # goes out at t = 1.0
    assert _flame_reading(s, 1.25, pose)[0] == pytest.approx(lit * math.exp(-0.5))
    assert _flame_reading(s, 2.0, pose)[0] == pytest.approx(lit * math.exp(-2.0))
    assert _flame_reading(s, 1.0 + 10 * tau + 0.01, pose)[0] == 0.0
    s2 = _suite(NoiseProfile())
    _flame_reading(s2, 0.0, pose)
    s2.candle.lit = False
    assert _flame_reading(s2, 1.0, pose)[0] == 0.0  # default: out at once


def test_strength_and_flicker_scale_the_direct_light() -> None:
    arena = load_arena()
    cx, cy = arena.room(1).default_candle
    pose = (cx - 0.3, cy, 0.0)
    ref = _flame_reading(_suite(NoiseProfile()), 0.5, pose)[0]
    fw = FlameWorld(strength_min=0.6, strength_max=1.4, flicker_amp=0.2, flicker_hz=1.5)
    for seed in range(5):
        s = _suite(NoiseProfile(flame_world=fw), seed)
        # no noise, no unit spread, no ranger draws: the flame's draws are the seed's first
        strength, p1, p2 = draw_flame(fw, np.random.default_rng(seed))
        assert s.flame_strength == pytest.approx(strength)
        got = _flame_reading(s, 0.5, pose)[0]
        assert got == pytest.approx(ref * strength * flicker(0.5, 0.2, 1.5, p1, p2), rel=1e-12)


def test_ir_source_adds_its_own_light_lit_or_not() -> None:
    """A lamp of strength 2 in room 1, 0.25 m straight ahead of the left sensor: it adds
    2 * 0.0125 * K(aim offset) / r^2 whether or not the flame burns."""
    arena = load_arena()
    robot = load_robot()
    cx, cy = arena.room(1).default_candle
    x, y, th = cx - 0.3, cy, 0.0
    fl = robot.flame
    px, py = x + fl.x, y + fl.y_offset
    aim = math.radians(fl.aim_deg)
    lx, ly = px + 0.25 * math.cos(aim), py + 0.25 * math.sin(aim)
    src = np.array([[lx, ly, fl.height, 2.0]])
    want = 2.0 * INTENSITY_COEFF / 0.0625
    s0 = _suite(NoiseProfile())
    s1 = _suite(NoiseProfile(), sources=src)
    a = _flame_reading(s0, 0.0, (x, y, th))[0]
    b = _flame_reading(s1, 0.0, (x, y, th))[0]
    assert b - a == pytest.approx(want, rel=1e-9)
    s0.candle.lit = False
    s1.candle.lit = False
    assert _flame_reading(s0, 0.1, (x, y, th))[0] == 0.0
    assert _flame_reading(s1, 0.1, (x, y, th))[0] == pytest.approx(want, rel=1e-9)



# -- configuration -----------------------------------------------------------------

def test_bundled_profiles_carry_the_models() -> None:
    from sim_plant.sensors import load_noise_profile
    real = load_noise_profile("realistic")
    assert real.ranger == RangerModel(2.0, 5, True, 0.0096, True)
    assert real.flame_world == FlameWorld(0.6, 1.4, 0.15, 1.5, 0.3, 0.5)
    assert load_noise_profile("single_ray").ranger.beam_half_angle_deg == 0.0
    assert load_noise_profile("none").ranger == RangerModel()  # the default: a 2-degree beam
    assert RangerModel().beam_half_angle_deg == 2.0 and not RangerModel().latency


@pytest.mark.parametrize("group,key,value,msg", [
    ("ranger", "beam_half_angle_deg", 45.0, "must be in"),
    ("ranger", "beam_rays", 2.5, "whole number"),
    ("ranger", "latency", 1, "true or false"),
    ("ranger", "period_spread", -0.001, "must be in"),
    ("ranger", "beam_width", 2.0, "unknown field"),
    ("flame_world", "wall_reflectance", 1.5, "must be in"),
    ("flame_world", "strength_max", 0.5, "must be >= strength_min"),
    ("flame_world", "afterglow_s", "long", "finite number"),
])
def test_bad_model_values_are_refused_naming_the_field(group: str, key: str, value: object,
                                                       msg: str) -> None:
    from sim_plant.errors import FfrInputError
    from sim_plant.sensors.noise import profile_from_table
    with pytest.raises(FfrInputError, match=msg) as e:
        profile_from_table({group: {key: value}}, "x.toml")
    assert f"{group}.{key}" in str(e.value) and "x.toml" in str(e.value)


@pytest.mark.parametrize("seed", range(5))
def test_beam_edge_filter_changes_no_distance(arena: Arena, seed: int) -> None:
    """The beam casts its rays only against the edges inside its wedge: every ray's distance
    must be exactly the one against all edges (random poses and aims over the whole arena)."""
    from sim_plant.geometry import ray_cast
    from sim_plant.sensors.gp2d12 import _edges_in_wedge
    rng = np.random.default_rng(seed)
    e = arena.wall_edges
    for _ in range(400):
        px, py = rng.uniform(0.03, 2.41, 2)
        a = rng.uniform(-math.pi, math.pi)
        h = math.radians(rng.uniform(0.1, 20.0))
        sub = _edges_in_wedge(px, py, math.cos(a), math.sin(a), h, e)
        assert sub.shape[0] <= e.shape[0]
        for o in np.linspace(-h, h, 7):
            dx, dy = math.cos(a) * math.cos(o) - math.sin(a) * math.sin(o), \
                math.cos(a) * math.sin(o) + math.sin(a) * math.cos(o)
            assert ray_cast(px, py, dx, dy, sub, 4.0) == ray_cast(px, py, dx, dy, e, 4.0)


@pytest.mark.parametrize("seed", range(3))
def test_beam_table_in_python_is_the_compiled_one_bit_for_bit(seed: int) -> None:
    """The suite builds the beam's rotations in Python (no kernel to load at start-up); they must
    be the very doubles the compiled ``beam_table`` (the per-ray expressions) gives, over the
    whole range of half-angles and ray counts, the one-ray cases included."""
    from sim_plant.sensors.gp2d12 import beam_table, beam_table_py
    rng = np.random.default_rng(seed)
    halves = [0.0, -0.1, *np.radians(rng.uniform(0.0, 45.0, 60))]
    for h in halves:
        for n in range(0, 12):
            py, nb_ = beam_table_py(float(h), n), beam_table(float(h), n)
            assert py.shape == nb_.shape == ((n if h > 0.0 and n > 1 else 1) + 1, 2)
            assert py.tobytes() == nb_.tobytes()


@pytest.mark.parametrize("seed", range(3))
def test_beam_with_reused_scratch_is_the_fresh_beam(arena: Arena, seed: int) -> None:
    """The sensors keep one scratch buffer for the wedge's edges across measurements: a buffer
    left full by earlier measurements must change no distance (random poses, aims, beams, with
    and without the candle's base as a target)."""
    from sim_plant.sensors.gp2d12 import beam_distance_tab, beam_table_py, wedge_soa
    rng = np.random.default_rng(seed)
    e, polys = arena.wall_edges, arena.wall_polys
    scratch = np.empty((e.shape[0], 4))
    keep = np.empty(e.shape[0], dtype=np.uint8)
    for _ in range(300):
        px, py = rng.uniform(0.03, 2.41, 2)
        a = rng.uniform(-math.pi, math.pi)
        h = math.radians(rng.uniform(0.0, 20.0))
        n = int(rng.integers(1, 9))
        obs = float(rng.choice([0.0, 0.04]))
        cx, cy = rng.uniform(0.3, 2.1, 2)
        got = beam_distance_tab(px, py, math.cos(a), math.sin(a), beam_table_py(h, n), e, polys,
                                scratch, wedge_soa(e), keep, 4.0, cx, cy, obs)
        want = beam_distance(px, py, math.cos(a), math.sin(a), h, n, e, polys, 4.0, cx, cy, obs)
        assert got == want


@pytest.mark.parametrize("seed", range(3))
def test_reflections_with_edge_table_are_the_reference(arena: Arena, seed: int) -> None:
    """The suite reads each edge's length and normal from a table made once (edge_normals):
    every reflected light must be the very double ``reflected_fc`` computes (random sensor and
    source positions, heights and aims over the whole arena, in the arena with furniture too)."""
    from sim_plant.furniture import draw_furniture, furnish
    from sim_plant.sensors.flame_sensor import edge_normals, reflected_fc_tab
    rng = np.random.default_rng(seed)
    pieces = draw_furniture(arena, 3, arena.room(2).default_candle, np.random.default_rng(seed))
    arenas = [arena, furnish(arena, pieces)]
    assert arenas[1].wall_edges.shape[0] > arena.wall_edges.shape[0]
    for ar in arenas:
        e = ar.wall_edges
        en = edge_normals(e)
        soa = edges_soa(e)
        for _ in range(300):
            px, py, sx, sy = rng.uniform(0.03, 2.41, 4)
            pz, sz = rng.uniform(0.05, 0.3, 2)
            aim = rng.uniform(-math.pi, math.pi)
            half = math.radians(rng.uniform(20.0, 90.0))
            want = reflected_fc(px, py, pz, aim, sx, sy, sz, e, half, 0.02)
            assert reflected_fc_tab(px, py, pz, aim, sx, sy, sz, soa, en, half, 0.02) == want



@pytest.mark.parametrize("seed", range(3))
def test_branch_free_line_of_sight_is_segment_blocked(arena: Arena, seed: int) -> None:
    """``segment_blocked_soa`` (the flame sensors' line of sight) must answer as
    ``segment_blocked`` for any segment: random ones over the arena (furniture too), segments
    along a wall face, from a wall's corner, of zero length, and parallel to a wall."""
    from sim_plant.furniture import draw_furniture, furnish
    from sim_plant.geometry import segment_blocked, segment_blocked_soa
    rng = np.random.default_rng(seed)
    pieces = draw_furniture(arena, 3, arena.room(3).default_candle, np.random.default_rng(seed))
    for ar in (arena, furnish(arena, pieces)):
        e = ar.wall_edges
        soa = edges_soa(e)
        segs = [tuple(rng.uniform(0.0, 2.44, 4)) for _ in range(2000)]
        for i in rng.integers(0, e.shape[0], 200):
            x1, y1, x2, y2 = e[i]
            segs += [(x1, y1, x2, y2), (x1, y1, x1 + (x2 - x1) * 0.5, y1 + (y2 - y1) * 0.5),
                     (x1, y1, x1, y1), (x1 + 0.01, y1, x2 + 0.01, y2),
                     (x1, y1, *rng.uniform(0.0, 2.44, 2))]
        hits = 0
        for s in segs:
            want = segment_blocked(*s, e)
            hits += want
            assert segment_blocked_soa(*s, soa) == want, s
        assert 0 < hits < len(segs)
