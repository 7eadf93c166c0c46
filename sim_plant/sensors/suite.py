"""All of the robot's sensors, sampled together once per firmware tick.

``SensorSuite.sample`` is on the hot path (every 10 ms tick of every
mission), so it is one compiled kernel call: the Python side only passes the
pose and pre-packed arrays; configuration is packed once at construction.
Rangers ray-cast only when their measurement is due (every 38.3 ms); the
flame line-of-sight test runs only when the flame is lit and within a
sensor's field of view.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.arena import Arena
from sim_plant.candle import Candle
from sim_plant.geometry import edges_soa
from sim_plant.robot import IR_NAMES, RobotParams
from sim_plant.sensors.channels import (
    CH_ENC_L,
    CH_ENC_R,
    CH_FLAME_L,
    CH_FLAME_R,
    CH_IR,
    CH_LINE,
    N_CHANNELS,
)
from sim_plant.sensors.encoders import encoder_counts
from sim_plant.sensors.flame_sensor import (
    FlameModel,
    edge_normals,
    flame_sensor_fc,
    point_fc,
    reflected_fc_tab,
)
from sim_plant.sensors.gp2d12 import (
    IR_MV_MAX,
    Gp2d12Model,
    beam_distance_tab,
    beam_table_py,
    mv_of_distance,
    wedge_soa,
)
from sim_plant.sensors.line_sensor import door_segments, white_fraction
from sim_plant.sensors.models import FLICKER_RATIO, draw_flame, draw_ranger_timing
from sim_plant.sensors.noise import (
    ENABLED,
    FLAME_BASE,
    IR_BASE,
    NoiseProfile,
    NoiseStream,
    apply_analog,
    flip_bit,
    needs_refill,
    slip,
)

_T_EPS = 1e-9  # s, a measurement due "at" a tick time is taken at that tick

# ir_cfg columns: pose, phase, the part's own gain and offset (unit spread), its period
_BX, _BY, _CA, _SA, _PHASE, _UG, _UO, _PER = range(8)
# ir_state columns (_PEND: the last measurement's output, shown one period later with latency)
_K, _HELD, _DIST, _CLEAN, _PEND = range(5)
# cfg entries
(C_PERIOD, C_MAX_RANGE, C_FX, C_FY, C_FZ, C_AIM, C_HALF, C_RMIN, C_GAIN, C_DARK, C_FULL,
 C_CX, C_CY, C_CZ, C_LX, C_LY, C_HALFW, C_RHO, C_THRESH, C_HX, C_HY, C_HR, C_CR,
 C_TPR, C_UNIT_IR, C_IR_PIVOT, C_UNIT_FL, C_FL_PIVOT, C_FG_L, C_FG_R, C_FO_L, C_FO_R,
 C_BEAM_HALF, C_BEAM_N, C_LATENCY, C_OBS_R, C_STRENGTH, C_FLICK_A, C_FLICK_W, C_FLICK_P1,
 C_FLICK_P2, C_REFL, C_GLOW) = range(43)
N_CFG = 43
# st entries: state and diagnostics
(S_INIT, S_T0, S_PHI_L, S_PHI_R, S_SLIP_L, S_SLIP_R, S_FLAME_PREV_L, S_FLAME_PREV_R,
 S_FC_L, S_FC_R, S_LINE_FRAC, S_FLAME_PHASE, S_OFF_T) = range(13)
N_ST = 13
# S_FLAME_PHASE: 0 = no sample yet saw the flame lit, 1 = lit, 2 = out since S_OFF_T


@nb.njit(cache=True)
def _round(v: float) -> float:
    return math.floor(v + 0.5)


# Compiled lazily (an explicit signature would load it at import, ~0.1 s of every
# start-up, though the compiled mission loop never calls it from Python). ``sample``
# converts t and the pose to float and checks ``out``, so there is one specialization.
@nb.njit(cache=True)
def _sample_kernel(t: float, x: float, y: float, theta: float, phi_l: float, phi_r: float,
                   lit: bool, out: np.ndarray, ir_cfg: np.ndarray, ir_state: np.ndarray,
                   cfg: np.ndarray, st: np.ndarray, edges: np.ndarray, wall_polys: np.ndarray,
                   doors: np.ndarray, npar: np.ndarray, normals: np.ndarray,
                   uniforms: np.ndarray, npos: np.ndarray, srcs: np.ndarray,
                   beam: np.ndarray, scratch: np.ndarray, enorm: np.ndarray,
                   esoa: np.ndarray, wsoa: np.ndarray, keep: np.ndarray) -> bool:
    c = math.cos(theta)
    s = math.sin(theta)
    first = st[S_INIT] == 0.0
    if first:
        st[S_INIT] = 1.0
        st[S_T0] = t
        st[S_PHI_L] = phi_l
        st[S_PHI_R] = phi_r
    noisy = npar[ENABLED] != 0.0
    t0 = st[S_T0]

    # GP2D12 rangers: measure when due, hold in between (with latency: show the previous one).
    for i in range(ir_cfg.shape[0]):
        k = ir_state[i, _K]
        phase = ir_cfg[i, _PHASE]
        period = ir_cfg[i, _PER]
        if first or t + _T_EPS >= t0 + phase + k * period:
            bx = ir_cfg[i, _BX]
            by = ir_cfg[i, _BY]
            ca = ir_cfg[i, _CA]
            sa = ir_cfg[i, _SA]
            px = x + c * bx - s * by
            py = y + s * bx + c * by
            d = beam_distance_tab(px, py, c * ca - s * sa, s * ca + c * sa, beam, edges,
                                  wall_polys, scratch, wsoa, keep, cfg[C_MAX_RANGE], cfg[C_CX], cfg[C_CY],
                                  cfg[C_OBS_R])
            mv = mv_of_distance(d)
            ir_state[i, _DIST] = d
            ir_state[i, _CLEAN] = mv
            if cfg[C_UNIT_IR] != 0.0:
                pv = cfg[C_IR_PIVOT]
                mv = pv + ir_cfg[i, _UG] * (mv - pv) + ir_cfg[i, _UO]
            if noisy:
                mv = apply_analog(mv, npar, IR_BASE, normals, uniforms, npos, ir_state[i, _PEND])
            mv = min(max(_round(mv), 0.0), IR_MV_MAX)
            ir_state[i, _HELD] = mv if first or cfg[C_LATENCY] == 0.0 else ir_state[i, _PEND]
            ir_state[i, _PEND] = mv
            while t + _T_EPS >= t0 + phase + k * period:
                k += 1.0
            ir_state[i, _K] = k
        out[i] = np.int32(ir_state[i, _HELD])

    # The flame's strength now: drawn strength, flicker, afterglow once it is out.
    scale = 0.0
    if lit:
        st[S_FLAME_PHASE] = 1.0
        scale = cfg[C_STRENGTH]
        if cfg[C_FLICK_A] > 0.0:
            w = cfg[C_FLICK_W] * t
            scale *= 1.0 + cfg[C_FLICK_A] * (0.6 * math.sin(w + cfg[C_FLICK_P1])
                                             + 0.4 * math.sin(FLICKER_RATIO * w + cfg[C_FLICK_P2]))
    else:
        if st[S_FLAME_PHASE] == 1.0:
            st[S_FLAME_PHASE] = 2.0
            st[S_OFF_T] = t
        tau = cfg[C_GLOW]
        if st[S_FLAME_PHASE] == 2.0 and tau > 0.0 and t - st[S_OFF_T] < 10.0 * tau:
            scale = cfg[C_STRENGTH] * math.exp(-(t - st[S_OFF_T]) / tau)

    # Flame sensors, left (+y, +aim) then right.
    for j in range(2):
        side = 1.0 if j == 0 else -1.0
        fc = 0.0
        if scale > 0.0:
            fc = flame_sensor_fc(x, y, c, s, cfg[C_FX], side * cfg[C_FY], cfg[C_FZ],
                                 side * cfg[C_AIM], theta, cfg[C_CX], cfg[C_CY], cfg[C_CZ],
                                 esoa, cfg[C_HALF], cfg[C_RMIN])
            if cfg[C_REFL] > 0.0:
                by = side * cfg[C_FY]
                px = x + c * cfg[C_FX] - s * by
                py = y + s * cfg[C_FX] + c * by
                fc += cfg[C_REFL] * reflected_fc_tab(px, py, cfg[C_FZ],
                                                     theta + side * cfg[C_AIM], cfg[C_CX],
                                                     cfg[C_CY], cfg[C_CZ], esoa, enorm,
                                                     cfg[C_HALF], cfg[C_RMIN])
            fc = scale * fc
        if srcs.shape[0] > 0:
            by = side * cfg[C_FY]
            px = x + c * cfg[C_FX] - s * by
            py = y + s * cfg[C_FX] + c * by
            for q in range(srcs.shape[0]):
                fc += srcs[q, 3] * point_fc(px, py, cfg[C_FZ], theta + side * cfg[C_AIM],
                                            srcs[q, 0], srcs[q, 1], srcs[q, 2], esoa,
                                            cfg[C_HALF], cfg[C_RMIN])
        st[S_FC_L + j] = fc
        v = cfg[C_GAIN] * fc + cfg[C_DARK]
        if cfg[C_UNIT_FL] != 0.0:
            pv = cfg[C_FL_PIVOT]
            v = pv + cfg[C_FG_L + j] * (v - pv) + cfg[C_FO_L + j]
        if noisy:
            v = apply_analog(v, npar, FLAME_BASE, normals, uniforms, npos, st[S_FLAME_PREV_L + j])
        v = min(max(_round(v), 0.0), cfg[C_FULL])
        st[S_FLAME_PREV_L + j] = v
        out[5 + j] = np.int32(v)

    # Line sensor.
    lx = x + c * cfg[C_LX] - s * cfg[C_LY]
    ly = y + s * cfg[C_LX] + c * cfg[C_LY]
    frac = white_fraction(lx, ly, doors, cfg[C_HALFW], cfg[C_RHO], cfg[C_HX], cfg[C_HY],
                          cfg[C_HR], cfg[C_CX], cfg[C_CY], cfg[C_CR])
    st[S_LINE_FRAC] = frac
    bit = 1 if frac >= cfg[C_THRESH] - 1e-12 else 0
    if noisy:
        bit = flip_bit(bit, npar, uniforms, npos)
    out[7] = bit

    # Encoders; a slip loses part of this tick's rotation for good.
    if noisy:
        st[S_SLIP_L] += slip(phi_l - st[S_PHI_L], npar, uniforms, npos)
        st[S_SLIP_R] += slip(phi_r - st[S_PHI_R], npar, uniforms, npos)
    st[S_PHI_L] = phi_l
    st[S_PHI_R] = phi_r
    out[8] = np.int32(encoder_counts(phi_l - st[S_SLIP_L], cfg[C_TPR]))
    out[9] = np.int32(encoder_counts(phi_r - st[S_SLIP_R], cfg[C_TPR]))
    return noisy and needs_refill(npos, normals.shape[0])


assert CH_IR == (0, 1, 2, 3, 4) and (CH_FLAME_L, CH_FLAME_R, CH_LINE, CH_ENC_L, CH_ENC_R) == (
    5, 6, 7, 8, 9), "the kernel writes these channel indices literally"


class SensorSuite:
    """The robot's sensors in one arena with one candle: ``sample`` once per tick.

    ``noise`` defaults to the ``none`` profile; ``rng`` is needed only when the
    profile turns something on, and is the only source of randomness. The
    candle's position is read once here; whether it is lit, at every sample.
    ``ir_model`` / ``flame_model`` override the GP2D12 timing and the flame
    sensor's gain, dark level and field of view. The beam, latency, per-part
    timing and the flame's strength, flicker, reflections and afterglow come
    from the profile's ``ranger`` and ``flame_world`` groups (models.py); the
    candle's base is a ranger target when ``candle.base_radius`` > 0;
    ``ir_sources``: (n, 4) rows x, y, z (m), strength (x a standard flame),
    other infrared sources the flame sensors see.
    """

    def __init__(self, arena: Arena, robot: RobotParams, candle: Candle,
                 noise: NoiseProfile | None = None, rng: np.random.Generator | None = None,
                 *, ir_model: Gp2d12Model | None = None,
                 flame_model: FlameModel | None = None,
                 ir_sources: np.ndarray | None = None) -> None:
        self.arena = arena
        self.robot = robot
        self.candle = candle
        self.noise = noise if noise is not None else NoiseProfile()
        self.ir_model = ir_model if ir_model is not None else Gp2d12Model()
        self.flame_model = flame_model if flame_model is not None else FlameModel()
        if self.ir_model.period <= 0.0:
            raise ValueError(f"GP2D12 period must be > 0, got {self.ir_model.period}")

        phases = self.ir_model.phases(len(IR_NAMES))
        self._ir_cfg = np.array(
            [[robot.ir[n].x, robot.ir[n].y, math.cos(math.radians(robot.ir[n].angle_deg)),
              math.sin(math.radians(robot.ir[n].angle_deg)), phases[i], 1.0, 0.0,
              self.ir_model.period]
             for i, n in enumerate(IR_NAMES)], dtype=np.float64)
        self._ir_state = np.zeros((len(IR_NAMES), 5))
        fm = self.flame_model
        fl = robot.flame
        ls = robot.line_sensor
        cfg = np.zeros(N_CFG)
        cfg[C_PERIOD] = self.ir_model.period
        cfg[C_MAX_RANGE] = self.ir_model.max_range
        cfg[C_FX], cfg[C_FY], cfg[C_FZ] = fl.x, fl.y_offset, fl.height
        cfg[C_AIM] = math.radians(fl.aim_deg)
        cfg[C_HALF] = math.radians(fm.k_half_width_deg)
        cfg[C_RMIN] = fm.r_min
        cfg[C_GAIN] = fm.gain
        cfg[C_DARK] = fm.dark
        cfg[C_FULL] = (1 << fl.adc_bits) - 1
        cfg[C_CX], cfg[C_CY], cfg[C_CZ] = candle.x, candle.y, candle.height
        cfg[C_LX], cfg[C_LY] = ls.x, ls.y
        cfg[C_HALFW] = arena.line_width / 2.0
        cfg[C_RHO] = ls.spot_radius
        cfg[C_THRESH] = ls.white_fraction
        cfg[C_HX], cfg[C_HY] = arena.home_center
        cfg[C_HR] = arena.home_radius
        cfg[C_CR] = arena.candle_circle_radius
        cfg[C_TPR] = robot.encoder.ticks_per_rev
        self._cfg = cfg
        self._st = np.zeros(N_ST)
        self._stream = NoiseStream(rng, self.noise.enabled)
        # each part's own calibration, drawn once (after the first noise block)
        ir_units = self.noise.ir.draw_units(len(IR_NAMES), rng)
        fl_units = self.noise.flame.draw_units(2, rng)
        self._ir_cfg[:, _UG:_UO + 1] = ir_units
        cfg[C_UNIT_IR] = 1.0 if self.noise.ir.unit_spread else 0.0
        cfg[C_IR_PIVOT] = self.noise.ir.unit_pivot
        cfg[C_UNIT_FL] = 1.0 if self.noise.flame.unit_spread else 0.0
        cfg[C_FL_PIVOT] = self.noise.flame.unit_pivot
        cfg[C_FG_L], cfg[C_FG_R] = fl_units[:, 0]
        cfg[C_FO_L], cfg[C_FO_R] = fl_units[:, 1]
        self.units = {"ir": ir_units, "flame": fl_units}
        # issue 12's models; their draws (if any) after the units' (models.py)
        rm = self.noise.ranger
        periods, phases2 = draw_ranger_timing(rm, self.ir_model.period, phases, rng)
        self._ir_cfg[:, _PER] = periods
        self._ir_cfg[:, _PHASE] = phases2
        cfg[C_BEAM_HALF] = math.radians(rm.beam_half_angle_deg)
        cfg[C_BEAM_N] = rm.beam_rays
        cfg[C_LATENCY] = 1.0 if rm.latency else 0.0
        cfg[C_OBS_R] = candle.base_radius
        fw = self.noise.flame_world
        strength, p1, p2 = draw_flame(fw, rng)
        cfg[C_STRENGTH] = strength
        cfg[C_FLICK_A] = fw.flicker_amp
        cfg[C_FLICK_W] = 2.0 * math.pi * fw.flicker_hz
        cfg[C_FLICK_P1], cfg[C_FLICK_P2] = p1, p2
        cfg[C_REFL] = fw.wall_reflectance
        cfg[C_GLOW] = fw.afterglow_s
        self.flame_strength = strength
        srcs = np.zeros((0, 4)) if ir_sources is None else np.asarray(ir_sources, dtype=np.float64)
        if srcs.ndim != 2 or srcs.shape[1] != 4:
            raise ValueError(f"ir_sources must be (n, 4): x, y, z, strength; got {srcs.shape}")
        self._srcs = np.ascontiguousarray(srcs)
        # the beam's rotations once (gp2d12.beam_table_py), the scratch its wedge filter fills, and
        # the edges as rows for that filter (gp2d12.wedge_soa) with its one-byte-per-edge scratch
        self._beam = beam_table_py(float(cfg[C_BEAM_HALF]), int(cfg[C_BEAM_N]))
        self._args = (self._ir_cfg, self._ir_state, cfg, self._st, arena.wall_edges,
                      arena.wall_polys, door_segments(arena), self.noise.packed(),
                      self._stream.normals, self._stream.uniforms, self._stream.pos, self._srcs,
                      self._beam, np.empty((arena.wall_edges.shape[0], 4)),
                      edge_normals(arena.wall_edges), edges_soa(arena.wall_edges),
                      wedge_soa(arena.wall_edges), np.empty(arena.wall_edges.shape[0], dtype=np.uint8))
        self._checked_out: np.ndarray | None = None

    def sample(self, t: float, x: float, y: float, theta: float, phi_l: float, phi_r: float,
               out: np.ndarray) -> None:
        """Write the sensors' hardware-unit readings at time t (s) and pose into ``out``."""
        if out is not self._checked_out:
            if out.dtype != np.int32 or out.shape != (N_CHANNELS,):
                raise TypeError(f"out must be int32 of shape ({N_CHANNELS},), "
                                f"got {out.dtype} {out.shape}")
            self._checked_out = out
        if _sample_kernel(float(t), float(x), float(y), float(theta), float(phi_l), float(phi_r),
                          bool(self.candle.lit), out, *self._args):
            self._stream.refill()

    def kernel_args(self) -> tuple[np.ndarray, ...]:
        """``_sample_kernel``'s arguments after ``out`` (state arrays shared with this suite),
        for a compiled caller (harness/tick.py) that also does the refills."""
        return self._args

    def reset(self) -> None:
        """Forget all sensor state (held ranger readings, slip, start time); noise stream kept."""
        self._ir_state[:] = 0.0
        self._st[:] = 0.0

    # -- ground truth, for tests and plots ---------------------------------
    @property
    def ir_distance(self) -> np.ndarray:
        """True (beam) distance (m) at each ranger's last measurement, IR_NAMES order (with
        latency, the firmware sees it one period later)."""
        return self._ir_state[:, _DIST].copy()

    @property
    def ir_periods(self) -> np.ndarray:
        """Each ranger's measurement period (s) and, below, first measurement offset (s)."""
        return self._ir_cfg[:, _PER].copy()

    @property
    def ir_phases(self) -> np.ndarray:
        return self._ir_cfg[:, _PHASE].copy()

    @property
    def ir_mv_clean(self) -> np.ndarray:
        """Noise-free output (mV, float) of each ranger's last measurement."""
        return self._ir_state[:, _CLEAN].copy()

    @property
    def flame_fc(self) -> tuple[float, float]:
        """Light on the left and right flame sensors at the last sample (foot-candles)."""
        return float(self._st[S_FC_L]), float(self._st[S_FC_R])

    @property
    def line_fraction(self) -> float:
        """White fraction of the line sensor's spot at the last sample."""
        return float(self._st[S_LINE_FRAC])
