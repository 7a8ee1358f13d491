"""The peer libraries' step and fit, measured the way their documentation uses them.

movement_primitives (DFKI): ``DMP(n_dims=1, execution_time=T, dt=1 ms, n_weights_per_dim=N,
int_dt=1 ms)``, ``imitate(T, Y)``, then either ``step(y, yd, step_function=...)`` once per tick
(the closed-loop API) or ``open_loop(step_function=...)`` (the API of its own benchmarks/).
Its compiled steps are ``euler-cython`` (the same integration scheme as forceskill's step) and
``rk4-cython`` (the library's default). pydmps: ``DMPs_discrete(n_dmps=1, n_bfs=N, dt=...)``,
``imitate_path(y_des)``, ``step()`` per tick; pydmps normalises every movement to a run time
of 1, so a T s demonstration at 1 kHz is ``dt = 1/(T*1000)``: the same number of samples and
steps, the same work per step.

Every library imitates the same samples: the learning target ``x* = f/k`` of bench/peers/demo.py.
Times are wall-clock ``time.perf_counter_ns`` with the garbage collector off during a measured
loop (as ``timeit`` does).
"""

from __future__ import annotations

import gc
import time
import tracemalloc
from collections.abc import Callable
from typing import Any

import numpy as np
from demo import Demo


# ---------------------------------------------------------------------------------------------
# movement_primitives
def mp_fit(demo: Demo, n_kernels: int) -> Any:
    """movement_primitives: a 1-D DMP imitating x* (construction + imitate, as its docs do)."""
    from movement_primitives.dmp import DMP

    y = demo.target_m[:, np.newaxis]
    dmp = DMP(n_dims=1, execution_time=demo.duration_s, dt=0.001, n_weights_per_dim=n_kernels, int_dt=0.001)
    dmp.imitate(demo.t_s, y)
    return dmp


def mp_step_ns(dmp: Any, n_steps: int, step_function: str) -> float:
    """ns per DMP.step(last_y, last_yd, step_function) over n_steps ticks from the start."""
    dmp.reset()
    y = np.copy(dmp.start_y)
    yd = np.zeros_like(y)
    step = dmp.step

    def loop() -> None:
        nonlocal y, yd
        for _ in range(n_steps):
            y, yd = step(y, yd, step_function=step_function)

    return gc_off_ns(loop) / n_steps


def mp_open_loop_ns(dmp: Any, step_function: str, run_t: float | None = None) -> float:
    """ns per step of DMP.open_loop(step_function) (the call movement_primitives' benchmarks time)."""
    steps = []
    ns = gc_off_ns(lambda: steps.append(len(dmp.open_loop(run_t=run_t, step_function=step_function)[0]) - 1))
    return ns / steps[0]


# ---------------------------------------------------------------------------------------------
# pydmps
def pydmps_fit(demo: Demo, n_kernels: int) -> Any:
    """pydmps: DMPs_discrete imitating x* over its normalised run time (dt = 1/(samples - 1))."""
    import pydmps.dmp_discrete

    n = demo.t_s.size
    dmp = pydmps.dmp_discrete.DMPs_discrete(n_dmps=1, n_bfs=n_kernels, dt=1.0 / (n - 1))
    dmp.imitate_path(y_des=demo.target_m[np.newaxis, :])
    return dmp


def pydmps_step_ns(dmp: Any, n_steps: int) -> float:
    """ns per DMPs.step() over n_steps ticks from the start."""
    dmp.reset_state()
    step = dmp.step

    def loop() -> None:
        for _ in range(n_steps):
            step()

    return gc_off_ns(loop) / n_steps


# ---------------------------------------------------------------------------------------------
# timing and memory helpers
def time_ms(fn: Callable[[], Any]) -> float:
    """Wall time of one call in ms (garbage collector off during the call)."""
    gc.collect()
    return gc_off_ns(fn) / 1e6


def gc_off_ns(fn: Callable[[], Any]) -> int:
    """Wall time of one call in ns with the garbage collector off during it (as timeit does)."""
    gc_was = gc.isenabled()
    gc.disable()
    try:
        t0 = time.perf_counter_ns()
        fn()
        return time.perf_counter_ns() - t0
    finally:
        if gc_was:
            gc.enable()


def peak_kib(fn: Callable[[], Any]) -> float:
    """Peak traced memory (tracemalloc, includes numpy's buffers) of one call, in KiB."""
    gc.collect()
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        base = tracemalloc.get_traced_memory()[0]
        result = fn()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    del result
    return (peak - base) / 1024.0


def mp_fit_error_pct(dmp: Any, demo: Demo) -> float:
    """Max |x* - y| of the movement_primitives rollout, % of max x* (sanity: it did fit)."""
    t, y = dmp.open_loop(step_function="euler-cython")
    yi = np.interp(demo.t_s, t, y[:, 0])
    return float(np.max(np.abs(yi - demo.target_m)) / np.max(demo.target_m) * 100.0)


def pydmps_fit_error_pct(dmp: Any, demo: Demo) -> float:
    """Max |x* - y| of the pydmps rollout, % of max x* (sanity: it did fit)."""
    y, _, _ = dmp.rollout()
    yi = y[:, 0]
    ref = demo.target_m[: yi.size]
    return float(np.max(np.abs(yi - ref)) / np.max(demo.target_m) * 100.0)
