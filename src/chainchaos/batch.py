"""A batch engine: B trajectories integrated at once, vectorised across trajectories.

``integrators.advance`` integrates one trajectory; its bond loop runs over N+1 = 41 bonds, too
short for wide SIMD to pay off and full of loop-carried index arithmetic. Here every array has the
trajectory index innermost and contiguous, shape (site, B) or (bond, B), so each inner loop runs
over B independent trajectories with unit stride: the square roots of the Hertz force, the
polynomial FPUT force and the whole tangent map run in SIMD lanes, one trajectory per lane.

The trajectories of a batch share the model, the scheme, dt and the number of steps; each has its
own state, deviation vector and chain parameters (per-trajectory arrays shaped (N+1, B) for bond
parameters and (N, B) for inverse masses: one chain repeated, or B different realizations).

Semantics are those of ``integrators.advance`` lane by lane (the tests check agreement to
round-off): the same kick/drift table (``integrators.SCHEMES``), a force evaluation reused by the
next kick when no drift came in between, the tangent map drift(c): dq += c dt M^-1 dp,
kick(d): dp -= d dt Hess V(u) dq with Hess V tridiagonal from the bond stiffness, and every
``check_every`` steps and at the end of a call the deviation vector of each trajectory is
renormalised, its log growth added to ``log_growth[j]``. A trajectory whose state becomes
non-finite is reported in ``bad[j]`` (the step of the first failed check) while the other lanes go
on: lanes never mix.

Throughput (benchmarks/batch_throughput.py, CPU time, N = 40, SRKN6b with tangent map, AVX-512):
about 0.34-0.36 us per step and trajectory at 64-128 lanes against 0.39 us for
``integrators.advance``, which is itself vectorised across the (padded) bonds; at 8-16 lanes the
batch is slower (LLVM's vectorised lane loops need >= 32 iterations). Against the scalar
single-trajectory kernel it replaced (commit 05c2853, 0.79 us Hertz / 0.62 us FPUT) the batch
engine is 2.2x / 1.7x faster.
"""

import numpy as np
from numba import njit

from chainchaos.errors import require
from chainchaos.integrators import get_scheme
from chainchaos.models import HERTZ, coefficients, model_id

#: Lanes per batch the scan pads to (a multiple of AVX-512's 8 doubles).
LANE_MULTIPLE = 8


@njit(cache=True, error_model="numpy")
def _sweep(hertz, tangent, U, DQ, p, dp, inv_mass, A, delta, K2, K3, K4, F, K, a, c, do_drift, do_kick):
    """One pass over the chain: drift(a) of every bead, the forces (and stiffnesses) at the new
    positions, kick(c) of every bead, in one sweep over the beads so that the rows in use stay in
    L1 cache; each operation is its own loop over the lanes (few arrays per loop, so that LLVM
    vectorises it).

    Bead n (0-based) is row n+1 of U and DQ (walls at rows 0 and N+1); bond b joins rows b and
    b+1. At bead n the drift of row n+1 completes bond n, so bead n-1 can be kicked. Per element
    the arithmetic is that of separate drift, force and kick loops, in the same order.
    """
    N, B = p.shape
    for n in range(N + 1):
        if do_drift and n < N:
            for j in range(B):
                U[n + 1, j] += a * inv_mass[n, j] * p[n, j]
            if tangent:
                for j in range(B):
                    DQ[n + 1, j] += a * inv_mass[n, j] * dp[n, j]
        if do_kick:
            if hertz:
                for j in range(B):
                    x = max(delta[n, j] + U[n, j] - U[n + 1, j], 0.0)
                    s = np.sqrt(x)
                    F[n, j] = A[n, j] * x * s
                    K[n, j] = 1.5 * A[n, j] * s
            else:
                for j in range(B):
                    D = U[n, j] - U[n + 1, j]
                    F[n, j] = D * (K2[n, j] - D * (K3[n, j] - D * K4[n, j]))
                    K[n, j] = K2[n, j] - D * (2.0 * K3[n, j] - 3.0 * K4[n, j] * D)
            if n >= 1:
                m = n - 1
                for j in range(B):
                    p[m, j] += c * (F[m, j] - F[n, j])
                if tangent:
                    for j in range(B):
                        dp[m, j] += c * (K[m, j] * (DQ[m, j] - DQ[n, j]) - K[n, j] * (DQ[n, j] - DQ[n + 1, j]))


@njit(cache=True, error_model="numpy")
def _kick_only(tangent, DQ, p, dp, F, K, c):
    N, B = p.shape
    for n in range(N):
        for j in range(B):
            p[n, j] += c * (F[n, j] - F[n + 1, j])
        if tangent:
            for j in range(B):
                dp[n, j] += c * (K[n, j] * (DQ[n, j] - DQ[n + 1, j]) - K[n + 1, j] * (DQ[n + 1, j] - DQ[n + 2, j]))


@njit(cache=True, error_model="numpy")
def advance_batch(model, q, p, dq, dp, inv_mass, A, delta, K2, K3, K4, kicks, drifts, dt, n_steps,
                  tangent, check_every, track_gaps, gap_steps, log_growth, max_gaps, bad):
    """Advance B trajectories (q, p) of shape (N, B) and, if ``tangent``, their deviation vectors
    (dq, dp) by n_steps steps of the scheme (kicks, drifts).

    inv_mass (N, B); A, delta, K2, K3, K4 (N+1, B), bond b joining beads b-1 and b (walls at
    b = 0 and b = N). Every ``check_every`` steps and at the end: each lane's state is checked for
    finiteness (``bad[j]`` set to the step count of the first failed check if it is still < 0)
    and, with ``tangent``, its deviation vector renormalised, ln|v| added to ``log_growth[j]``.
    With ``track_gaps`` (Hertz) ``gap_steps[b, j]`` counts the steps bond b of lane j ends open
    (delta_b + u_{b-1} - u_b < 0) and ``max_gaps[j]`` keeps the largest number of simultaneously
    open bonds. All arrays must be C-contiguous; they are updated in place.

    A drift followed by a non-zero kick is done as one fused sweep (``_sweep``); a kick that
    follows a kick reuses the forces, as in ``integrators.advance``.
    """
    N, B = q.shape
    hertz = model == HERTZ
    # displacements and deviations with the walls: U[0] = U[N+1] = 0, bead n at row n+1
    U = np.zeros((N + 2, B))
    DQ = np.zeros((N + 2, B))
    for n in range(N):
        for j in range(B):
            U[n + 1, j] = q[n, j]
            DQ[n + 1, j] = dq[n, j]
    F = np.zeros((N + 1, B))
    K = np.zeros((N + 1, B))
    norm2 = np.zeros(B)
    check = np.zeros(B)
    n_open = np.zeros(B, dtype=np.int64)
    n_stages = drifts.shape[0]
    force_valid = False
    for step in range(n_steps):
        c = kicks[0] * dt
        if c != 0.0:
            if not force_valid:
                _sweep(hertz, tangent, U, DQ, p, dp, inv_mass, A, delta, K2, K3, K4, F, K, 0.0, 0.0,
                       False, True)
                # the sweep kicked with c = 0 (p += 0 * ...): exact no-op on finite states
                force_valid = True
            _kick_only(tangent, DQ, p, dp, F, K, c)
        for i in range(n_stages):
            a = drifts[i] * dt
            c = kicks[i + 1] * dt
            _sweep(hertz, tangent, U, DQ, p, dp, inv_mass, A, delta, K2, K3, K4, F, K, a, c, True,
                   c != 0.0)
            force_valid = c != 0.0
        if track_gaps:
            for j in range(B):
                n_open[j] = 0
            for b in range(N + 1):
                for j in range(B):
                    if delta[b, j] + U[b, j] - U[b + 1, j] < 0.0:
                        gap_steps[b, j] += 1
                        n_open[j] += 1
            for j in range(B):
                if n_open[j] > max_gaps[j]:
                    max_gaps[j] = n_open[j]
        if (step + 1) % check_every == 0 or step + 1 == n_steps:
            for j in range(B):
                check[j] = 0.0
            for n in range(N):
                for j in range(B):
                    check[j] += U[n + 1, j] + p[n, j]
            if tangent:
                for j in range(B):
                    norm2[j] = 0.0
                for n in range(N):
                    for j in range(B):
                        norm2[j] += DQ[n + 1, j] * DQ[n + 1, j] + dp[n, j] * dp[n, j]
                for j in range(B):
                    norm = np.sqrt(norm2[j])
                    log_growth[j] += np.log(norm)
                    norm2[j] = norm
                for n in range(N):
                    for j in range(B):
                        DQ[n + 1, j] /= norm2[j]
                        dp[n, j] /= norm2[j]
                for j in range(B):
                    check[j] += DQ[1, j]
            for j in range(B):
                if bad[j] < 0 and not np.isfinite(check[j]):
                    bad[j] = step + 1
    for n in range(N):
        for j in range(B):
            q[n, j] = U[n + 1, j]
            dq[n, j] = DQ[n + 1, j]


def lane_parameters(model: int, chains) -> dict[str, np.ndarray]:
    """Per-trajectory parameter arrays of the batch engine for a list of chains (one per lane).

    Returns inv_mass (N, B) and A, delta, K2, K3, K4 (N+1, B), C-contiguous, with the chains'
    own K4 sign; the harmonic model gets K3 = K4 = 0 (``models.coefficients``).
    """
    chains = list(chains)
    require(len(chains) >= 1, "chains", len(chains), "at least one chain")
    N = chains[0].N
    require(all(c.N == N for c in chains), "N", sorted({c.N for c in chains}), "one N per batch")
    cols = {k: [] for k in ("inv_mass", "A", "delta", "K2", "K3", "K4")}
    for chain in chains:
        K2, K3, K4 = coefficients(model, chain)
        for key, value in zip(cols, (1.0 / chain.mass, chain.A, chain.delta, K2, K3, K4)):
            cols[key].append(value)
    return {k: np.ascontiguousarray(np.stack(v, axis=1), dtype=float) for k, v in cols.items()}


class Batch:
    """B trajectories of one model under one scheme, advanced together by ``advance_batch``.

    ``q, p, dq, dp`` are (N, B) arrays (trajectory index last); ``log_growth`` (B,) accumulates
    ln|v| over renormalisations, so Lambda(t) = log_growth / t as in ``integrators.advance``.
    """

    def __init__(self, model: str | int, chains, q, p, dq=None, dp=None, integrator: str = "SRKN6b",
                 dt: float = 5e-4, tangent: bool = True, track_gaps: bool = False,
                 check_every: int = 1000):
        self.model = model_id(model) if isinstance(model, str) else int(model)
        require(not track_gaps or self.model == HERTZ, "track_gaps", track_gaps, "gaps only for Hertz")
        require(np.isfinite(dt) and dt > 0, "dt", dt, "a finite step > 0")
        require(int(check_every) >= 1, "check_every", check_every, "an integer >= 1")
        self.params = lane_parameters(self.model, chains)
        self.scheme = get_scheme(integrator)
        self.q = np.ascontiguousarray(q, dtype=float).copy()
        self.p = np.ascontiguousarray(p, dtype=float).copy()
        shape = self.q.shape
        require(self.p.shape == shape == self.params["inv_mass"].shape, "state shape", shape,
                f"(N, B) = {self.params['inv_mass'].shape}")
        self.dq = np.zeros(shape) if dq is None else np.ascontiguousarray(dq, dtype=float).copy()
        self.dp = np.zeros(shape) if dp is None else np.ascontiguousarray(dp, dtype=float).copy()
        self.dt, self.tangent, self.track_gaps = float(dt), bool(tangent), bool(track_gaps)
        self.check_every = int(check_every)
        N, B = shape
        self.gap_steps = np.zeros((N + 1, B), dtype=np.int64)
        self.max_gaps = np.zeros(B, dtype=np.int64)
        self.log_growth = np.zeros(B)
        self.bad = np.full(B, -1, dtype=np.int64)
        self.steps = 0

    @property
    def size(self) -> int:
        return self.q.shape[1]

    def advance(self, n_steps: int) -> None:
        """Advance every lane by n_steps; a lane that turned non-finite gets ``bad`` >= 0 (its
        absolute step count), the others are unaffected."""
        if n_steps <= 0:
            return
        bad = np.full(self.size, -1, dtype=np.int64)
        P = self.params
        advance_batch(self.model, self.q, self.p, self.dq, self.dp, P["inv_mass"], P["A"], P["delta"],
                      P["K2"], P["K3"], P["K4"], self.scheme.kicks, self.scheme.drifts, self.dt,
                      int(n_steps), self.tangent, self.check_every, self.track_gaps, self.gap_steps,
                      self.log_growth, self.max_gaps, bad)
        newly = (bad >= 0) & (self.bad < 0)
        self.bad[newly] = self.steps + bad[newly]
        self.steps += int(n_steps)


def warm_up() -> None:
    """Compile (or load from the on-disk cache) the batch kernel for both models, with and
    without the tangent map and gap counting."""
    from chainchaos.chain import random_chain

    chain = random_chain(0, 2.0, 4)
    for model, gaps in (("hertz", True), ("hertz", False), ("fput", False)):
        for tangent in (True, False):
            q = np.zeros((4, 2))
            q[1] = 0.1
            b = Batch(model, [chain, chain], q, np.zeros((4, 2)), dp=np.full((4, 2), 0.5), dt=0.1,
                      tangent=tangent, track_gaps=gaps, check_every=3)
            b.advance(4)
