"""Noise and fault profiles: loading, errors, determinism by seed, and 'none' making no draws."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from sim_plant.candle import Candle
from sim_plant.errors import FfrInputError
from sim_plant.sensors import (
    CH_ENC_L,
    CH_ENC_R,
    CH_FLAME_L,
    CH_FLAME_R,
    CH_IR,
    CH_LINE,
    N_CHANNELS,
    FlameModel,
    NoiseProfile,
    SensorSuite,
    distance_to_mv,
    load_noise_profile,
    new_output,
)
from sim_plant.sensors.noise import BLOCK, NoiseStream

N_TICKS = 3000  # long enough for several refills of the random blocks (checked below)


def trajectory(n):
    """Up the corridor, across the home circle's hallway, and around room BR's doorway."""
    for k in range(n):
        t = k * 0.01
        u = (k % 1000) / 1000.0
        leg = (k // 1000) % 3
        if leg == 0:
            yield t, 0.97, 0.3 + 1.6 * u, math.pi / 2, 10 * u, 10 * u
        elif leg == 1:
            yield t, 1.3 + 0.9 * u, 1.17, 0.0, 10 + 8 * u, 10 + 8.2 * u
        else:
            yield t, 1.0 + 0.6 * u, 0.7, math.sin(6 * u) - 0.2, 18 + 5 * u, 18 + 4.5 * u


def make(arena, robot, noise, rng):
    candle = Candle(*arena.room(1).default_candle, robot, arena)
    return SensorSuite(arena, robot, candle, noise, rng)


def run(suite, n=N_TICKS, truth=False):
    trace = np.empty((n, N_CHANNELS), dtype=np.int32)
    dists = np.empty((n, 5))
    out = new_output()
    for k, (t, x, y, th, pl, pr) in enumerate(trajectory(n)):
        suite.sample(t, x, y, th, pl, pr, out)
        trace[k] = out
        dists[k] = suite.ir_distance
    return (trace, dists) if truth else trace


def test_bundled_profiles_load():
    none = load_noise_profile("none")
    assert not none.enabled and none == NoiseProfile()
    typ = load_noise_profile("typical")
    assert typ.enabled and typ.ir.quant_step == pytest.approx(4.883) and typ.ir.sigma > 0
    harsh = load_noise_profile("harsh")
    assert harsh.ir.dropout_prob > 0 and harsh.flame.dropout_mode == "hold"
    assert harsh.line.flip_prob > 0 and harsh.encoder.slip_prob > typ.encoder.slip_prob


def test_unknown_profile_name():
    with pytest.raises(FfrInputError) as exc:
        load_noise_profile("noisy")
    msg = str(exc.value)
    assert "noise_profiles.toml" in msg and "'noisy'" in msg and "typical" in msg


@pytest.mark.parametrize(
    ("body", "field", "value"),
    [
        ("[p.ir]\nsigma = -1.5\n", "p.ir.sigma", "-1.5"),
        ("[p.flame]\nspike_prob = 1.5\n", "p.flame.spike_prob", "1.5"),
        ("[p.ir]\nsigmaa = 3\n", "p.ir.sigmaa", "3"),
        ("[p.ir]\ndropout_mode = \"sometimes\"\n", "p.ir.dropout_mode", "'sometimes'"),
        ("[p.encoder]\nslip_fraction = \"half\"\n", "p.encoder.slip_fraction", "'half'"),
        ("[p.gyro]\nsigma = 1\n", "p.gyro", "sigma"),
    ],
)
def test_bad_profile_file_names_file_field_value(tmp_path, body, field, value):
    path = tmp_path / "bad_noise.toml"
    path.write_text(body)
    with pytest.raises(FfrInputError) as exc:
        load_noise_profile(path)
    msg = str(exc.value)
    assert "\n" not in msg
    assert str(path) in msg and f"{field} = " in msg and value in msg
    assert exc.value.field == field


def test_profile_from_file_and_by_name_in_file(tmp_path):
    path = tmp_path / "mine.toml"
    path.write_text("[a.ir]\nsigma = 2.0\n[b.line]\nflip_prob = 0.5\n")
    assert load_noise_profile(f"{path}#b").line.flip_prob == 0.5
    with pytest.raises(FfrInputError):
        load_noise_profile(path)  # two profiles, none named
    one = tmp_path / "one.toml"
    one.write_text("[solo.flame]\nsigma = 1\n")
    p = load_noise_profile(one)
    assert p.name == "solo" and p.flame.sigma == 1.0 and p.enabled


def test_same_seed_bit_identical_other_seed_different(arena, robot):
    typ = load_noise_profile("typical")
    a = run(make(arena, robot, typ, np.random.default_rng(1234)))
    b = run(make(arena, robot, typ, np.random.default_rng(1234)))
    c = run(make(arena, robot, typ, np.random.default_rng(1235)))
    assert np.array_equal(a, b)
    assert not np.array_equal(a[:, CH_IR[0]], c[:, CH_IR[0]])
    assert not np.array_equal(a[:, CH_FLAME_L], c[:, CH_FLAME_L])


def test_harsh_same_seed_bit_identical(arena, robot):
    harsh = load_noise_profile("harsh")
    a = run(make(arena, robot, harsh, np.random.default_rng(7)))
    b = run(make(arena, robot, harsh, np.random.default_rng(7)))
    assert np.array_equal(a, b)


def test_none_profile_is_noise_free_and_draws_nothing(arena, robot):
    rng = np.random.default_rng(99)
    before = rng.bit_generator.state
    trace, dists = run(make(arena, robot, load_noise_profile("none"), rng), truth=True)
    assert rng.bit_generator.state == before
    expected_ir = np.floor(distance_to_mv(dists) + 0.5).astype(np.int32)
    assert np.array_equal(trace[:, :5], expected_ir)
    assert np.array_equal(trace, run(make(arena, robot, None, None)))
    # Far from the candle and behind walls most of the way: flame at the dark level.
    assert np.all(trace[:1000, CH_FLAME_L] == FlameModel().dark)
    assert set(np.unique(trace[:, CH_LINE])) == {0, 1}


def test_typical_noise_is_small_and_quantised(arena, robot):
    clean, dists = run(make(arena, robot, None, None), truth=True)
    noisy = run(make(arena, robot, load_noise_profile("typical"), np.random.default_rng(5)))
    diff = noisy[:, :5].astype(float) - clean[:, :5]
    assert 3.0 < diff.std() < 25.0  # sigma 10 mV, quantised, rare 150 mV spikes
    # Every noisy IR reading is a whole number of 10-bit ADC steps (to the mV).
    steps = noisy[:, :5] / 4.883
    assert np.all(np.abs(steps - np.round(steps)) * 4.883 <= 0.5 + 1e-9)
    # Slip only loses counts.
    assert np.all(noisy[:, CH_ENC_L] <= clean[:, CH_ENC_L])
    assert noisy[-1, CH_ENC_R] < clean[-1, CH_ENC_R]


def test_harsh_faults_show_up(arena, robot):
    clean = run(make(arena, robot, None, None))
    harsh = run(make(arena, robot, load_noise_profile("harsh"), np.random.default_rng(11)))
    assert np.any(harsh[:, :5] == 0) and not np.any(clean[:, :5] == 0)  # IR dropouts read 0 V
    assert np.count_nonzero(harsh[:, CH_LINE] != clean[:, CH_LINE]) > 0  # line misreads
    assert harsh[-1, CH_ENC_L] < clean[-1, CH_ENC_L] - 10  # heavy slip
    assert np.all((harsh[:, CH_FLAME_R] >= 0) & (harsh[:, CH_FLAME_R] <= 4095))


def test_noise_needs_a_generator(arena, robot):
    with pytest.raises(ValueError, match="Generator"):
        make(arena, robot, load_noise_profile("typical"), None)


def test_blocks_refill_during_a_run(arena, robot, monkeypatch):
    refills = []
    orig = NoiseStream.refill

    def counting(self):
        refills.append(1)
        orig(self)

    monkeypatch.setattr(NoiseStream, "refill", counting)
    run(make(arena, robot, load_noise_profile("typical"), np.random.default_rng(3)))
    assert len(refills) >= 3  # the initial fill and at least two of BLOCK draws each
    assert BLOCK == 4096


def test_datasheet_unit_spread_stays_within_the_datasheet_limits(arena, robot):
    """Each GP2D12 gets its own gain and offset, drawn once: output at 80 cm within 0.25-0.55 V
    around the typical 0.40 V (our curve: 0.42 V) and swing 80->10 cm within 1.75-2.25 V."""
    prof = load_noise_profile("datasheet")
    v80, v10 = float(distance_to_mv(0.80)), float(distance_to_mv(0.10))
    gains, offsets = [], []
    for seed in range(200):
        units = prof.ir.draw_units(5, np.random.default_rng(seed))
        for g, o in units:
            out80 = prof.ir.unit_pivot + g * (v80 - prof.ir.unit_pivot) + o
            out10 = prof.ir.unit_pivot + g * (v10 - prof.ir.unit_pivot) + o
            assert 420 - 150 - 1e-9 <= out80 <= 420 + 150 + 1e-9
            assert 0.875 * (v10 - v80) - 1e-9 <= out10 - out80 <= 1.125 * (v10 - v80) + 1e-9
            gains.append(g)
            offsets.append(o)
    # the draws cover the limits, not just the middle
    assert min(gains) < 0.89 and max(gains) > 1.11 and min(offsets) < -140 and max(offsets) > 140


def test_unit_spread_is_drawn_once_per_suite_and_shifts_readings(arena, robot):
    prof = NoiseProfile(name="u", ir=dataclasses.replace(NoiseProfile().ir, unit_offset_spread=100.0))
    a = make(arena, robot, prof, np.random.default_rng(1))
    b = make(arena, robot, prof, np.random.default_rng(1))
    c = make(arena, robot, prof, np.random.default_rng(2))
    assert np.array_equal(a.units["ir"], b.units["ir"]) and not np.array_equal(a.units["ir"], c.units["ir"])
    clean = run(make(arena, robot, NoiseProfile(), None), n=200)
    shifted = run(a, n=200)
    off = a.units["ir"][:, 1]
    for i in range(5):
        d = shifted[:, CH_IR[i]] - clean[:, CH_IR[i]]
        # a constant offset (rounded to whole mV), except where clipped at 0 V
        assert np.all(np.abs(d[clean[:, CH_IR[i]] > 200] - off[i]) <= 1.0)


def test_unit_spread_profile_validation(tmp_path):
    path = tmp_path / "u.toml"
    path.write_text("[u.ir]\nunit_gain_spread = 1.5\n")
    with pytest.raises(FfrInputError) as exc:
        load_noise_profile(path)
    assert "u.ir.unit_gain_spread" in str(exc.value)
