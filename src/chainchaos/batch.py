"""A batch engine: B trajectories integrated at once, vectorised across trajectories.

``integrators.advance`` integrates one trajectory, vectorised across its bonds: every split step
makes separate passes over the bonds (forces, kick, drift), each storing what the next one loads.
Here the trajectories go in blocks of ``LANES`` (the SIMD width fitted to the CPU,
``chainchaos.simd``), one lane per trajectory: a drift, the forces and stiffnesses at the new
positions and a kick are one sweep over the bonds that keeps the neighbouring beads' vectors, and
a bead's momenta from its drift to its kick, in registers, so the square roots of the Hertz force
overlap with the rest of the work; forces are stored only where the next step's first kick reuses
them. A block's state and parameters live in one 64-byte aligned buffer, row by row (row r: the
LANES lanes of each of the ``QUANTITIES`` in turn): all a sweep touches fits in L1 cache, every
vector load is aligned, and no two quantities that one iteration reads and writes sit 4 KiB apart
(separately allocated arrays made the timing vary from one process to the next).

The trajectories of a batch share the model, the scheme, dt and the number of steps; each has its
own state, deviation vector and chain parameters (per-trajectory arrays shaped (N+1, B) for bond
parameters and (N, B) for inverse masses: one chain repeated, or B different realizations). A
batch of any size B is padded to whole blocks by repeating its last trajectory.
:class:`SerialBatch` offers the same interface on the single-trajectory engine, the cheaper one
for a lane or two.

Semantics are those of ``integrators.advance`` lane by lane, to the bit (tests/test_batch.py,
tests/test_lane_width.py, at every width): the same kick/drift table (``integrators.SCHEMES``),
the same floating-point operations in the same order, a force evaluation reused by the next kick
when no drift came in between, the tangent map drift(c): dq += c dt M^-1 dp, kick(d): dp -= d dt
Hess V(u) dq with Hess V tridiagonal from the bond stiffness, and every ``check_every`` steps and
at the end of a call the deviation vector of each trajectory renormalised, its log growth added
to ``log_growth[j]``. A trajectory whose state becomes non-finite is reported in ``bad[j]`` (the
step of the first failed check) while the other lanes go on: lanes never mix.

Speed: ``benchmarks/batch_throughput.py`` (figures in the README, per machine).
"""

import numpy as np
from numba import literally, njit

from chainchaos.errors import require
from chainchaos.integrators import _aligned_zeros, _renormalise, advance
from chainchaos.models import MAX_BOND_PARAMETERS
from chainchaos.models.base import bond_force, bond_force_stiffness, bond_opening
from chainchaos.simd import LANES, vbelow, vload, vstore

#: The per-row contents of a block's buffer, LANES doubles each. Row r of U and DQ is bead r-1
#: (the walls are rows 0 and N+1); row n of P, DP and IM is bead n; row b of the bond parameters
#: B0, B1, B2 (the model's, ``models.base``) and of the bond force F and stiffness K is bond b,
#: which joins beads b-1 and b.
QUANTITIES = ("U", "DQ", "P", "DP", "IM", "B0", "B1", "B2", "F", "K")
_U, _DQ, _P, _DP, _IM, _B0, _B1, _B2, _F, _K = (i * LANES for i in range(len(QUANTITIES)))
assert len(QUANTITIES) == 7 + MAX_BOND_PARAMETERS
#: Doubles per row of a block's buffer.
ROW = len(QUANTITIES) * LANES


@njit(cache=True, inline="always")
def _bond_parameters(Z, bond):
    """The bond parameters (B0, B1, B2) of the bond whose row starts at ``bond``, as vectors."""
    return vload(Z, bond + _B0), vload(Z, bond + _B1), vload(Z, bond + _B2)


@njit(cache=True, error_model="numpy")
def _sweep(model, tangent, drift, kick, keep_forces, N, Z, a, c):
    """One pass over the bonds b = 0..N of a block: (if ``drift``) drift(a) of bead b, then (if
    ``kick``) the force and stiffness of bond b at the new positions and kick(c) of bead b-1,
    whose two bonds are then both up to date; with ``keep_forces`` the forces and stiffnesses are
    stored for a kick that follows without a drift. A bead's momenta stay in registers from its
    drift to its kick, and a bond's force f and tangent force g = k (dq_{b-1} - dq_b) from the
    kick of the bead on its left to that of the bead on its right: each is computed once. Per lane
    the operations are those of ``integrators.advance``, in the same order. Row N (no bead) has zero momenta and inverse masses, so its drift leaves the right
    wall at zero and the loop needs no branch."""
    literally(tangent)
    literally(drift)
    literally(kick)
    literally(keep_forces)
    u_left = vload(Z, _U)  # the wall
    dq_left = vload(Z, _DQ)  # deviation of bead b-1
    p_left = vload(Z, _P)  # momenta of bead b-1 (row 0 is bead 0: its kick comes at b = 1)
    dp_left = p_left
    f_left = p_left  # force of bond b-1
    g_left = p_left  # tangent force k (dq_{b-2} - dq_{b-1}) of bond b-1
    for b in range(N + 1):
        bond = b * ROW
        bead = bond + ROW  # row of bead b in U and DQ
        u_right = vload(Z, bead + _U)
        dq_right = vload(Z, bead + _DQ)
        p_right = vload(Z, bond + _P)
        dp_right = vload(Z, bond + _DP) if tangent else p_right
        if drift:
            im = vload(Z, bond + _IM)
            u_right = u_right + a * im * p_right
            vstore(Z, bead + _U, u_right)
            if tangent:
                dq_right = dq_right + a * im * dp_right
                vstore(Z, bead + _DQ, dq_right)
        if kick:
            parameters = _bond_parameters(Z, bond)
            if tangent:
                f, k = bond_force_stiffness(model, parameters, u_left, u_right)
            else:
                f = bond_force(model, parameters, u_left, u_right)
                k = f
            if keep_forces:
                vstore(Z, bond + _F, f)
                if tangent:
                    vstore(Z, bond + _K, k)
            g = k * (dq_left - dq_right) if tangent else f
            if b >= 1:
                m = bond - ROW  # bead b-1
                vstore(Z, m + _P, p_left + c * (f_left - f))
                if tangent:
                    vstore(Z, m + _DP, dp_left + c * (g_left - g))
            f_left, g_left = f, g
        u_left = u_right
        dq_left = dq_right
        p_left, dp_left = p_right, dp_right


@njit(cache=True, error_model="numpy")
def _kick_only(tangent, N, Z, c):
    """kick(c) of every bead with the stored forces and stiffnesses (the tangent force of bond b,
    g_b = k_b (dq_{b-1} - dq_b), carried from one bead to the next)."""
    literally(tangent)
    f_left = vload(Z, _F)
    g_left = vload(Z, _K) * (vload(Z, _DQ) - vload(Z, ROW + _DQ)) if tangent else f_left
    for n in range(N):
        row = n * ROW
        f = vload(Z, row + ROW + _F)
        vstore(Z, row + _P, vload(Z, row + _P) + c * (f_left - f))
        f_left = f
        if tangent:
            g = vload(Z, row + ROW + _K) * (vload(Z, row + ROW + _DQ) - vload(Z, row + 2 * ROW + _DQ))
            vstore(Z, row + _DP, vload(Z, row + _DP) + c * (g_left - g))
            g_left = g


@njit(cache=True, error_model="numpy")
def _count_gaps(model, N, Z, gap_steps, max_gaps):
    """Open bonds of every lane (the model's opening < 0): one step added to
    gap_steps[b] (a row of LANES counts per bond, as doubles) and max_gaps (LANES) raised to the
    number open now where that is larger."""
    n_open = vload(max_gaps, 0) * 0.0
    for b in range(N + 1):
        bond = b * ROW
        parameters = _bond_parameters(Z, bond)
        is_open = vbelow(bond_opening(model, parameters, vload(Z, bond + _U), vload(Z, bond + ROW + _U)), 0.0)
        vstore(gap_steps, b * LANES, vload(gap_steps, b * LANES) + is_open)
        n_open = n_open + is_open
    vstore(max_gaps, 0, max(n_open, vload(max_gaps, 0)))


@njit(cache=True, error_model="numpy")
def _advance_block(model, tangent, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps, gap_steps,
                   log_growth, max_gaps, bad):
    """``advance_batch`` for one block in its buffer Z; gap_steps is (N+1) x LANES, flattened, and
    with max_gaps held as doubles."""
    literally(tangent)
    n_stages = drifts.shape[0]
    force_valid = False
    for step in range(n_steps):
        c = kicks[0] * dt
        if c != 0.0:
            if force_valid:
                _kick_only(tangent, N, Z, c)
            else:
                _sweep(model, tangent, False, True, False, N, Z, 0.0, c)
        for i in range(n_stages):
            a, c = drifts[i] * dt, kicks[i + 1] * dt
            if c == 0.0:
                _sweep(model, tangent, True, False, False, N, Z, a, c)
            elif i == n_stages - 1:  # the next step's first kick reuses these forces
                _sweep(model, tangent, True, True, True, N, Z, a, c)
            else:
                _sweep(model, tangent, True, True, False, N, Z, a, c)
            force_valid = c != 0.0
        if track_gaps:
            _count_gaps(model, N, Z, gap_steps, max_gaps)
        if (step + 1) % check_every == 0 or step + 1 == n_steps:
            for j in range(LANES):
                s = 0.0
                for n in range(N):
                    s += Z[(n + 1) * ROW + _U + j] + Z[n * ROW + _P + j]
                if tangent:  # lane j's deviation vector: every ROW-th element of the buffer
                    log_growth[j] += _renormalise(Z[ROW + _DQ + j:(N + 1) * ROW + _DQ + j:ROW],
                                                  Z[_DP + j:N * ROW + _DP + j:ROW])
                    s += Z[ROW + _DQ + j]
                if bad[j] < 0 and not np.isfinite(s):
                    bad[j] = step + 1


@njit(cache=True, error_model="numpy")
def advance_batch(model, q, p, dq, dp, inv_mass, bonds, kicks, drifts, dt, n_steps, tangent, check_every, track_gaps,
                  gap_steps, log_growth, max_gaps, bad):
    """Advance B trajectories (q, p) of ``model`` (a ``chainchaos.models`` Model), shape (N, B),
    and, if ``tangent``, their deviation vectors (dq, dp) by n_steps steps of the scheme (kicks,
    drifts).

    inv_mass (N, B); bonds (MAX_BOND_PARAMETERS, N+1, B), the model's bond parameters, bond b
    joining beads b-1 and b (walls at b = 0 and b = N). Every ``check_every`` steps and at the
    end: each lane's state is checked for finiteness (``bad[j]`` set to the step count of the
    first failed check if it is still < 0) and, with ``tangent``, its deviation vector
    renormalised, ln|v| added to ``log_growth[j]``. With ``track_gaps`` (a model whose bonds open)
    ``gap_steps[b, j]`` counts the steps bond b of lane j ends open and ``max_gaps[j]`` keeps the
    largest number of simultaneously open bonds. All arrays are updated in place.
    """
    N, B = q.shape
    Z = _aligned_zeros((N + 2) * ROW)
    block_gaps = _aligned_zeros((N + 1) * LANES)  # counts as doubles, exact below 2**53
    block_growth = np.zeros(LANES)
    block_max_gaps = _aligned_zeros(LANES)
    block_bad = np.zeros(LANES, dtype=np.int64)
    for first in range(0, B, LANES):
        Z[:] = 0.0
        for lane in range(LANES):
            j = min(first + lane, B - 1)  # padding lanes repeat the last trajectory
            for n in range(N):
                Z[(n + 1) * ROW + _U + lane] = q[n, j]
                Z[(n + 1) * ROW + _DQ + lane] = dq[n, j]
                Z[n * ROW + _P + lane] = p[n, j]
                Z[n * ROW + _DP + lane] = dp[n, j]
                Z[n * ROW + _IM + lane] = inv_mass[n, j]
            for b in range(N + 1):
                for r in range(MAX_BOND_PARAMETERS):
                    Z[b * ROW + _B0 + r * LANES + lane] = bonds[r, b, j]
                block_gaps[b * LANES + lane] = gap_steps[b, j]
            block_growth[lane] = log_growth[j]
            block_max_gaps[lane] = max_gaps[j]
            block_bad[lane] = bad[j]
        # the tangent flag literal: each case compiles to its own code without these branches
        if tangent:
            _advance_block(model, True, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps,
                           block_gaps, block_growth, block_max_gaps, block_bad)
        else:
            _advance_block(model, False, N, Z, kicks, drifts, dt, n_steps, check_every, track_gaps,
                           block_gaps, block_growth, block_max_gaps, block_bad)
        for lane in range(min(LANES, B - first)):
            j = first + lane
            for n in range(N):
                q[n, j] = Z[(n + 1) * ROW + _U + lane]
                dq[n, j] = Z[(n + 1) * ROW + _DQ + lane]
                p[n, j] = Z[n * ROW + _P + lane]
                dp[n, j] = Z[n * ROW + _DP + lane]
            for b in range(N + 1):
                gap_steps[b, j] = np.int64(block_gaps[b * LANES + lane])
            log_growth[j] = block_growth[lane]
            max_gaps[j] = np.int64(block_max_gaps[lane])
            bad[j] = block_bad[lane]


class Batch:
    """The lanes of a :class:`~chainchaos.problem.Problem` advanced together by ``advance_batch``.

    ``q, p, dq, dp`` are (N, B) arrays (trajectory index last); ``log_growth`` (B,) accumulates
    ln|v| over renormalisations, so Lambda(t) = log_growth / t as in ``integrators.advance``;
    ``gap_steps`` (N+1, B) and ``max_gaps`` (B,) accumulate the gap counts (the caller resets them).
    """

    def __init__(self, problem, q, p, dq=None, dp=None):
        self.problem, self.model, self.scheme = problem, problem.model, problem.scheme
        self.inv_mass, self.bonds = problem.lane_parameters
        self.q = np.ascontiguousarray(q, dtype=float).copy()
        self.p = np.ascontiguousarray(p, dtype=float).copy()
        shape = self.q.shape
        require(self.p.shape == shape == self.inv_mass.shape, "state shape", shape, f"(N, B) = {self.inv_mass.shape}")
        self.dq = np.zeros(shape) if dq is None else np.ascontiguousarray(dq, dtype=float).copy()
        self.dp = np.zeros(shape) if dp is None else np.ascontiguousarray(dp, dtype=float).copy()
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
        pr = self.problem
        bad = np.full(self.size, -1, dtype=np.int64)
        advance_batch(self.model, self.q, self.p, self.dq, self.dp, self.inv_mass, self.bonds, self.scheme.kicks,
                      self.scheme.drifts, pr.dt, int(n_steps), pr.tangent, pr.check_every, pr.track_gaps,
                      self.gap_steps, self.log_growth, self.max_gaps, bad)
        newly = (bad >= 0) & (self.bad < 0)
        self.bad[newly] = self.steps + bad[newly]
        self.steps += int(n_steps)


class SerialBatch(Batch):
    """The interface of :class:`Batch` on the single-trajectory engine (``integrators.advance``),
    one lane after the other: the cheaper engine for one lane or a few, with the same numbers."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._lanes = [self.problem.lane(j) for j in range(self.size)]

    def advance(self, n_steps: int) -> None:
        if n_steps <= 0:
            return
        pr = self.problem
        N, B = self.q.shape
        f, k = np.empty(N + 1), np.empty(N + 1)
        for j in range(B):
            q, p, dq, dp = (np.ascontiguousarray(a[:, j]) for a in (self.q, self.p, self.dq, self.dp))
            diagnostics = np.array([self.log_growth[j], float(self.max_gaps[j])])
            gaps = np.ascontiguousarray(self.gap_steps[:, j])
            bad = advance(self.model, q, p, dq, dp, *self._lanes[j], self.scheme.kicks, self.scheme.drifts, pr.dt,
                          int(n_steps), pr.tangent, pr.check_every, pr.track_gaps, gaps, diagnostics, f, k)
            self.q[:, j], self.p[:, j], self.dq[:, j], self.dp[:, j] = q, p, dq, dp
            self.gap_steps[:, j] = gaps
            self.log_growth[j], self.max_gaps[j] = diagnostics[0], int(diagnostics[1])
            if bad >= 0 and self.bad[j] < 0:
                self.bad[j] = self.steps + bad
        self.steps += int(n_steps)
