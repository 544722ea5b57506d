"""Disordered chains of spherical beads in the nondimensional units of DESIGN section 1.

Radii R_n are uniform in [R_min, alpha R_min]; the reference radius is the mean
R_ref = (alpha + 1) R_min / 2 and r_n = R_n / R_ref. Units: mass = reference bead mass,
length = reference static overlap, time such that the homogeneous linear chain has
omega_max = sqrt(4 K2 / m) = 1. Then

    m_n = r_n^3,  A_n = (1/6) sqrt(2 r_{n-1} r_n / (r_{n-1} + r_n)),  F0 = 1/6,
    delta_n = (F0 / A_n)^(2/3),
    K2 = (3/2) A delta^(1/2),  K3 = -(3/8) A delta^(-1/2),  K4 = s (1/16) A delta^(-3/2),

with s = +1 the paper's sign of K4 and s = -1 the exact Taylor expansion of the Hertz force.
Bond n (n = 1..N+1) joins beads n-1 and n; beads 0 and N+1 are fixed walls of radius
``wall_radius`` (1 by default, i.e. the reference bead).
"""

from dataclasses import dataclass, field

import numpy as np

from chainchaos.errors import require

F0 = 1.0 / 6.0
GENERATOR = "numpy.random.default_rng (PCG64)"


@dataclass(frozen=True)
class Chain:
    """A chain of N beads with reduced radii ``radius`` (r_n = R_n / R_ref, n = 1..N)."""

    radius: np.ndarray
    alpha: float
    seed: int | None = None
    wall_radius: float = 1.0
    k4_sign: float = 1.0
    mass: np.ndarray = field(init=False, repr=False)
    A: np.ndarray = field(init=False, repr=False)
    delta: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        r = np.ascontiguousarray(self.radius, dtype=float)
        require(r.ndim == 1 and r.size >= 2, "N", r.size, "N >= 2 beads")
        require(bool(np.all(np.isfinite(r)) and np.all(r > 0)), "radius", r.tolist(), "finite radii > 0")
        require(np.isfinite(self.alpha) and self.alpha >= 1, "alpha", self.alpha, "alpha >= 1")
        require(np.isfinite(self.wall_radius) and self.wall_radius > 0, "wall_radius", self.wall_radius, "> 0")
        require(self.k4_sign in (1.0, -1.0), "K4_sign", self.k4_sign, "+1 (paper) or -1 (Taylor expansion)")
        ext = np.concatenate(([self.wall_radius], r, [self.wall_radius]))
        A = np.sqrt(2.0 * ext[:-1] * ext[1:] / (ext[:-1] + ext[1:])) / 6.0
        object.__setattr__(self, "radius", r)
        object.__setattr__(self, "mass", r**3)
        object.__setattr__(self, "A", A)
        object.__setattr__(self, "delta", (F0 / A) ** (2.0 / 3.0))

    @property
    def N(self) -> int:
        return self.radius.size

    @property
    def K2(self) -> np.ndarray:
        return 1.5 * self.A * np.sqrt(self.delta)

    @property
    def K3(self) -> np.ndarray:
        return -0.375 * self.A / np.sqrt(self.delta)

    @property
    def K4(self) -> np.ndarray:
        return self.k4_sign * self.A * self.delta**-1.5 / 16.0

    def with_k4_sign(self, sign: float) -> "Chain":
        return Chain(self.radius, self.alpha, self.seed, self.wall_radius, float(sign))


def random_radii(seed: int, alpha: float, N: int) -> np.ndarray:
    """Reduced radii r_n = R_n / R_ref with R_n = default_rng(seed).uniform(1, alpha, N)."""
    require(isinstance(seed, (int, np.integer)) and seed >= 0, "seed", seed, "an integer >= 0")
    require(isinstance(N, (int, np.integer)) and N >= 2, "N", N, "an integer >= 2")
    require(np.isfinite(alpha) and alpha >= 1, "alpha", alpha, "alpha >= 1")
    radii = np.random.default_rng(int(seed)).uniform(1.0, alpha, int(N))
    return radii / ((alpha + 1.0) / 2.0)


def random_chain(seed: int, alpha: float, N: int = 40, wall_radius: float = 1.0) -> Chain:
    """The realization of disorder strength ``alpha`` drawn with ``seed`` (DESIGN section 1)."""
    return Chain(random_radii(seed, alpha, N), float(alpha), int(seed), wall_radius)


def chain_from_radii(radii, reference_radius: float | None = None, wall_radius: float = 1.0) -> Chain:
    """A chain from radii in any unit, scaled by ``reference_radius`` (default (min + max) / 2).

    The chain's ``alpha`` is max/min of the given radii, the paper's definition.
    """
    R = np.asarray(radii, dtype=float)
    require(R.ndim == 1 and R.size >= 2, "N", R.size, "N >= 2 radii")
    require(bool(np.all(np.isfinite(R)) and np.all(R > 0)), "radius", R.tolist(), "finite radii > 0")
    ref = (R.max() + R.min()) / 2.0 if reference_radius is None else float(reference_radius)
    require(np.isfinite(ref) and ref > 0, "reference_radius", ref, "> 0")
    return Chain(R / ref, float(R.max() / R.min()), None, wall_radius)
