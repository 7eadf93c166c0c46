"""The compiled lockstep tick: a whole mission in one numba call (in-process link only).

``harness/loop.py``'s Python loop steps sensors, events, the packer, the
firmware (ctypes), the plant and the candle one Python call each, per tick;
the call overhead was most of the ~11 us a tick cost. ``mission_kernel`` runs
the same tick, in the same order and with the same arithmetic, inside one
compiled function and calls the firmware's ``ffr_step`` through its C address
(``_call_step`` below), from the first tick until the mission ends.
Everything random comes from the scenario's one ``numpy.random.Generator``,
which numba draws from directly (same bit generator, same algorithms, same
order: the sensors' block refills and the ``noisy`` events' single draws
interleave exactly as in the Python loop).

Only the in-process ``CtypesLink`` has a C function to call; the wire links
(serial, CAN, QEMU) keep the Python loop. ``Mission.run(compiled=False)``
forces the Python loop, which the identity tests compare against.
"""

from __future__ import annotations

import numba as nb
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from harness.events import apply_events
from sim_plant.candle import CS_EXT_AT, CS_KNOCKED, CS_LIT, update_kernel
from sim_plant.drivetrain import S_LEFT, S_RIGHT, S_TH, S_X, S_Y
from sim_plant.plant import S_CONTACTS, S_FAN, S_IN_CONTACT, _advance
from sim_plant.sensors.suite import _sample_kernel

# Why the kernel stopped (loop.py turns these into outcome and detail).
END_DONE, END_FAILED, END_CONTACT, END_STUCK, END_FIND_LIMIT, END_RETURN_LIMIT, END_TICKS = range(1, 8)
END_CANDLE = 8  # the robot knocked the candle over


@intrinsic
def _call_step(typingctx, fn, st, inp, out):  # type: ignore[no-untyped-def]
    """``((void (*)(void *, void *, void *)) fn)(st, inp, out)`` on raw addresses (intp)."""
    if not all(isinstance(a, types.Integer) for a in (fn, st, inp, out)):
        return None
    sig = types.void(fn, st, inp, out)

    def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
        vp = ir.IntType(8).as_pointer()
        fnty = ir.FunctionType(ir.VoidType(), [vp, vp, vp])
        f = builder.inttoptr(args[0], fnty.as_pointer())
        builder.call(f, [builder.inttoptr(a, vp) for a in args[1:]])
        return context.get_dummy_value()

    return sig, codegen


# Packing the inputs and recording the trace: shared with loop.py's Python loop
# (which checks the byte offsets against the ABI).
@nb.njit(cache=True)
def _pack(u32: np.ndarray, i32: np.ndarray, u16: np.ndarray, u8: np.ndarray,
          t_ms: int, seq: int, hw: np.ndarray, start: int) -> None:
    u32[0] = t_ms
    u32[1] = seq
    i32[2] = hw[8]
    i32[3] = hw[9]
    for i in range(5):
        u16[8 + i] = hw[i]
    u16[13] = hw[5]
    u16[14] = hw[6]
    u8[30] = hw[7]
    u8[31] = start


@nb.njit(cache=True)
def _record(tf: np.ndarray, ti: np.ndarray, k: int, t: float, x: float, y: float, th: float,
            o16: np.ndarray, o8: np.ndarray, hw: np.ndarray, contact: int) -> None:
    tf[k, 0] = t
    tf[k, 1] = x
    tf[k, 2] = y
    tf[k, 3] = th
    ti[k, 0] = o16[2]
    ti[k, 1] = o16[3]
    ti[k, 2] = o8[8]
    ti[k, 3] = o8[9]
    ti[k, 4] = o8[13]
    ti[k, 5] = o8[14]
    ti[k, 6] = contact
    for c in range(hw.shape[0]):
        ti[k, 7 + c] = hw[c]


@nb.njit(cache=True)
def mission_kernel(fn_step: int, st_ptr: int, in_ptr: int, out_ptr: int,
                   u32: np.ndarray, i32: np.ndarray, u16: np.ndarray, in8: np.ndarray,
                   o16: np.ndarray, o8: np.ndarray, hw: np.ndarray,
                   tf: np.ndarray, ti: np.ndarray, record: bool,
                   ir_cfg: np.ndarray, ir_state: np.ndarray, scfg: np.ndarray, sst: np.ndarray,
                   edges: np.ndarray, wall_polys: np.ndarray, doors: np.ndarray, npar: np.ndarray,
                   normals: np.ndarray, uniforms: np.ndarray, npos: np.ndarray,
                   srcs: np.ndarray, beam: np.ndarray, scratch: np.ndarray,
                   enorm: np.ndarray, esoa: np.ndarray, wsoa: np.ndarray, keep: np.ndarray,
                   rng: np.random.Generator,
                   ev: np.ndarray, ev_state: np.ndarray, ev_active: np.ndarray,
                   S: np.ndarray, P: np.ndarray, poly: np.ndarray, walls: np.ndarray,
                   bbox: np.ndarray, n_sub: int,
                   cs: np.ndarray, cp: np.ndarray,
                   period_ms: int, start_tick: int, max_ticks: int, find_limit_s: float,
                   return_limit_s: float, stop_on_contact: bool, flag_done: int, flag_failed: int,
                   ) -> tuple[int, int, float]:
    """Run ticks until the mission ends; returns (END_* code, ticks run, time of the last tick)."""
    period = period_ms / 1000.0
    stuck_s = 0.0
    k = 0
    t = 0.0
    while True:
        t_ms = k * period_ms
        t = t_ms / 1000.0
        if _sample_kernel(t, S[S_X], S[S_Y], S[S_TH], S[S_LEFT + 2], S[S_RIGHT + 2],
                          cs[CS_LIT] != 0.0, hw, ir_cfg, ir_state, scfg, sst, edges, wall_polys,
                          doors, npar, normals, uniforms, npos, srcs, beam, scratch, enorm, esoa,
                          wsoa, keep):
            # NoiseStream.refill: the normals, then the uniforms, from the one Generator
            for i in range(normals.shape[0]):
                normals[i] = rng.standard_normal()
            for i in range(uniforms.shape[0]):
                uniforms[i] = rng.random()
            npos[0] = 0
            npos[1] = 0
        if ev.shape[0] > 0:
            apply_events(t, hw, ev, ev_state, ev_active, rng)
        _pack(u32, i32, u16, in8, t_ms, k, hw, 1 if k >= start_tick else 0)
        _call_step(fn_step, st_ptr, in_ptr, out_ptr)
        pwm_l = np.int64(o16[2])
        pwm_r = np.int64(o16[3])
        fan = o8[8] != 0
        flags = np.int64(o8[13])
        if record:
            _record(tf, ti, k, t, S[S_X], S[S_Y], S[S_TH], o16, o8, hw,
                    1 if S[S_IN_CONTACT] != 0.0 else 0)
        k += 1
        if flags & flag_done:  # the contract: a mission ends on DONE or FAILED in outputs.flags
            return END_DONE, k, t
        if flags & flag_failed:
            return END_FAILED, k, t
        S[S_FAN] = 1.0 if fan else 0.0  # Plant.apply's fan
        if n_sub:
            _advance(S, P, poly, walls, bbox, pwm_l, pwm_r, n_sub)
        update_kernel(cs, cp, edges, t + period, period, fan, S[S_X], S[S_Y], S[S_TH])
        if cs[CS_KNOCKED] != 0.0:
            return END_CANDLE, k, t
        if stop_on_contact and S[S_CONTACTS] > 0.0:
            return END_CONTACT, k, t
        stuck_s = stuck_s + period if S[S_IN_CONTACT] != 0.0 else 0.0
        if stuck_s >= 5.0:
            return END_STUCK, k, t
        if cs[CS_LIT] != 0.0 and t + period >= find_limit_s:
            return END_FIND_LIMIT, k, t
        if cs[CS_LIT] == 0.0 and t + period - cs[CS_EXT_AT] >= return_limit_s:
            return END_RETURN_LIMIT, k, t
        if k >= max_ticks:
            return END_TICKS, k, t
