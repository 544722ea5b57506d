"""A growing window: a long chain integrated only where its packet is.

A packet started on a few sites of a long chain touches only a stretch of it for a long time; the
sites beyond stay at rest. :class:`WindowedEngine` integrates the sites ``lo .. hi-1`` only, the
others held at rest (``Problem.restricted``: the window's first and last bonds join it to beads at
zero displacement, which is what a bead at rest is), and widens the window before the packet
reaches its edge. The rule (:class:`Window`): every ``every`` steps, for every lane, the share of
the energy, and of the deviation vector's squared norm, in the ``margin`` outermost sites of each
side of the window is measured; a side where some lane has more than ``threshold`` of either
moves out by ``2 * margin`` sites (up to the chain's end), so that a packet whose tails decay
faster than ``threshold`` over ``margin`` sites never feels the cut. The sites outside then start
moving only with the error the cut made, of the order of ``threshold`` of the energy. The
deviation vectors start on the excited sites (the run's own vectors, set to zero elsewhere and
scaled back to their norms, :func:`restricted_deviation`), ``2 margin`` sites inside the first
window.

On a square lattice (``system.geometry``) the window is a rectangle of sites, each of its four
sides measured and moved out the same way, the sites beyond held at rest: a DNLS lattice's
hopping to them adds nothing, and a Klein-Gordon lattice's bond across the window's edge is a
wall with that bond's parameters (``Geometry.window_bonds``; none where the lattice's own edge
is free).

The engine has the interface the sampling driver (``chainchaos.run.driver``) reads: full-lattice
states and deviation vectors, ln|v|, gap counts, ``bad`` steps; its cost follows the window's
size, not N. Only the mLCE vector runs beside the orbit (no spectrum or GALI vectors, whose
orthonormal sets do not restrict to a window).
"""

from dataclasses import dataclass

import numpy as np

from chainchaos.errors import require
from chainchaos.system.models import add_bond_halves, bond_potentials, lattice_bond_potentials, site_potentials


@dataclass(frozen=True)
class Window:
    """The growing window's rule: check every ``every`` steps; a side moves out by ``2 margin``
    sites when more than ``threshold`` of a lane's energy (or of its deviation vector's squared
    norm) lies in its ``margin`` outermost sites."""

    threshold: float = 1e-12
    margin: int = 16
    every: int = 100

    def __post_init__(self):
        require(isinstance(self.threshold, (int, float)) and 0 < self.threshold < 1, "window.threshold",
                self.threshold, "a fraction 0 < threshold < 1 of the energy")
        for key in ("margin", "every"):
            value = getattr(self, key)
            require(isinstance(value, (int, np.integer)) and value >= 1, f"window.{key}", value, "an integer >= 1")

    @classmethod
    def from_config(cls, block):
        """A :class:`Window` from a config block (None: no window)."""
        return None if block is None else (block if isinstance(block, cls) else cls(**block))

    @staticmethod
    def excited(q: np.ndarray, p: np.ndarray, geometry=None) -> tuple[int, ...]:
        """The sites lo..hi-1 from the first to the last one where some lane's state (q, p:
        (N, B)) is not at rest; on a square lattice ``geometry``, (lo_x, hi_x, lo_y, hi_y) of the
        smallest rectangle holding them."""
        moving = np.any(q != 0.0, axis=1) | np.any(p != 0.0, axis=1)
        require(moving.any(), "window", "a state at rest", "a state with a moving site")
        if geometry is None or geometry.dimension == 1:
            at = np.flatnonzero(moving)
            return int(at[0]), int(at[-1]) + 1
        grid = moving.reshape(geometry.shape[1], geometry.shape[0])  # [j, i]
        i, j = np.flatnonzero(grid.any(axis=0)), np.flatnonzero(grid.any(axis=1))
        return int(i[0]), int(i[-1]) + 1, int(j[0]), int(j[-1]) + 1

    def first_span(self, q: np.ndarray, p: np.ndarray, geometry=None) -> tuple[int, ...]:
        """The sites of the first window: the :meth:`excited` ones and ``2 margin`` more on each
        side, within the lattice."""
        lengths = (q.shape[0],) if geometry is None else geometry.shape
        span = self.excited(q, p, geometry)
        return tuple(v for a, n in enumerate(lengths)
                     for v in (max(0, span[2 * a] - 2 * self.margin), min(n, span[2 * a + 1] + 2 * self.margin)))


def window_sites(span: tuple, geometry) -> np.ndarray | slice:
    """The sites of window ``span`` ((lo, hi), or (lo_x, hi_x, lo_y, hi_y) on a square lattice)
    as an index of a lattice's arrays: a slice, or the rectangle's numbers in its flat order."""
    if len(span) == 2:
        return slice(*span)
    lo_x, hi_x, lo_y, hi_y = span
    return (np.arange(lo_y, hi_y)[:, None] * geometry.shape[0] + np.arange(lo_x, hi_x)[None, :]).ravel()


def restricted_deviation(dq: np.ndarray, dp: np.ndarray, *span: int, geometry=None) -> tuple[np.ndarray, np.ndarray]:
    """Deviation vectors (N, B) set to zero outside the sites of window ``span`` (lo, hi, or the
    rectangle lo_x, hi_x, lo_y, hi_y of ``geometry``) and scaled back to their norms."""
    dq, dp = np.array(dq, dtype=float), np.array(dp, dtype=float)
    norm = np.sqrt(np.sum(dq**2 + dp**2, axis=0))
    inside = np.zeros(dq.shape[0], dtype=bool)
    inside[window_sites(span, geometry)] = True
    dq[~inside], dp[~inside] = 0.0, 0.0
    inside = np.sqrt(np.sum(dq**2 + dp**2, axis=0))
    scale = np.divide(norm, inside, out=np.zeros_like(norm), where=inside > 0)
    return dq * scale, dp * scale


def site_weights(problem, q, p, dq, dp) -> tuple[np.ndarray, np.ndarray]:
    """Per site and lane of a (windowed) problem, (n, B) each: the energy
    H_n = p_n^2/(2 m_n) + (V_n + V_{n+1})/2 (+ w_n) (a split model's norm (q_n^2 + p_n^2)/2: its
    energy density may be negative) and the deviation vector's dq_n^2 + dp_n^2."""
    if problem.model.is_split:
        return 0.5 * (q * q + p * p), dq * dq + dp * dp
    inv_mass, bonds = problem.lane_parameters
    n, B = q.shape
    H = 0.5 * p * p * inv_mass
    ends = problem.geometry.bonds() if problem.geometry.dimension == 2 else None
    V, W = np.empty(bonds.shape[1]), np.empty(n)
    for j in range(B):
        qj, Pj = np.ascontiguousarray(q[:, j]), np.ascontiguousarray(bonds[:, :, j])
        if ends is None:
            bond_potentials(problem.model, qj, Pj, V)
            H[:, j] += 0.5 * (V[:-1] + V[1:])
        else:  # each bond's half to each of its sites, as models.energy_density
            lattice_bond_potentials(problem.model, qj, Pj, ends, V)
            add_bond_halves(H[:, j], V, ends)
        if problem.model.has_site_law:
            site_potentials(problem.model, qj, problem.lane_sites(j), W)
            H[:, j] += W
    return H, dq * dq + dp * dp


class WindowedEngine:
    """The engine of a problem run on a growing window (:class:`Window`); built from full-lattice
    states q, p, dq, dp (N, B), read as the driver reads ``batch.Batch``."""

    def __init__(self, problem, window: Window, q, p, dq, dp, kind: str = "auto"):
        require(problem.extra_vectors == 0, "window", window,
                "None with Lyapunov spectrum or GALI vectors (only the mLCE vector runs on a window)")
        self.problem, self.window, self.kind = problem, window, kind
        self.N, self.geometry = problem.N, problem.geometry
        q, p = np.asarray(q, dtype=float), np.asarray(p, dtype=float)
        dq = np.zeros_like(q) if dq is None else np.array(dq, dtype=float)
        dp = np.zeros_like(p) if dp is None else np.array(dp, dtype=float)
        span = window.first_span(q, p, self.geometry)
        if problem.tangent:  # the deviation vectors start on the excited sites, well inside the window
            dq, dp = restricted_deviation(dq, dp, *window.excited(q, p, self.geometry), geometry=self.geometry)
        B = q.shape[1]
        self.bad = np.full(B, -1, dtype=np.int64)
        self.steps = 0
        self.spans = [(0, *span)]  # (step, lo, hi) (per axis) of every window, for the record
        self._start(span, q, p, dq, dp)

    def _start(self, span, q, p, dq, dp, old=None, old_span=None) -> None:
        """A fresh engine on the sites of window ``span`` from full-lattice states, carrying the
        sums of ``old`` (the engine of the window ``old_span``)."""
        self.span = span
        inside = window_sites(span, self.geometry)
        self.sub = self.problem.restricted(*span)
        self.engine = self.sub.engine(q[inside], p[inside], dq[inside], dp[inside], self.kind)
        self.engine.steps = self.steps
        if old is not None:
            self.engine.log_growth[:] = old.log_growth
            self.engine.max_gaps[:] = old.max_gaps
            self.engine.bad[:] = old.bad
            if len(span) == 2:  # bonds open only on a chain
                lo, hi = span
                self.engine.gap_steps[:] = self._full(old.gap_steps, old_span, extra=1)[lo:hi + 1]

    def _full(self, part, span, extra: int = 0) -> np.ndarray:
        out = np.zeros((self.N + extra,) + part.shape[1:], dtype=part.dtype)
        if len(span) == 2:
            lo, hi = span
            out[lo:hi + extra] = part
        elif not extra:
            out[window_sites(span, self.geometry)] = part
        return out

    q = property(lambda self: self._full(self.engine.q, self.span))
    p = property(lambda self: self._full(self.engine.p, self.span))
    dq = property(lambda self: self._full(self.engine.dq, self.span))
    dp = property(lambda self: self._full(self.engine.dp, self.span))
    gap_steps = property(lambda self: self._full(self.engine.gap_steps, self.span, extra=1))
    log_growth = property(lambda self: self.engine.log_growth)
    max_gaps = property(lambda self: self.engine.max_gaps)
    x_growth = property(lambda self: self.engine.x_growth)

    def new_interval(self) -> None:
        self.engine.new_interval()

    def stop_vectors(self, lanes) -> None:
        self.engine.stop_vectors(lanes)

    def advance(self, n_steps: int) -> None:
        """Advance every lane by n_steps, checking the window every ``window.every`` steps."""
        left = int(n_steps)
        while left > 0:
            k = min(left, self.window.every - self.steps % self.window.every)
            self.engine.advance(k)
            self.steps += k
            left -= k
            self.bad[:] = self.engine.bad
            if self.steps % self.window.every == 0:
                self._check()

    def _check(self) -> None:
        """Widen the window where a lane's energy or deviation vector reaches its outer margin:
        each side (each end of each axis) on its own."""
        e, m, t = self.engine, self.window.margin, self.window.threshold
        sub = self.sub.geometry
        H, D = site_weights(self.sub, e.q, e.p, e.dq, e.dp)
        new = list(self.span)
        for axis, length in enumerate(self.geometry.shape):
            lo, hi = self.span[2 * axis], self.span[2 * axis + 1]
            near_lo, near_hi = [], []
            for w in (H, D):
                grid = w.reshape(sub.shape[1], sub.shape[0], -1) if sub.dimension == 2 else w[None]  # [j, i, lane]
                along = grid.sum(axis=0) if axis == 0 else grid.sum(axis=1)  # per position along the axis
                with np.errstate(invalid="ignore", divide="ignore"):
                    near_lo.append(along[:m].sum(axis=0) / along.sum(axis=0))
                    near_hi.append(along[-m:].sum(axis=0) / along.sum(axis=0))
            if lo > 0 and any(np.any(s > t) for s in near_lo):
                new[2 * axis] = max(0, lo - 2 * m)
            if hi < length and any(np.any(s > t) for s in near_hi):
                new[2 * axis + 1] = min(length, hi + 2 * m)
        new = tuple(new)
        if new == self.span:
            return
        self._start(new, self.q, self.p, self.dq, self.dp, e, self.span)
        self.spans.append((self.steps, *new))
