"""What issue 12's sensor and world models do to the missions: ``python -m harness.sensor_report``.

Prints, for the four default rooms, the times, contacts and clearance with the
models before issue 12 (one-ray GP2D12, no candle base), the default now (a
2-degree beam, the candle's 4 cm base), the default plus the GP2D12's latency,
and the ``realistic`` profile's sensor models; then the real-parts sample of
tests/property (``datasheet`` noise, 5 random candles a room, seeds 0-3,
sweep seed 11: 80 missions) with the default, with the one ray, and with the
latency added. docs/sensors.md quotes it. ``--quick``: the four rooms only.
"""

from __future__ import annotations

import dataclasses
import sys

from harness.loop import run_mission
from harness.scenario import make_scenario
from harness.scoring import seconds_text
from sim_plant.arena import Arena, load_arena
from sim_plant.broken_pipe import exit_with
from sim_plant.sensors import NoiseProfile, load_noise_profile


def _variants(base: NoiseProfile) -> list[tuple[str, Arena, NoiseProfile]]:
    arena = load_arena()
    bare = dataclasses.replace(arena, candle_base_radius=0.0)
    single = load_noise_profile("single_ray").ranger
    real = load_noise_profile("realistic")
    lat = dataclasses.replace(base.ranger, latency=True)
    return [
        ("before issue 12: one ray, no candle base", bare, dataclasses.replace(base, ranger=single)),
        ("default: 2-degree beam, candle base", arena, base),
        ("default + GP2D12 latency", arena, dataclasses.replace(base, ranger=lat)),
        ("realistic profile's sensor models", arena,
         dataclasses.replace(base, ranger=real.ranger, flame_world=real.flame_world)),
    ]


def beam() -> None:
    import math

    import numpy as np

    from sim_plant.sensors.gp2d12 import beam_distance
    from sim_plant.sensors.models import RangerModel
    m = RangerModel()
    h = math.radians(m.beam_half_angle_deg)
    wall = np.array([[0.4, -5.0, 0.4, 5.0]])
    d = beam_distance(0.0, 0.0, 1.0, 0.0, h, m.beam_rays, wall, np.zeros((0, 4, 2)), 4.0, 0.0, 0.0, 0.0)
    print(f"default beam: +-{m.beam_half_angle_deg:g} deg, {m.beam_rays} rays: a spot "
          f"{200 * 0.8 * math.tan(h):.1f} cm wide at 80 cm; a wall 40 cm ahead at right angles reads "
          f"{100 * d:.3f} cm ({100 * (d / 0.4 - 1):+.3f} %)")


def rooms() -> None:
    print("four rooms, no noise (flame out / home s; contacts; min clearance cm):")
    for name, arena, prof in _variants(NoiseProfile()):
        cells = []
        for room in (1, 2, 3, 4):
            r, _ = run_mission(make_scenario(arena=arena, room=room, noise=prof), record=False)
            ext = seconds_text(r.time_to_extinguish_s)
            home = seconds_text(r.total_time_s)
            cells.append(f"{ext}/{home} {r.outcome} {r.wall_contacts} {100 * r.min_wall_clearance_m:.1f}")
        print(f"  {name:42s} " + " | ".join(cells), flush=True)


def real_parts() -> None:
    from harness import sweep as sw

    spec = sw.SweepSpec(candles="random", n_candles=5, seeds=tuple(range(4)), noise="datasheet",
                        sweep_seed=11)
    places = sw.candle_positions(spec)
    ds = load_noise_profile("datasheet")
    print(f"real parts (datasheet noise), {len(places)} random candles x {len(spec.seeds)} seeds:")
    for name, arena, prof in _variants(ds)[:3]:
        ok = n = 0
        fails: dict[str, int] = {}
        for (_, cx, cy) in places:
            for seed in spec.seeds:
                r, _ = run_mission(make_scenario(arena=arena, candle=(cx, cy), noise=prof, seed=seed),
                                   record=False)
                n += 1
                if r.outcome == "home" and r.wall_contacts == 0:
                    ok += 1
                else:
                    fails[r.detail or r.outcome] = fails.get(r.detail or r.outcome, 0) + 1
        why = "; ".join(f"{k}: {v}" for k, v in sorted(fails.items()))
        print(f"  {name:42s} {ok}/{n} home with no contact = {100 * ok / n:.1f} %"
              + (f" (failures: {why})" if why else ""), flush=True)


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    beam()
    rooms()
    if "--quick" not in args:
        real_parts()


if __name__ == "__main__":
    exit_with(main)
