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

The engine has the interface the sampling driver (``chainchaos.run.driver``) reads: full-chain
states and deviation vectors, ln|v|, gap counts, ``bad`` steps; its cost follows the window's
width, not N. Only the mLCE vector runs beside the orbit (no spectrum or GALI vectors, whose
orthonormal sets do not restrict to a window).
"""

from dataclasses import dataclass

import numpy as np

from chainchaos.errors import require
from chainchaos.system.models import bond_potentials, site_potentials


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
    def excited(q: np.ndarray, p: np.ndarray) -> tuple[int, int]:
        """The sites lo..hi-1 from the first to the last one where some lane's state (q, p:
        (N, B)) is not at rest."""
        moving = np.flatnonzero(np.any(q != 0.0, axis=1) | np.any(p != 0.0, axis=1))
        require(moving.size > 0, "window", "a state at rest", "a state with a moving site")
        return int(moving[0]), int(moving[-1]) + 1

    def first_span(self, q: np.ndarray, p: np.ndarray) -> tuple[int, int]:
        """The sites of the first window: the :meth:`excited` ones and ``2 margin`` more on each
        side, within the chain."""
        lo, hi = self.excited(q, p)
        return max(0, lo - 2 * self.margin), min(q.shape[0], hi + 2 * self.margin)


def restricted_deviation(dq: np.ndarray, dp: np.ndarray, lo: int, hi: int) -> tuple[np.ndarray, np.ndarray]:
    """Deviation vectors (N, B) set to zero outside sites lo..hi-1 and scaled back to their norms."""
    dq, dp = np.array(dq, dtype=float), np.array(dp, dtype=float)
    norm = np.sqrt(np.sum(dq**2 + dp**2, axis=0))
    dq[:lo], dq[hi:], dp[:lo], dp[hi:] = 0.0, 0.0, 0.0, 0.0
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
    V, W = np.empty(n + 1), np.empty(n)
    for j in range(B):
        qj = np.ascontiguousarray(q[:, j])
        bond_potentials(problem.model, qj, np.ascontiguousarray(bonds[:, :, j]), V)
        H[:, j] += 0.5 * (V[:-1] + V[1:])
        if problem.model.has_site_law:
            site_potentials(problem.model, qj, problem.lane_sites(j), W)
            H[:, j] += W
    return H, dq * dq + dp * dp


class WindowedEngine:
    """The engine of a problem run on a growing window (:class:`Window`); built from full-chain
    states q, p, dq, dp (N, B), read as the driver reads ``batch.Batch``."""

    def __init__(self, problem, window: Window, q, p, dq, dp, kind: str = "auto"):
        require(problem.extra_vectors == 0, "window", window,
                "None with Lyapunov spectrum or GALI vectors (only the mLCE vector runs on a window)")
        self.problem, self.window, self.kind = problem, window, kind
        self.N = problem.N
        q, p = np.asarray(q, dtype=float), np.asarray(p, dtype=float)
        dq = np.zeros_like(q) if dq is None else np.array(dq, dtype=float)
        dp = np.zeros_like(p) if dp is None else np.array(dp, dtype=float)
        lo, hi = window.first_span(q, p)
        if problem.tangent:  # the deviation vectors start on the excited sites, well inside the window
            dq, dp = restricted_deviation(dq, dp, *window.excited(q, p))
        B = q.shape[1]
        self.bad = np.full(B, -1, dtype=np.int64)
        self.steps = 0
        self.spans = [(0, lo, hi)]  # (step, lo, hi) of every window, for the record
        self._start(lo, hi, q, p, dq, dp)

    def _start(self, lo, hi, q, p, dq, dp, old=None, old_span=None) -> None:
        """A fresh engine on sites lo..hi-1 from full-chain states, carrying the sums of ``old``
        (the engine of the window ``old_span``)."""
        self.lo, self.hi = lo, hi
        self.sub = self.problem.restricted(lo, hi)
        self.engine = self.sub.engine(q[lo:hi], p[lo:hi], dq[lo:hi], dp[lo:hi], self.kind)
        self.engine.steps = self.steps
        if old is not None:
            self.engine.log_growth[:] = old.log_growth
            self.engine.max_gaps[:] = old.max_gaps
            self.engine.bad[:] = old.bad
            self.engine.gap_steps[:] = self._full(old.gap_steps, old_span, extra=1)[lo:hi + 1]

    def _full(self, part, span, extra: int = 0) -> np.ndarray:
        lo, hi = span
        out = np.zeros((self.N + extra,) + part.shape[1:], dtype=part.dtype)
        out[lo:hi + extra] = part
        return out

    @property
    def span(self) -> tuple[int, int]:
        return self.lo, self.hi

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
        """Widen the window where a lane's energy or deviation vector reaches its outer margin."""
        e = self.engine
        lo, hi, m, N = self.lo, self.hi, self.window.margin, self.N
        H, D = site_weights(self.sub, e.q, e.p, e.dq, e.dp)
        with np.errstate(invalid="ignore", divide="ignore"):
            shares = [(w[:m].sum(axis=0) / w.sum(axis=0), w[-m:].sum(axis=0) / w.sum(axis=0)) for w in (H, D)]
        t = self.window.threshold
        new_lo = max(0, lo - 2 * m) if lo > 0 and any(np.any(s[0] > t) for s in shares) else lo
        new_hi = min(N, hi + 2 * m) if hi < N and any(np.any(s[1] > t) for s in shares) else hi
        if (new_lo, new_hi) == (lo, hi):
            return
        self._start(new_lo, new_hi, self.q, self.p, self.dq, self.dp, e, (lo, hi))
        self.spans.append((self.steps, new_lo, new_hi))
