"""How an integration runs and is sampled: the settings that scenes and orbit sets share.

:class:`RunSettings` is validated once, when it is built; a scene
(:class:`~chainchaos.run.scenes.SceneParameters`) and a set of orbits
(:class:`~chainchaos.run.orbits.OrbitSettings`) extend it with what only they have. Times are in
units of 1/omega_max of the homogeneous linear chain (docs/conventions.md#units).
"""

from dataclasses import dataclass

import numpy as np

from chainchaos.engine.integrators import SCHEMES
from chainchaos.engine.split_schemes import SPLIT_SCHEMES
from chainchaos.engine.problem import Problem, check_step
from chainchaos.errors import require, require_finite_positive
from chainchaos.run.driver import sample_steps
from chainchaos.system.initial import (
    extra_deviations,
    initial_deviation,
    orthonormalised,
)


@dataclass(kw_only=True)
class RunSettings:
    """The scheme and step, the run's length, the sampling schedule (``samples_per_decade``
    log-spaced samples from ``t_first_sample``, ``sample_steps``), the
    steps between finiteness checks and deviation-vector renormalisations, the sign of the FPUT
    quartic term, the seed of the initial deviation vector and the energy-error bound.

    Parameters
    ----------
    t_final : float
        Final time, in the model's time unit (> 0).
    dt : float
        Time step (> 0, at most ``t_final``).
    integrator : str, optional
        A splitting scheme of ``SCHEMES``, or of ``SPLIT_SCHEMES`` for a split model (default
        ``"SRKN6b"``; the problem refuses a scheme of the other kind).
    samples_per_decade : int, optional
        Log-spaced samples per decade of time (default 40).
    t_first_sample : float, optional
        Time of the first sample after t = 0 (default 0.1, or dt if larger).
    check_every : int, optional
        Steps between finiteness checks and deviation-vector renormalisations (default 1000).
    k4_sign : float, optional
        Sign of the FPUT quartic coefficient: +1 (default) or -1.
    deviation_seed : int, optional
        Seed of the initial deviation vector (default 0).
    max_energy_error : float, optional
        A run stops (SimulationError) when its relative energy error exceeds this (default 1e-2).
    exponents : int, optional
        Lyapunov exponents where an observable needs the spectrum (default 0: all 2N).
    gali_order : int, optional
        k of GALI_k where an observable needs SALI or GALI (default 2).
    """

    t_final: float
    dt: float
    integrator: str = "SRKN6b"
    samples_per_decade: int = 40
    t_first_sample: float = 0.1
    check_every: int = 1000
    k4_sign: float = 1.0
    deviation_seed: int = 0
    max_energy_error: float = 1e-2
    exponents: int = 0  # Lyapunov exponents where an observable needs the spectrum (0: all 2N)
    gali_order: int = 2  # k of GALI_k where an observable needs SALI or GALI

    def __post_init__(self):
        require(self.integrator in SCHEMES or self.integrator in SPLIT_SCHEMES, "integrator", self.integrator,
                f"one of {sorted(SCHEMES)}, or for a split model (DNLS) one of {sorted(SPLIT_SCHEMES)}")
        require_finite_positive(self, "t_final", "t_first_sample", "max_energy_error")
        check_step(self.dt, self.t_final)
        require(self.k4_sign in (1, -1), "k4_sign", self.k4_sign, "+1 (paper) or -1 (Taylor expansion)")
        for key, least in (("samples_per_decade", 1), ("check_every", 1), ("exponents", 0), ("gali_order", 2)):
            value = getattr(self, key)
            require(isinstance(value, (int, np.integer)) and value >= least, key, value, f"an integer >= {least}")

    def sample_steps(self) -> np.ndarray:
        """Step indices of the log-spaced samples, from 0 to the last step.

        Returns
        -------
        numpy.ndarray of int
            Increasing step indices (sample time = step dt), from 0 to round(t_final / dt)
            (``chainchaos.run.driver.sample_steps``).
        """
        return sample_steps(self.t_final, self.dt, self.samples_per_decade, self.t_first_sample)

    def problem(self, model, chains, tangent: bool, track_gaps: bool, spectrum: bool = False,
                alignment: bool = False) -> Problem:
        """The ``Problem`` of ``model`` on ``chains`` (one per lane, taken with this run's
        sign of K4) at this run's scheme, step and check interval; with ``spectrum`` the
        deviation vectors of ``exponents`` Lyapunov exponents, with ``alignment`` those of
        GALI_``gali_order``.

        Parameters
        ----------
        model : str or Model
            The model.
        chains : sequence of Chain or KGLattice
            One lattice per lane.
        tangent : bool
            Whether the tangent map runs.
        track_gaps : bool
            Whether open bonds are counted.
        spectrum : bool, default False
            Whether the deviation vectors of the Lyapunov spectrum run.
        alignment : bool, default False
            Whether those of SALI / GALI run.

        Returns
        -------
        Problem
            The problem, validated.
        """
        N = chains[0].N
        return Problem(model, [c.with_k4_sign(self.k4_sign) for c in chains], integrator=self.integrator, dt=self.dt,
                       tangent=tangent, track_gaps=track_gaps, check_every=self.check_every,
                       spectrum=(self.exponents or 2 * N) if spectrum else 1,
                       gali=self.gali_order if alignment else 1)

    def extra_deviations(self, problem, lane: int = 0) -> tuple[np.ndarray, np.ndarray]:
        """The initial extra deviation vectors of ``problem`` (K, N) of the deviation seed
        ``deviation_seed + lane`` (lane j of an orbit set, whose first vector has that seed): the
        spectrum's, orthonormal to the first vector (``initial.initial_deviation``) and each other,
        then GALI's, each of norm 1 (``initial.extra_deviations``).

        Parameters
        ----------
        problem : Problem
            The problem (its N and its numbers of extra vectors).
        lane : int, default 0
            The lane, whose deviation seed is ``deviation_seed + lane``.

        Returns
        -------
        xq, xp : numpy.ndarray of shape (K, N)
            The displacement and momentum parts of the K = ``problem.extra_vectors`` vectors.
        """
        N, seed = problem.N, self.deviation_seed + int(lane)
        spectrum = orthonormalised(np.concatenate(initial_deviation(N, seed)),
                                   np.hstack(extra_deviations(N, seed, problem.spectrum - 1, 1)))
        gali = np.hstack(extra_deviations(N, seed, problem.gali - 1, 2))
        vectors = np.concatenate([spectrum, gali])
        return vectors[:, :N], vectors[:, N:]
