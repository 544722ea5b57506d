"""Advance with the energy checked in compiled code: chunks of the single-trajectory engine, the
relative energy error recorded after each, the run stopped at the first chunk that breaks a bound.

The measured runs of ``chainchaos.studies.numerics`` (work precision, step advice, stability,
long-time drift) check the energy every few steps, up to 1e6 times a run: a Python loop per check
would cost more than the integration it watches.
"""

import numpy as np
from numba import njit

from chainchaos.engine.integrators import advance
from chainchaos.system.models import energy_kernel


@njit(cache=True)
def run_chunks(model, q, p, dq, dp, inv_mass, mass, bonds, kicks, drifts, dt, n_chunks,
               chunk_steps, tangent, H0, err, err_offset, stop_error, track_gaps, gap_steps, diagnostics,
               f, k, V, sites=None):
    """Advance ``n_chunks`` chunks of ``chunk_steps`` steps with :func:`advance`, recording the
    signed relative energy error (H - H0) / |H0| after each chunk in err[err_offset + i].

    Returns -1, or the index of the chunk after which the state was non-finite or the energy
    error exceeded ``stop_error`` (the run then stops). ``sites``: the site parameters of a model
    with a site law (``advance``).
    """
    for i in range(n_chunks):
        bad = advance(model, q, p, dq, dp, inv_mass, bonds, kicks, drifts, dt, chunk_steps,
                      tangent, chunk_steps, track_gaps, gap_steps, diagnostics, f, k, sites)
        e = (energy_kernel(model, q, p, mass, bonds, V, sites) - H0) / abs(H0)
        err[err_offset + i] = e
        if bad >= 0 or not abs(e) <= stop_error:
            if bad >= 0 or not np.isfinite(e):
                err[err_offset + i] = np.inf
            return i
    return -1


class CheckedRun:
    """Lane 0 of a :class:`~chainchaos.engine.problem.Problem` advanced by :func:`run_chunks`
    from the state q, p (and deviation dq, dp; zero without the tangent map), with its energy H0,
    the diagnostics (ln|v| accumulated, largest number of open gaps) and per-bond open-gap step
    counts of :func:`~chainchaos.engine.integrators.advance`. The state arrays are its own copies."""

    def __init__(self, problem, q, p, dq=None, dp=None):
        self.problem = problem
        N = problem.N
        self.inv_mass, self.bonds = problem.lane(0)
        self.site_parameters = problem.lane_sites(0)  # None passed, not omitted: one compiled variant for every caller
        self.mass = problem.chains[0].mass
        self.q, self.p = np.array(q, dtype=float), np.array(p, dtype=float)
        self.dq = np.zeros(N) if dq is None else np.array(dq, dtype=float)
        self.dp = np.zeros(N) if dp is None else np.array(dp, dtype=float)
        self.H0 = float(energy_kernel(problem.model, self.q, self.p, self.mass, self.bonds, np.empty(N + 1),
                                      self.site_parameters))
        self.diagnostics = np.zeros(2)
        self.gap_steps = np.zeros(N + 1, dtype=np.int64)
        self._scratch = [np.empty(N + 1) for _ in range(3)]

    def advance(self, n_chunks: int, chunk_steps: int, err: np.ndarray, offset: int = 0,
                stop_error: float = np.inf) -> int:
        """``n_chunks`` chunks of ``chunk_steps`` steps, the signed relative energy error after each
        in err[offset + i]; -1, or the chunk after which the run stopped (:func:`run_chunks`)."""
        pr, scheme = self.problem, self.problem.scheme
        return run_chunks(pr.model, self.q, self.p, self.dq, self.dp, self.inv_mass, self.mass, self.bonds,
                          scheme.kicks, scheme.drifts, pr.dt, n_chunks, chunk_steps, pr.tangent, self.H0, err,
                          offset, stop_error, pr.track_gaps, self.gap_steps, self.diagnostics, *self._scratch,
                          self.site_parameters)
