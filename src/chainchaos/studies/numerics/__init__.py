"""Numerical accuracy and stability of the integrators (the project's issue 5).

Small, orthogonal pieces, all in the nondimensional units of docs/conventions.md#units (times in
1/omega_max of the homogeneous linear chain, relative energy errors |H(t) - H(0)| / H(0)):

- :mod:`~chainchaos.engine.rhs`: the equations of motion (and their tangent extension) as a
  compiled right-hand side ``rhs(t, y)`` for scipy's solve_ivp, built on the package's kernels.
- :mod:`~chainchaos.studies.numerics.runs`: one measured run of a splitting scheme (``run_scheme``) or
  of solve_ivp's RK45/DOP853 (``run_solve_ivp``): energy error, phase-space state, Lambda, seconds.
- :mod:`~chainchaos.studies.numerics.work_precision`: error against run time over steps and tolerances
  (``work_precision``), observed orders (``observed_order``, ``order_table``).
- :mod:`~chainchaos.studies.numerics.stability`: linear stability bounds of the schemes, the largest
  stable step by bisection (``largest_stable_dt``), the near-sonic-vacuum chain
  (``sonic_vacuum_chain``), long-time energy drift (``energy_drift``), the FPUT Taylor-sign escape.
- :mod:`~chainchaos.studies.numerics.advice`: the energy error of the production step per scene.
- :mod:`~chainchaos.studies.numerics.tables` and :mod:`~chainchaos.output.plotting.numerics`: CSV/LaTeX tables and
  the two figures (imported on demand: they pull in matplotlib).
"""

from chainchaos.studies.numerics.advice import step_advice
from chainchaos.studies.numerics.runs import RunResult, phase_space_error, run_scheme, run_solve_ivp
from chainchaos.studies.numerics.stability import (
                                                   energy_drift,
                                                   largest_stable_dt,
                                                   linear_instability_intervals,
                                                   linear_omega_max,
                                                   linear_stability_bound,
                                                   stability_scan,
                                                   taylor_sign_probe,
)
from chainchaos.studies.numerics.work_precision import observed_order, order_table, work_precision

__all__ = [
    "RunResult", "run_scheme", "run_solve_ivp", "phase_space_error",
    "work_precision", "observed_order", "order_table", "linear_stability_bound", "linear_instability_intervals",
    "linear_omega_max", "largest_stable_dt", "stability_scan", "energy_drift", "taylor_sign_probe", "step_advice",
]
