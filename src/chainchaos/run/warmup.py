"""The one warm-up: compile (or load from the on-disk cache) every Numba kernel a run uses.

The first call of a Numba function with new argument types compiles it, or loads it from the
cache (``chainchaos.kernels.cache``). The workflow's ``compile_kernels`` rule calls
:func:`warm_up` once before anything integrates, so that the jobs that fan out after it load the
kernels instead of each compiling them; a timed run (``chainchaos.studies.numerics``) calls it
first so that no timing includes a compilation.
"""

import os

import numpy as np

from chainchaos.engine.checked import CheckedRun
from chainchaos.engine.problem import Problem
from chainchaos.engine.rhs import RightHandSide
from chainchaos.observe.registry import (
    ALIGNMENT,
    OBSERVABLES,
    REGISTRY,
    SPECTRUM,
    model_observables,
    variables,
)
from chainchaos.run.driver import sample, sample_steps
from chainchaos.system.chain import dnls_chain, kg_chain, random_chain
from chainchaos.system.models import MODELS, get_model


def _sampled_runs(model, chain) -> None:
    """Both engines, with and without the tangent map and gap counting, through the driver, and
    the kernels of every observable the model has (modes, logarithms); then a run with more
    deviation vectors and the chaos indicators they give."""
    q, p, dq, dp = np.zeros((4, 2)), np.zeros((4, 2)), np.zeros((4, 2)), np.full((4, 2), 0.5)
    q[1] = 0.1
    steps = sample_steps(0.4, 0.1, 2, 0.1)
    for track_gaps in sorted({False, model.has_gaps}):
        for tangent in (True, False):
            for kind in ("single", "batch"):
                problem = Problem(model, [chain] * 2, dt=0.1, tangent=tangent, track_gaps=track_gaps, check_every=3)
                samples = sample(problem, q, p, dq, dp, steps, kind=kind)
                if tangent and track_gaps == model.has_gaps and kind == "batch":
                    variables(samples.run(0, np.concatenate([dq[:, 0], dp[:, 0]])), model_observables(model.name))
    problem = Problem(model, [chain] * 2, dt=0.1, track_gaps=model.has_gaps, check_every=3, spectrum=2, gali=2)
    x = np.full((2, 4, 2), 0.5)
    samples = sample(problem, q, p, dq, dp, steps, xq0=x, xp0=x)
    variables(samples.run(0, np.concatenate([dq[:, 0], dp[:, 0]])),
              [name for name in OBSERVABLES if REGISTRY[name].needs & {SPECTRUM, ALIGNMENT}])


def _measured_runs(model, chain) -> None:
    """The energy-checked advance and the right-hand side for scipy's solvers."""
    q, p = np.zeros(chain.N), np.zeros(chain.N)
    q[1] = 0.1
    for track_gaps in sorted({False, model.has_gaps}):
        for tangent in (True, False):
            problem = Problem(model, [chain], integrator="verlet", dt=0.1, tangent=tangent, track_gaps=track_gaps,
                              check_every=1)
            CheckedRun(problem, q, p, q, p).advance(1, 1, np.zeros(1))
    for tangent in (True, False):
        fun = RightHandSide(model, chain, tangent)
        y = np.zeros(fun.size)
        fun(0.0, y)
        fun.energy(y)


def warm_up(models=None) -> str:
    """Compile or load every kernel that sampled runs (scenes, orbit sets) and measured runs
    (``chainchaos.studies.numerics``) of ``models`` use (default: every registered model).
    Returns the cache directory. A model not warmed up here compiles in the first job that runs
    it."""
    chains = {"beads": random_chain(0, 2.0, 4), "kg": kg_chain(0, 4.0, 4), "dnls": dnls_chain(0, 4.0, 4)}
    for model in map(get_model, MODELS if models is None else models):
        chain = chains[model.lattice]
        _sampled_runs(model, chain)
        if not model.is_split:  # the measured runs of the numerics are the bond models'
            _measured_runs(model, chain)
    return os.environ.get("NUMBA_CACHE_DIR", "")
