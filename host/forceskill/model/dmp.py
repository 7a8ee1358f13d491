"""The learned force DMP in numpy: the reference the C core (firmware/core/dmp.c) is checked against.

docs/math.md section 2 is the algorithm, step for step. The DMP runs in force units: the state
``[u, v, I, y, z]`` (u = u~, v = v~, the normalised phase; y = k*x - f0, the force above the starting
force f0, in N; g, z, I and h in N, the weights dimensionless) is zero at t = 0; forward Euler with every right-hand side at
the old state:

    h  = g_e * v * S(u)
    y' = y + dt/tau_e * (z - y - gamma*I + h + c_y)
    z' = z + dt/tau_e * alpha*(beta*(g_e - y) - z)
    I' = I + dt/tau_e * y
    v' = v + dt/tau_e * alpha*(beta*(1 - u) - v)
    u' = u + dt/tau_e * v
    f_hat = f0 + y'

Nothing in it depends on the stiffness k (it enters only the execution reference x_d = surface +
f_hat/k and the controller's k_f = kkf/k, k_i = kki/k).

``rollout`` runs that loop literally (one Python step per tick, kernels vectorised over all ticks,
since the phase does not depend on x). ``linear_scan`` is the same recursion evaluated in blocks,
used by the fit for speed and checked against the loop in tests/host/model/test_dmp.py.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Iterator, Sequence

import numpy as np

from .scales import check_scales, check_steps
from .skill import Skill

#: Kernels with (u - c_i)^2/(2 sigma_i^2) above this are skipped (DMP_KERNEL_CUTOFF_EXP, dmp.h).
KERNEL_CUTOFF_EXP = 23.0
_ROW_CHUNK = 4096
#: Values (rows x kernels) per block of ``kernel_blocks``.
KERNEL_BLOCK_VALUES = 1 << 17
#: Steps per block of ``phase_blocks`` (the fit's passes over a recording).
FIT_BLOCK = 1 << 15


def kernel_exponents(u: np.ndarray, centres: np.ndarray, widths: np.ndarray) -> np.ndarray:
    """e[n, i] = (u_n - c_i)^2 / (2 sigma_i^2), computed as d*d*half_inv_var like the C core's
    float/double layer (fs_num_real.h, kernel_scale = 1/(2 sigma^2))."""
    half_inv_var = 1.0 / (2.0 * widths * widths)
    d = np.asarray(u, dtype=float)[:, None] - centres[None, :]
    e: np.ndarray = d * d * half_inv_var[None, :]
    return e


def normalised_kernels(u: np.ndarray, centres: np.ndarray, widths: np.ndarray) -> np.ndarray:
    """Matrix K[n, i] = psi_i(u_n)/sum_j psi_j(u_n) with the cutoff rule of docs/math.md section 2.

    Kernels with e_i > 23 get 0; psi_i = exp(-(e_i - e_min)) over the rest; a row with no kernel
    within the cutoff puts 1 on the nearest kernel (smallest e_i, the first on a tie).
    S(u_n) = K[n] @ w. A non-decreasing u (every rollout and fit) is evaluated only inside each
    kernel's band of rows, the same numbers as the dense evaluation (tested).
    """
    u = np.asarray(u, dtype=float).reshape(-1)
    if u.size > 1 and np.all(np.diff(u) >= 0.0):
        banded: np.ndarray = _normalised_kernels_banded(u, centres, widths).T
        return banded
    return _normalised_kernels_dense(u, centres, widths)


def _normalised_kernels_dense(u: np.ndarray, centres: np.ndarray, widths: np.ndarray) -> np.ndarray:
    out = np.empty((u.size, centres.size))
    for r0 in range(0, u.size, _ROW_CHUNK):
        e = kernel_exponents(u[r0 : r0 + _ROW_CHUNK], centres, widths)
        e_act = np.where(e <= KERNEL_CUTOFF_EXP, e, np.inf)
        e_min = e_act.min(axis=1)
        none = ~np.isfinite(e_min)
        e_min[none] = 0.0
        psi = np.exp(-(e_act - e_min[:, None]))  # exp(-inf) = 0 for skipped kernels
        if none.any():
            rows = np.flatnonzero(none)
            psi[rows] = 0.0
            psi[rows, np.argmin(e[rows], axis=1)] = 1.0
        out[r0 : r0 + psi.shape[0]] = psi / psi.sum(axis=1, keepdims=True)
    return out


def _normalised_kernels_banded(u: np.ndarray, centres: np.ndarray, widths: np.ndarray) -> np.ndarray:
    """Transposed kernel matrix (N, n) for non-decreasing u; each kernel touches only its band."""
    n_k = centres.size
    half_inv_var = 1.0 / (2.0 * widths * widths)
    radius = np.sqrt(KERNEL_CUTOFF_EXP / half_inv_var) * (1.0 + 1e-6) + 1e-300
    lo = np.searchsorted(u, centres - radius, side="left")
    hi = np.searchsorted(u, centres + radius, side="right")
    e_t = np.full((n_k, u.size), np.inf)
    for i in range(n_k):
        if hi[i] > lo[i]:
            d = u[lo[i] : hi[i]] - centres[i]
            e = d * d * half_inv_var[i]
            e_t[i, lo[i] : hi[i]] = np.where(e <= KERNEL_CUTOFF_EXP, e, np.inf)
    e_min = e_t.min(axis=0)
    psi_t = np.zeros((n_k, u.size))
    for i in range(n_k):
        if hi[i] > lo[i]:
            sl = slice(lo[i], hi[i])
            psi_t[i, sl] = np.exp(-(e_t[i, sl] - e_min[sl]))
    none = np.flatnonzero(~np.isfinite(e_min))
    if none.size:
        e_full = kernel_exponents(u[none], centres, widths)
        psi_t[:, none] = 0.0
        psi_t[np.argmin(e_full, axis=1), none] = 1.0
    psi_t /= psi_t.sum(axis=0, keepdims=True)
    return psi_t


def kernel_blocks(
    u: np.ndarray, centres: np.ndarray, widths: np.ndarray, budget: int = KERNEL_BLOCK_VALUES
) -> Iterator[tuple[int, int, np.ndarray]]:
    """(r0, k0, psi) for consecutive rows r0:r0+psi.shape[1] of a non-decreasing ``u``: psi[j, n]
    = exp(-e) of kernel k0 + j at u[r0 + n] where e <= KERNEL_CUTOFF_EXP, else 0, every kernel
    within the cutoff of those rows among them; about ``budget`` values a block at most (the
    kernels are never all evaluated on every row: a long recording has up to 1024 of them).
    psi is kernel-major (a row of it is one kernel) and lives in a buffer the next block reuses.
    No e_min shift: e <= 23 cannot underflow and the normalised weights do not depend on it."""
    u = np.asarray(u, dtype=float).reshape(-1)
    half_inv_var = 1.0 / (2.0 * widths * widths)
    radius = np.sqrt(KERNEL_CUTOFF_EXP / half_inv_var) * (1.0 + 1e-6)
    lo = np.searchsorted(u, centres - radius, side="left")  # the rows each kernel reaches
    hi = np.searchsorted(u, centres + radius, side="right")
    most = max(64, budget // 16)
    values = np.empty(max(budget, 64 * centres.size))
    inside = np.empty(values.size, dtype=bool)
    rows = most
    r0 = 0
    while r0 < u.size:
        r1 = min(u.size, r0 + rows)
        reach = np.flatnonzero((lo < r1) & (hi > r0))
        k0, k1 = (int(reach[0]), int(reach[-1]) + 1) if reach.size else (0, 0)
        if (r1 - r0) * (k1 - k0) > budget and r1 - r0 > 64:
            rows = max(64, (r1 - r0) // 2)  # many narrow kernels here: fewer rows
            continue
        shape = (k1 - k0, r1 - r0)
        e = values[: shape[0] * shape[1]].reshape(shape)
        ok = inside[: e.size].reshape(shape)
        np.subtract(u[None, r0:r1], centres[k0:k1, None], out=e)
        np.multiply(e, e, out=e)
        e *= half_inv_var[k0:k1, None]
        np.less_equal(e, KERNEL_CUTOFF_EXP, out=ok)
        np.minimum(e, KERNEL_CUTOFF_EXP + 1.0, out=e)
        np.negative(e, out=e)
        psi = np.exp(e, out=e)
        psi *= ok
        yield r0, k0, psi
        r0 = r1
        rows = min(most, 2 * rows)


def normalise_rows(psi: np.ndarray) -> np.ndarray:
    """Kernel-major psi (``kernel_blocks``) divided in place by each row's sum over its kernels
    (rows without a kernel stay 0); returns the mask of the rows with one."""
    rowsum = psi.sum(axis=0)
    covered: np.ndarray = rowsum > 0.0
    psi *= np.reciprocal(np.where(covered, rowsum, 1.0))
    return covered


def kernel_mix(
    u: np.ndarray, centres: np.ndarray, widths: np.ndarray, weights: Sequence[np.ndarray]
) -> list[np.ndarray]:
    """S(u) = sum_i w_i psi_i(u) / sum_i psi_i(u) for each weight vector at a non-decreasing u, by
    ``kernel_blocks``; a row no kernel reaches takes the nearest kernel's weight (the smallest
    e_i, the first on a tie), as ``normalised_kernels`` gives it."""
    u = np.asarray(u, dtype=float).reshape(-1)
    out = [np.empty(u.size) for _ in weights]
    term = np.empty(0)
    for r0, k0, psi in kernel_blocks(u, centres, widths):
        covered = normalise_rows(psi)
        r1 = r0 + psi.shape[1]
        term = np.empty(psi.shape[1]) if term.size < psi.shape[1] else term[: psi.shape[1]]
        for s, w in zip(out, weights, strict=True):
            # kernel by kernel in their order: a row's sum does not depend on which kernels share
            # its block (a matrix product's would), so any blocks give the same numbers
            acc = s[r0:r1]
            acc.fill(0.0)
            for j, w_j in enumerate(w[k0 : k0 + psi.shape[0]].tolist()):
                acc += np.multiply(psi[j], w_j, out=term)
        if not covered.all():
            rows = r0 + np.flatnonzero(~covered)
            nearest = np.argmin(kernel_exponents(u[rows], centres, widths), axis=1)
            for s, w in zip(out, weights, strict=True):
                s[rows] = w[nearest]
    return out


def _mixes(u: np.ndarray, skill: Skill, weights: list[np.ndarray]) -> list[np.ndarray]:
    """``kernel_mix`` for a non-decreasing u (every rollout: no (rows, N) matrix), else the
    normalised kernels' matrix times each weight vector."""
    u = np.asarray(u, dtype=float).reshape(-1)
    if u.size > 1 and bool(np.all(u[1:] >= u[:-1])):
        return kernel_mix(u, skill.centres, skill.widths, weights)
    k = normalised_kernels(u, skill.centres, skill.widths)
    return [k @ w for w in weights]


def forcing_scale(u: np.ndarray, skill: Skill) -> np.ndarray:
    """S(u) = sum psi_i w_i / sum psi_i for every u (the kernel part of h = g*v*S(u))."""
    return _mixes(u, skill, [skill.weights])[0]


def phase_loop(alpha: float, beta: float, a: float, n_steps: int) -> tuple[np.ndarray, np.ndarray]:
    """u~_n, v~_n for n = 0..n_steps, a = dt/tau_e; the literal forward-Euler loop."""
    u = np.empty(n_steps + 1)
    v = np.empty(n_steps + 1)
    uu = vv = 0.0
    u[0] = v[0] = 0.0
    for n in range(1, n_steps + 1):
        uu, vv = uu + a * vv, vv + a * alpha * (beta * (1.0 - uu) - vv)
        u[n] = uu
        v[n] = vv
    return u, v


def transform_loop(
    alpha: float,
    beta: float,
    gamma: float,
    a: float,
    goal: float | np.ndarray,
    h: np.ndarray,
    c_x: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x_n, z_n, I_n for n = 0..len(h) from zero state, forcing h_n and goal g_n (scalar or per step).

    The literal loop of docs/math.md section 2 (x, z, I part); ``c_x`` is the coupling term.
    """
    m = len(h)
    g = np.broadcast_to(np.asarray(goal, dtype=float), (m,))
    cx = np.zeros(m) if c_x is None else np.asarray(c_x, dtype=float)
    x = np.empty(m + 1)
    z = np.empty(m + 1)
    big_i = np.empty(m + 1)
    xx = zz = ii = 0.0
    x[0] = z[0] = big_i[0] = 0.0
    hl = h.tolist()
    gl = g.tolist()
    cl = cx.tolist()
    for n in range(m):
        xx, zz, ii = (
            xx + a * (zz - xx - gamma * ii + hl[n] + cl[n]),
            zz + a * alpha * (beta * (gl[n] - xx) - zz),
            ii + a * xx,
        )
        x[n + 1] = xx
        z[n + 1] = zz
        big_i[n + 1] = ii
    return x, z, big_i


def _powers(a_mat: np.ndarray, count: int) -> np.ndarray:
    """A^0 .. A^count as an array (count+1, d, d)."""
    d = a_mat.shape[0]
    p = np.empty((count + 1, d, d))
    p[0] = np.eye(d)
    for k in range(1, count + 1):
        p[k] = a_mat @ p[k - 1]
    return p


@functools.lru_cache(maxsize=16)
def _scan_plan(a_bytes: bytes, d: int, L: int) -> tuple[np.ndarray, np.ndarray]:
    """``linear_scan``'s powers A^0..A^L and its block-Toeplitz matrix for one A, kept: a long
    recording is scanned block by block with the same few matrices."""
    p = _powers(np.frombuffer(a_bytes).reshape(d, d), L)
    # Toeplitz: y_k = sum_{j<k} A^(k-1-j) b_j for k = 1..L  ->  Y[(k-1)*d + r] = T[...] @ bflat
    kk = np.arange(L)[:, None]  # row block k-1
    jj = np.arange(L)[None, :]  # column block j
    lag = kk - jj  # power k-1-j, valid for j <= k-1
    t4 = np.where((lag >= 0)[:, :, None, None], p[np.clip(lag, 0, L)], 0.0)  # (L, L, d, d)
    t = np.ascontiguousarray(t4.transpose(0, 2, 1, 3).reshape(L * d, L * d))
    p.setflags(write=False)
    t.setflags(write=False)
    return p, t


def linear_scan(
    a_mat: np.ndarray, b: np.ndarray, s0: np.ndarray | None = None, block: int = 64
) -> np.ndarray:
    """States s_0..s_M of s_{n+1} = A s_n + b_n (b: (M, d)) evaluated in blocks.

    Within a block the response to b is one matrix product with a block-Toeplitz matrix of
    powers of A; only the block boundaries are propagated sequentially. Equal to the sequential
    loop within round-off (tests: 1e-12 relative on the fit's recursions).
    """
    a_mat = np.atleast_2d(np.asarray(a_mat, dtype=float))
    d = a_mat.shape[0]
    b = np.asarray(b, dtype=float).reshape(-1, d)
    m = b.shape[0]
    s0v = np.zeros(d) if s0 is None else np.asarray(s0, dtype=float).reshape(d)
    out = np.empty((m + 1, d))
    out[0] = s0v
    if m == 0:
        return out
    L = max(1, min(block, m))
    nb = -(-m // L)
    p, t = _scan_plan(a_mat.tobytes(), d, L)
    bp = np.zeros((nb * L, d))
    bp[:m] = b
    y = (bp.reshape(nb, L * d) @ t.T).reshape(nb, L, d)  # y[mb, k-1] = local state at k
    a_l = p[L]
    if nb > 64:  # the block boundaries are the same kind of recursion (A^L, y_L): scan it too
        starts = linear_scan(a_l, y[:, L - 1], s0v, block=16)[:-1]
    else:
        starts = np.empty((nb, d))
        s = s0v.copy()
        for mb in range(nb):
            starts[mb] = s
            s = a_l @ s + y[mb, L - 1]
    # s_{mb*L + k} = A^k s_start + y_k, k = 1..L
    full = (starts @ p[1:].reshape(L * d, d).T).reshape(nb, L, d) + y
    out[1:] = full.reshape(nb * L, d)[:m]
    return out


def phase_scan(alpha: float, beta: float, a: float, n_steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Same as ``phase_loop`` via ``linear_scan`` (fast; round-off level differences)."""
    a_mat = np.array([[1.0, a], [-a * alpha * beta, 1.0 - a * alpha]])
    b = np.tile([0.0, a * alpha * beta], (n_steps, 1))
    s = linear_scan(a_mat, b)
    return s[:, 0], s[:, 1]


def phase_blocks(
    alpha: float, beta: float, a: float, n_steps: int, block: int | None = None
) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
    """(i0, u, v): u~_n, v~_n for n = i0..i0 + len(u) - 1, consecutive blocks of ``block`` steps
    (FIT_BLOCK unless given) sharing their end sample (the next block starts at the last n of
    this one, so a block holds n and n+1 of every step in it) through n = n_steps:
    ``phase_scan`` in blocks, the state carried (round-off level differences), memory bounded by
    the block. The same arguments give the same numbers each time (the fit passes twice)."""
    block = block or FIT_BLOCK
    a_mat = np.array([[1.0, a], [-a * alpha * beta, 1.0 - a * alpha]])
    b = np.tile([0.0, a * alpha * beta], (max(1, min(block, n_steps)), 1))
    s0 = np.zeros(2)
    for i0 in range(0, max(n_steps, 1), block):
        s = linear_scan(a_mat, b[: min(block, n_steps - i0)], s0)
        yield i0, s[:, 0], s[:, 1]
        s0 = s[-1]


def transform_scan(
    alpha: float, beta: float, gamma: float, a: float, goal: float, h: np.ndarray, chunk: int = 1 << 16
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Same as ``transform_loop`` (constant goal) via ``linear_scan``, ``chunk`` steps at a time
    (the state carried from one chunk to the next), so its temporaries do not grow with len(h)."""
    h = np.asarray(h, dtype=float).reshape(-1)
    out = np.empty((h.size + 1, 3))
    out[0] = 0.0
    for i0 in range(0, max(h.size, 1), chunk):
        hb = h[i0 : i0 + chunk]
        out[i0 : i0 + hb.size + 1] = transform_block(alpha, beta, gamma, a, goal, hb, out[i0])
    return out[:, 0], out[:, 1], out[:, 2]


def transform_block(
    alpha: float, beta: float, gamma: float, a: float, goal: float, h: np.ndarray, state: np.ndarray
) -> np.ndarray:
    """The states (x, z, I) before and after each step of forcing ``h`` from ``state``: shape
    (len(h) + 1, 3), ``transform_scan``'s recursion for one block."""
    a_mat = np.array([[1.0 - a, a, -a * gamma], [-a * alpha * beta, 1.0 - a * alpha, 0.0], [a, 0.0, 1.0]])
    b = np.zeros((h.size, 3))
    b[:, 0] = a * h
    b[:, 1] = a * alpha * beta * goal
    return linear_scan(a_mat, b, state)


def default_steps(skill: Skill, time_scale: float = 1.0) -> int:
    """round(T*time_scale/dt): the rollout writes rows 0..this."""
    return int(round(skill.duration_s * time_scale / skill.dt_s))


#: Rows per block of ``rollout_blocks`` (memory: a few N x block arrays of float64).
ROLLOUT_BLOCK = 16384


def rollout_blocks(
    skill: Skill,
    goal_scale: float = 1.0,
    time_scale: float = 1.0,
    n_steps: int | None = None,
    block: int = ROLLOUT_BLOCK,
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """``rollout`` in consecutive blocks of rows (t, f_hat), the same numbers, memory bounded by
    the block; scales and the step count are checked first (109, 663)."""
    check_scales(goal_scale, time_scale)
    n = default_steps(skill, time_scale) if n_steps is None else int(n_steps)
    check_steps(n)
    a = skill.dt_s / (skill.tau_s * time_scale)
    g_e = skill.goal_N * goal_scale
    alpha, beta, gamma, f0 = skill.alpha, skill.beta, skill.gamma, skill.force0_N
    uu = vv = xx = zz = ii = 0.0
    start = 0
    while start <= n:
        m = min(block, n + 1 - start)
        u = np.empty(m)
        v = np.empty(m)
        ul: list[float] = [0.0] * m
        vl: list[float] = [0.0] * m
        for j in range(m):  # rows start..start+m-1; (uu, vv) is row start+j
            ul[j] = uu
            vl[j] = vv
            uu, vv = uu + a * vv, vv + a * alpha * (beta * (1.0 - uu) - vv)
        u[:] = ul
        v[:] = vl
        with np.errstate(all="ignore"):  # a hostile skill overflows to inf: the caller judges it
            hl = (g_e * v * forcing_scale(u, skill)).tolist()
        xl: list[float] = [0.0] * m
        for j in range(m):  # y of row start+j, then one step with that row's forcing
            xl[j] = xx
            xx, zz, ii = (
                xx + a * (zz - xx - gamma * ii + hl[j]),
                zz + a * alpha * (beta * (g_e - xx) - zz),
                ii + a * xx,
            )
        with np.errstate(all="ignore"):
            f = f0 + np.asarray(xl)  # the DMP runs in N above the starting force
        yield np.arange(start, start + m) * skill.dt_s, f
        start += m


def rollout(
    skill: Skill, goal_scale: float = 1.0, time_scale: float = 1.0, n_steps: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """t_n = n*dt and f_hat_n = f0 + y_n for n = 0..n_steps (default round(T*time_scale/dt)).

    The DMP alone (docs/math.md section 2): the end policy after T is applied by the executor. The
    goal scale multiplies the part above the starting force: f_hat - f0 scales exactly by it.
    """
    blocks = list(rollout_blocks(skill, goal_scale, time_scale, n_steps))
    return np.concatenate([b[0] for b in blocks]), np.concatenate([b[1] for b in blocks])


def rollout_peak(skill: Skill, goal_scale: float = 1.0, time_scale: float = 1.0) -> float:
    """max |f_hat| over the default rollout (inf if any value is not finite)."""
    peak = 0.0
    for _, f in rollout_blocks(skill, goal_scale, time_scale):
        if not np.all(np.isfinite(f)):
            return math.inf
        if f.size:
            peak = max(peak, float(np.max(np.abs(f))))
    return peak


def forcing_scales(u: np.ndarray, skill: Skill) -> tuple[np.ndarray, np.ndarray | None]:
    """S(u) of the force DMP and S_y(u) of the y DMP (None for a force-only skill) from one
    evaluation of the normalised kernels: both DMPs share the phase and the kernels."""
    if skill.y_weights is None:
        return forcing_scale(u, skill), None
    s_x, s_y = _mixes(u, skill, [skill.weights, skill.y_weights])
    return s_x, s_y


def rollout_path(
    skill: Skill, time_scale: float = 1.0, path_scale: float = 1.0, n_steps: int | None = None
) -> tuple[np.ndarray, np.ndarray]:
    """t_n and y_hat_n = y_start + p_n of the position DMP on y (paper eq. 9: the force DMP's law
    with k_f = k_i = 0, so gamma = 0 and beta_y = k_p/(m_d*alpha) - 1), n = 0..n_steps:

        h_y = s_p * v * S_y(u)
        p'  = p + dt/tau_e * (z_p - p + h_y)
        z_p' = z_p + dt/tau_e * alpha*(beta_y*(s_p*g_y - p) - z_p)

    from zero state on the force DMP's phase (the same u, v, tau_e: time scaling stretches both).
    s_p = path_scale scales p exactly (p is linear in s_p from a zero state): the path scales
    about its start. The goal scale of the force does not enter. A force-only skill gives y_start.
    """
    from .scales import check_path_scale

    check_scales(1.0, time_scale)
    check_path_scale(path_scale)
    n = default_steps(skill, time_scale) if n_steps is None else int(n_steps)
    check_steps(n)
    t = np.arange(n + 1) * skill.dt_s
    if skill.y_weights is None:
        return t, np.full(n + 1, skill.y_start_m)
    a = skill.dt_s / (skill.tau_s * time_scale)
    u, v = phase_loop(skill.alpha, skill.beta, a, n)
    with np.errstate(all="ignore"):
        h = path_scale * v[:-1] * _mixes(u[:-1], skill, [skill.y_weights])[0]
    p, _, _ = transform_loop(skill.alpha, skill.beta_y, 0.0, a, path_scale * skill.goal_y_m, h)
    with np.errstate(all="ignore"):
        y = skill.y_start_m + p
    return t, y
