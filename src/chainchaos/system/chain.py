"""Disordered chains of spherical beads (docs/conventions.md#disorder) in the nondimensional units
of docs/conventions.md#units.

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

With the bond's mean h_n = 2 r_{n-1} r_n / (r_{n-1} + r_n), every bond parameter is a power of it:

    A = sqrt(h / 36),  delta = h^(-1/3),  K2 = h^(1/3) / 4,  K3 = -h^(2/3) / 16,  K4 = s h / 96,

so each parameter, and the mass r^3, is computed as the double nearest to its exact value for the
given double radii (exact integer arithmetic, chainchaos.kernels.exactmath): the same on every machine.
"""

import copy
from dataclasses import KW_ONLY, dataclass, field
from functools import cached_property
from typing import ClassVar

import numpy as np

from chainchaos.errors import require
from chainchaos.kernels.exactmath import rational, root
from chainchaos.system.geometry import Geometry, chain_geometry

F0 = 1.0 / 6.0
GENERATOR = "numpy.random.default_rng (PCG64)"


def bead_mass(r: float) -> float:
    """m = r^3, the double nearest to the exact cube of the double r > 0.

    Parameters
    ----------
    r : float
        Reduced bead radius r = R / R_ref (> 0).

    Returns
    -------
    float
        The bead mass r^3, in units of the reference bead's mass, correctly rounded.
    """
    num, den = float(r).as_integer_ratio()
    return rational(num**3, den**3)


#: Each bond parameter (K4 with s = +1) as the double nearest to its exact value, from the bond's
#: mean h = 2 r_l r_r / (r_l + r_r) = P / Q given as the integers P, Q.
BOND_LAWS = {
    "A": lambda P, Q: root(P, 36 * Q, 2),  # sqrt(h / 36)
    "delta": lambda P, Q: root(Q, P, 3),  # h^(-1/3)
    "K2": lambda P, Q: root(P, 64 * Q, 3),  # h^(1/3) / 4
    "K3": lambda P, Q: -root(P * P, 4096 * Q * Q, 3),  # -h^(2/3) / 16
    "K4": lambda P, Q: rational(P, 96 * Q),  # h / 96
}


def bond_mean(r_left: float, r_right: float) -> tuple[int, int]:
    """(P, Q) with h = 2 r_l r_r / (r_l + r_r) = P / Q exactly, for radii r_l, r_r > 0.

    Parameters
    ----------
    r_left, r_right : float
        Reduced radii of the bond's two beads (> 0).

    Returns
    -------
    tuple of (int, int)
        The integers P and Q of the bond's mean h = P / Q (dimensionless), exactly.
    """
    nl, dl = float(r_left).as_integer_ratio()
    nr, dr = float(r_right).as_integer_ratio()
    return 2 * nl * nr, nl * dr + nr * dl  # dl, dr are powers of two


@dataclass(frozen=True)
class Chain:
    """A chain of N beads with reduced radii ``radius`` (r_n = R_n / R_ref, n = 1..N).

    mass (N,), A, delta, K2, K3 and K4 (N+1 bonds) are correctly rounded (module docstring), each
    bond parameter computed on its first use (the linear rule of the realization search reads K2
    alone, of ten thousand chains); K4 carries the sign ``k4_sign``. Made by :func:`random_chain`,
    :func:`chain_from_radii` or read from a chain file (``chainchaos.records.io.read_chain``).

    Parameters
    ----------
    radius : array_like of shape (N,)
        Reduced bead radii r_n > 0 (units of R_ref), N >= 2.
    alpha : float
        Disorder strength, max R / min R of the draw (>= 1), recorded with the chain.
    seed : int, optional
        Seed of the draw (None: radii given, not drawn).
    wall_radius : float, optional
        Reduced radius of the two wall beads (default 1).
    k4_sign : float, optional
        Sign of the FPUT quartic coefficient K4: +1 (the paper's, default) or -1 (the Taylor
        expansion of the Hertz law).

    Attributes
    ----------
    N : int
        Number of moving beads.
    mass : numpy.ndarray of shape (N,)
        Bead masses m_n = r_n^3 (units of the reference bead's mass).
    A, delta, K2, K3, K4 : numpy.ndarray of shape (N + 1,)
        Per bond: the Hertz contact coefficient, the static precompression and the FPUT
        coefficients of the Taylor expansion of the Hertz law about it
        (docs/conventions.md#bond-laws).

    Examples
    --------
    >>> from chainchaos import random_chain
    >>> chain = random_chain(seed=879, alpha=5.0, N=40)
    >>> chain.N, chain.K2.shape
    (40, (41,))
    """

    kind: ClassVar[str] = "beads"  # the lattice kind of the bead models (models.base.LATTICES)

    radius: np.ndarray
    alpha: float
    _: KW_ONLY
    seed: int | None = None
    wall_radius: float = 1.0
    k4_sign: float = 1.0
    mass: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        r = np.ascontiguousarray(self.radius, dtype=float)
        require(r.ndim == 1 and r.size >= 2, "N", r.size, "N >= 2 beads")
        require(bool(np.all(np.isfinite(r)) and np.all(r > 0)), "radius", r.tolist(), "finite radii > 0")
        require(np.isfinite(self.alpha) and self.alpha >= 1, "alpha", self.alpha, "alpha >= 1")
        require(np.isfinite(self.wall_radius) and self.wall_radius > 0, "wall_radius", self.wall_radius, "> 0")
        require(self.k4_sign in (1.0, -1.0), "K4_sign", self.k4_sign, "+1 (paper) or -1 (Taylor expansion)")
        object.__setattr__(self, "radius", r)
        object.__setattr__(self, "mass", np.array([bead_mass(x) for x in r.tolist()]))

    def _bond_law(self, name: str, bonds) -> np.ndarray:
        """Bond parameter ``name`` (:data:`BOND_LAWS`, K4 with the chain's sign) of the bonds
        ``bonds`` (0..N; bond b joins beads b-1 and b, the walls at 0 and N+1)."""
        ext = [float(self.wall_radius), *self.radius.tolist(), float(self.wall_radius)]
        values = np.array([BOND_LAWS[name](*bond_mean(ext[b], ext[b + 1])) for b in bonds])
        return self.k4_sign * values if name == "K4" else values

    def bond_values(self, name: str, bonds) -> np.ndarray:
        """Bond parameter ``name`` of the bonds ``bonds`` (0..N) alone: their entries of the column,
        without computing the rest of it where it is not known yet.

        Parameters
        ----------
        name : str
            The bond parameter, one of "A", "delta", "K2", "K3", "K4" (:data:`BOND_LAWS`; K4 with
            the chain's sign).
        bonds : iterable of int
            Bond indices 0..N; bond b joins beads b-1 and b (the walls are 0 and N+1).

        Returns
        -------
        numpy.ndarray
            The parameter of those bonds, in the order given, in the units of the attribute
            of the same name.
        """
        if name in self.__dict__:  # computed, or set by a subclass
            return getattr(self, name)[list(bonds)]
        return self._bond_law(name, bonds)

    @cached_property
    def A(self) -> np.ndarray:
        """Hertz contact coefficient A_n of every bond, shape (N + 1,) (nondimensional units)."""
        return self._bond_law("A", range(self.N + 1))

    @cached_property
    def delta(self) -> np.ndarray:
        """Static overlap delta_n of every bond under F0, shape (N + 1,) (units of delta_ref)."""
        return self._bond_law("delta", range(self.N + 1))

    @cached_property
    def K2(self) -> np.ndarray:
        """Quadratic FPUT coefficient K2_n of every bond, shape (N + 1,) (nondimensional units)."""
        return self._bond_law("K2", range(self.N + 1))

    @cached_property
    def K3(self) -> np.ndarray:
        """Cubic FPUT coefficient K3_n of every bond, shape (N + 1,) (nondimensional units)."""
        return self._bond_law("K3", range(self.N + 1))

    @cached_property
    def K4(self) -> np.ndarray:
        """Quartic FPUT coefficient K4_n of every bond, sign ``k4_sign``, shape (N + 1,)."""
        return self._bond_law("K4", range(self.N + 1))

    @property
    def N(self) -> int:
        """Number of moving beads."""
        return self.radius.size

    @cached_property
    def geometry(self) -> Geometry:
        """The chain of N beads between two walls (``system.geometry``)."""
        return chain_geometry(self.N)

    def with_k4_sign(self, sign: float) -> "Chain":
        """The same chain with K4 of sign ``sign`` (+1 the paper's, -1 the Taylor expansion).

        Parameters
        ----------
        sign : float
            +1 or -1.

        Returns
        -------
        Chain
            A copy with ``k4_sign = sign`` (the chain itself is not changed).

        Raises
        ------
        ParameterError
            For a sign other than +1 or -1.
        """
        sign = float(sign)
        require(sign in (1.0, -1.0), "K4_sign", sign, "+1 (paper) or -1 (Taylor expansion)")
        other = copy.copy(self)
        object.__setattr__(other, "k4_sign", sign)
        object.__setattr__(other, "K4", self.K4 if sign == self.k4_sign else -self.K4)
        return other


def random_radii(seed: int, alpha: float, N: int) -> np.ndarray:
    """Reduced radii r_n = R_n / R_ref with R_n = default_rng(seed).uniform(1, alpha, N).

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng`` (>= 0).
    alpha : float
        Disorder strength max R / min R (>= 1).
    N : int
        Number of beads (>= 2).

    Returns
    -------
    numpy.ndarray of shape (N,)
        The reduced radii (units of R_ref = (alpha + 1) R_min / 2).

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, N < 2 or alpha < 1.
    """
    require(isinstance(seed, (int, np.integer)) and seed >= 0, "seed", seed, "an integer >= 0")
    require(isinstance(N, (int, np.integer)) and N >= 2, "N", N, "an integer >= 2")
    require(np.isfinite(alpha) and alpha >= 1, "alpha", alpha, "alpha >= 1")
    radii = np.random.default_rng(int(seed)).uniform(1.0, alpha, int(N))
    return radii / ((alpha + 1.0) / 2.0)


def random_chain(seed: int, alpha: float, N: int = 40, wall_radius: float = 1.0) -> Chain:
    """The realization of disorder strength ``alpha`` drawn with ``seed`` (docs/conventions.md#disorder).

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``: the same seed gives the same chain everywhere.
    alpha : float
        Disorder strength max R / min R (>= 1): the radii are uniform in [R_min, alpha R_min].
    N : int, default 40
        Number of beads.
    wall_radius : float, default 1.0
        Reduced radius of the fixed wall beads at both ends.

    Returns
    -------
    Chain
        Reduced radii, masses and the bond parameters of every model, correctly rounded.

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, N < 2 or alpha < 1.

    Examples
    --------
    >>> from chainchaos import random_chain
    >>> chain = random_chain(879, 5.0, 40)  # the paper's chain
    >>> chain.N, chain.alpha
    (40, 5.0)
    """
    return Chain(random_radii(seed, alpha, N), float(alpha), seed=int(seed), wall_radius=wall_radius)


def chain_from_radii(radii, reference_radius: float | None = None, wall_radius: float = 1.0,
                     alpha: float | None = None) -> Chain:
    """A chain from radii in any unit: r_n = R_n / ``reference_radius``.

    A random chain's R_ref is the mean (1 + alpha) / 2 of the distribution its radii were drawn
    from, which the radii alone do not give: by default R_ref is their (min + max) / 2 and
    ``alpha`` their max / min (the paper's definition). Reduced radii read from a chain file are
    already in units of R_ref: ``reference_radius=1`` and the file's alpha give back that chain.

    Parameters
    ----------
    radii : array_like
        The N >= 2 bead radii, finite and positive, in any unit.
    reference_radius : float, optional
        The radius R_ref that becomes 1, in the radii's unit; default (min + max) / 2 of the radii.
    wall_radius : float, default 1.0
        Reduced radius of the fixed wall beads at both ends.
    alpha : float, optional
        Disorder strength of the distribution the radii came from (at least their max / min);
        default their max / min.

    Returns
    -------
    Chain
        The chain of reduced radii R_n / R_ref.

    Raises
    ------
    ParameterError
        For fewer than 2 radii, a radius that is not finite and > 0, a bad ``reference_radius``,
        or an ``alpha`` below the radii's max / min.

    Examples
    --------
    >>> from chainchaos import chain_from_radii
    >>> chain = chain_from_radii([2.0, 3.0, 4.5, 6.0], reference_radius=4.0)   # radii in mm
    >>> chain.radius.tolist(), chain.alpha
    ([0.5, 0.75, 1.125, 1.5], 3.0)
    """
    R = np.asarray(radii, dtype=float)
    require(R.ndim == 1 and R.size >= 2, "N", R.size, "N >= 2 radii")
    require(bool(np.all(np.isfinite(R)) and np.all(R > 0)), "radius", R.tolist(), "finite radii > 0")
    ref = (R.max() + R.min()) / 2.0 if reference_radius is None else float(reference_radius)
    require(np.isfinite(ref) and ref > 0, "reference_radius", ref, "a finite number > 0")
    spread = float(R.max() / R.min())
    if alpha is not None:
        # the radii were drawn from [R_min, alpha R_min]: their spread is at most alpha (to rounding)
        require(np.isfinite(alpha) and alpha >= spread * (1 - 1e-12), "alpha", alpha,
                f"a number >= max/min of the radii = {spread:.17g}")
    return Chain(R / ref, spread if alpha is None else float(alpha), seed=None, wall_radius=wall_radius)


class PrecompressedChain(Chain):
    """A chain whose precompression force is ``precompression`` times the reference F0, in the
    units of the reference chain (see :func:`sonic_vacuum_chain`).

    delta scales as ``precompression``^(2/3) and K2, K3, K4 follow from A and the new delta; A
    and the masses are those of :class:`Chain`.

    Parameters
    ----------
    radius : array_like of shape (N,)
        Reduced bead radii r_n > 0 (units of R_ref), N >= 2.
    alpha : float
        Disorder strength (>= 1), recorded with the chain.
    seed : int, optional
        Seed of the draw (None: radii given, not drawn).
    wall_radius : float, optional
        Reduced radius of the two wall beads (default 1).
    k4_sign : float, optional
        Sign of K4, +1 (default) or -1.
    precompression : float, optional
        The precompression force in units of the reference F0 (> 0, default 1).
    """

    precompression: float = 1.0

    def __init__(self, radius, alpha, seed=None, wall_radius=1.0, k4_sign=1.0, precompression=1.0):
        object.__setattr__(self, "precompression", float(precompression))
        super().__init__(radius, alpha, seed=seed, wall_radius=wall_radius, k4_sign=k4_sign)

    def __post_init__(self):
        super().__post_init__()
        require(np.isfinite(self.precompression) and self.precompression > 0, "precompression",
                self.precompression, "a factor > 0")
        # delta ~ F0^(2/3); the expansion coefficients follow from A and the new delta:
        # K2 = (3/2) A delta^(1/2), K3 = -(3/8) A delta^(-1/2), K4 = s (1/16) A delta^(-3/2)
        delta = self.delta * self.precompression ** (2.0 / 3.0)
        root = np.sqrt(delta)
        object.__setattr__(self, "delta", delta)
        object.__setattr__(self, "K2", 1.5 * self.A * root)
        object.__setattr__(self, "K3", -0.375 * self.A / root)
        object.__setattr__(self, "K4", self.k4_sign * self.A / (16.0 * delta * root))

    def with_k4_sign(self, sign: float) -> "PrecompressedChain":
        """The same chain, at the same precompression, with K4 of sign ``sign``.

        Parameters
        ----------
        sign : float
            +1 or -1.

        Returns
        -------
        PrecompressedChain
            A new chain with ``k4_sign = sign``.
        """
        return PrecompressedChain(self.radius, self.alpha, self.seed, self.wall_radius, float(sign),
                                  self.precompression)


def sonic_vacuum_chain(chain, factor: float = 1e-6) -> PrecompressedChain:
    """The same beads with the precompression force reduced to ``factor`` F0 (near sonic vacuum).

    Approach: keep the units of the reference chain (docs/conventions.md#units: mass = reference bead
    mass, length = the reference static overlap delta_ref *at the original* F0, time =
    1/omega_max of the original homogeneous chain). In those units the Hertz coefficients A_n
    and the masses do not depend on F0; F0 enters only through delta_n = (F0/A_n)^(2/3), so
    delta_n -> factor^(2/3) delta_n (1e-4 delta_n for factor 1e-6). The linear stiffness
    K2 ~ delta^(1/2) drops by factor^(1/3) and every linear frequency by factor^(1/6) (0.1 for
    1e-6): the time unit is still 1/omega_max of the *original* homogeneous chain, and the weakly
    compressed chain's own omega_max is factor^(1/6) in it. Contacts open as soon as a
    displacement exceeds ~1e-4, i.e. at any energy of interest.

    Hertz scaling: u -> factor^(2/3) u, t -> factor^(-1/6) t, H -> factor^(5/3) H maps the
    reference chain onto this one, so a run at energy H and step dt here is the reference chain
    at energy H factor^(-5/3) (1e10 H) and step factor^(1/6) dt: the near-sonic-vacuum limit is
    the extreme-energy limit of the reference chain.

    Parameters
    ----------
    chain : Chain
        The beads (a :class:`PrecompressedChain` keeps its own factor, multiplied by ``factor``).
    factor : float, default 1e-6
        The new precompression force in units of the chain's own (> 0).

    Returns
    -------
    PrecompressedChain
        The same radii, alpha, seed, walls and K4 sign at the reduced precompression.

    Raises
    ------
    ParameterError
        For a factor that is not finite and > 0.
    """
    require(np.isfinite(factor) and factor > 0, "precompression factor", factor, "a factor > 0")
    return PrecompressedChain(chain.radius, chain.alpha, chain.seed, chain.wall_radius, chain.k4_sign,
                              float(factor) * getattr(chain, "precompression", 1.0))


def chain_at_alpha(chain, alpha: float) -> Chain:
    """The same disorder draws at another disorder strength ``alpha``: each bead keeps its
    uniform variate U_n = (R_n/R_min - 1)/(alpha_0 - 1), so R_n/R_min = 1 + (alpha - 1) U_n and
    r_n = R_n / R_ref with R_ref = (alpha + 1) R_min / 2 (docs/conventions.md#disorder).

    Parameters
    ----------
    chain : Chain
        A chain drawn at its own alpha > 1 (``random_chain``).
    alpha : float
        The new disorder strength (> 1).

    Returns
    -------
    Chain
        The chain at ``alpha`` (seed, walls and K4 sign kept); ``chain`` itself when alpha equals
        its own.

    Raises
    ------
    ParameterError
        For alpha <= 1, or a chain of alpha 1 (no draws to rescale).
    """
    require(np.isfinite(alpha) and alpha > 1, "alpha", alpha, "alpha > 1")
    if float(alpha) == float(chain.alpha):
        return chain
    require(chain.alpha > 1, "chain alpha", chain.alpha, "alpha > 1 (a disordered chain)")
    U = (chain.radius * (chain.alpha + 1.0) / 2.0 - 1.0) / (chain.alpha - 1.0)
    radius = (1.0 + (alpha - 1.0) * U) / ((alpha + 1.0) / 2.0)
    return Chain(radius, float(alpha), seed=chain.seed, wall_radius=chain.wall_radius, k4_sign=chain.k4_sign)


# ---- the disordered Klein-Gordon lattice (models.klein_gordon) --------------------------------


@dataclass(frozen=True)
class KGLattice:
    """A disordered Klein-Gordon lattice of N sites (docs/conventions.md#klein-gordon).

    In its Hamiltonian's own units (not the bead chains' 1/omega_max of the homogeneous chain):

        H = sum_l [ p_l^2/2 + eps_l u_l^2/2 + u_l^4/4 ] + sum_{b=1}^{N+1} (u_b - u_{b-1})^2 / (2W)

    with fixed ends u_0 = u_{N+1} = 0. ``mass`` (N,) is 1 on every site, ``K2`` (N+1,) the
    harmonic coupling 1/W on every bond (the harmonic bond law's parameter), ``eps`` (N,) the
    on-site linear stiffness (the site law's parameter), ``site_stiffness`` its linear limit.
    Made by :func:`kg_chain`.

    Parameters
    ----------
    eps : array_like of shape (N,)
        On-site linear stiffnesses eps_l (finite), N >= 2.
    W : float
        Disorder strength (> 0); every bond's harmonic coupling is 1/W.
    seed : int, optional
        Seed of the draw (None: eps given, not drawn).
    geometry : Geometry, optional
        The lattice's shape (``system.geometry``; eps in its flat order), default the chain of
        ``eps.size`` sites between two walls.

    Attributes
    ----------
    N : int
        Number of sites.
    mass : numpy.ndarray of shape (N,)
        1 on every site.
    K2 : numpy.ndarray of shape (bonds,)
        1/W on every bond, in the order of ``geometry.bonds()`` (N + 1 on a chain).

    Examples
    --------
    >>> import numpy as np
    >>> from chainchaos import KGLattice
    >>> lattice = KGLattice(np.ones(8), W=4.0)   # an ordered KG chain of 8 sites
    >>> lattice.N, float(lattice.K2[0])
    (8, 0.25)
    """

    kind: ClassVar[str] = "kg"  # the lattice kind of the KG models (models.base.LATTICES)

    eps: np.ndarray
    W: float
    seed: int | None = None
    geometry: Geometry | None = None
    mass: np.ndarray = field(init=False, repr=False)
    K2: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        eps = np.ascontiguousarray(self.eps, dtype=float)
        require(eps.ndim == 1 and eps.size >= 2, "N", eps.size, "N >= 2 sites")
        require(bool(np.all(np.isfinite(eps))), "eps", eps.tolist(), "finite on-site stiffnesses")
        require(isinstance(self.W, (int, float, np.floating)) and np.isfinite(self.W) and self.W > 0, "W", self.W,
                "a finite disorder strength W > 0")
        geometry = chain_geometry(eps.size) if self.geometry is None else self.geometry
        require(geometry.N == eps.size, "geometry", list(geometry.shape), f"a shape of {eps.size} sites (eps)")
        object.__setattr__(self, "geometry", geometry)
        object.__setattr__(self, "eps", eps)
        object.__setattr__(self, "W", float(self.W))
        object.__setattr__(self, "mass", np.ones(eps.size))
        object.__setattr__(self, "K2", np.full(geometry.n_bonds, 1.0 / self.W))

    @property
    def N(self) -> int:
        """Number of sites."""
        return self.eps.size

    @property
    def site_stiffness(self) -> np.ndarray:
        """w''(0) of every site, eps_l: what the linear modes add to the diagonal of the bonds'
        stiffness matrix (``linear.normal_modes``)."""
        return self.eps

    def with_k4_sign(self, sign: float) -> "KGLattice":
        """The lattice itself: the sign of the FPUT quartic coefficient, which runs set on every
        chain they integrate, has no meaning for the harmonic coupling of a KG lattice.

        Parameters
        ----------
        sign : float
            Ignored.

        Returns
        -------
        KGLattice
            ``self``.
        """
        return self


def kg_chain(seed: int, W: float, N: int) -> KGLattice:
    """The disordered KG lattice of disorder strength W drawn with ``seed``: eps_l =
    default_rng(seed).uniform(0.5, 1.5, N), coupling 1/W, masses 1 (docs/conventions.md#klein-gordon).

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``: the same seed gives the same lattice everywhere.
    W : float
        Disorder strength (> 0); the harmonic coupling is 1/W.
    N : int
        Number of sites (>= 2).

    Returns
    -------
    KGLattice
        The lattice (eps drawn, masses 1, couplings 1/W), in the KG Hamiltonian's units.

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, N < 2, or W not finite and > 0.

    Examples
    --------
    >>> from chainchaos import kg_chain
    >>> lattice = kg_chain(seed=1, W=4.0, N=64)
    >>> lattice.N, bool(0.5 <= lattice.eps.min() and lattice.eps.max() <= 1.5)
    (64, True)
    """
    require(isinstance(N, (int, np.integer)) and N >= 2, "N", N, "an integer >= 2")
    return kg_lattice(seed, W, (int(N),))


def kg_lattice(seed: int, W: float, shape, boundary=None) -> KGLattice:
    """The disordered KG lattice of shape ``shape`` (a chain (N,) or a square lattice (Nx, Ny),
    ``system.geometry``) and disorder strength W drawn with ``seed``: eps =
    default_rng(seed).uniform(0.5, 1.5, N) in the geometry's flat order, coupling 1/W on every
    bond (along the lines and across them, walls included where an edge is fixed), masses 1; a
    lattice of width 1 with free transverse edges is the chain :func:`kg_chain` draws.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``.
    W : float
        Disorder strength (> 0); the harmonic coupling of every bond is 1/W.
    shape : int or tuple of int
        (N,) or (Nx, Ny).
    boundary : tuple of str, optional
        Per axis, "fixed" (a wall bond at each end) or "free" (none); default "fixed".

    Returns
    -------
    KGLattice
        The lattice, in the KG Hamiltonian's units.

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, a bad shape or boundary, or W not finite and > 0.

    Examples
    --------
    >>> from chainchaos.system.chain import kg_lattice
    >>> lattice = kg_lattice(seed=1, W=4.0, shape=(6, 5), boundary=("fixed", "free"))
    >>> lattice.N, lattice.K2.size   # 5 lines of 7 bonds, 6 columns of 4
    (30, 59)
    """
    require(isinstance(seed, (int, np.integer)) and seed >= 0, "seed", seed, "an integer >= 0")
    geometry = Geometry(shape, boundary)
    eps = np.random.default_rng(int(seed)).uniform(0.5, 1.5, geometry.N)
    return KGLattice(eps, W, int(seed), geometry)


# ---- the disordered DNLS lattice (models.dnls) ------------------------------------------------


@dataclass(frozen=True)
class DNLSLattice:
    """A disordered discrete nonlinear Schroedinger (DNLS) lattice of N sites
    (docs/conventions.md#dnls).

    In real canonical coordinates psi_l = (q_l + i p_l) / sqrt(2):

        H = sum_l [ eps_l (q_l^2 + p_l^2)/2 + beta (q_l^2 + p_l^2)^2 / 8 ]
            - sum_l (q_l q_{l+1} + p_l p_{l+1}),

    with fixed ends psi_0 = psi_{N+1} = 0; the norm S = sum_l (q_l^2 + p_l^2)/2 is conserved
    with H. Made by :func:`dnls_chain`.

    Parameters
    ----------
    eps : array_like of shape (N,)
        On-site energies eps_l (finite), N >= 2.
    W : float
        Disorder strength (> 0): eps_l is drawn uniform in [-W/2, W/2].
    beta : float, optional
        Nonlinearity (finite, default 1); the linear lattice has beta = 0.
    seed : int, optional
        Seed of the draw (None: eps given, not drawn).
    geometry : Geometry, optional
        The lattice's shape (``system.geometry``; eps in its flat order), default the chain of
        ``eps.size`` sites.

    Attributes
    ----------
    N : int
        Number of sites.

    Examples
    --------
    >>> import numpy as np
    >>> from chainchaos import DNLSLattice
    >>> lattice = DNLSLattice(np.zeros(8), W=4.0, beta=0.72)   # an ordered DNLS chain of 8 sites
    >>> lattice.N, lattice.beta
    (8, 0.72)
    """

    kind: ClassVar[str] = "dnls"  # the lattice kind of the DNLS models (models.base.LATTICES)

    eps: np.ndarray
    W: float
    beta: float = 1.0
    seed: int | None = None
    geometry: Geometry | None = None

    def __post_init__(self):
        eps = np.ascontiguousarray(self.eps, dtype=float)
        require(eps.ndim == 1 and eps.size >= 2, "N", eps.size, "N >= 2 sites")
        geometry = chain_geometry(eps.size) if self.geometry is None else self.geometry
        require(geometry.N == eps.size, "geometry", list(geometry.shape), f"a shape of {eps.size} sites (eps)")
        object.__setattr__(self, "geometry", geometry)
        require(bool(np.all(np.isfinite(eps))), "eps", eps.tolist(), "finite on-site energies")
        require(isinstance(self.W, (int, float, np.floating)) and np.isfinite(self.W) and self.W > 0, "W", self.W,
                "a finite disorder strength W > 0")
        require(isinstance(self.beta, (int, float, np.floating)) and np.isfinite(self.beta), "beta", self.beta,
                "a finite nonlinearity beta")
        object.__setattr__(self, "eps", eps)
        object.__setattr__(self, "W", float(self.W))
        object.__setattr__(self, "beta", float(self.beta))

    @property
    def N(self) -> int:
        """Number of sites."""
        return self.eps.size

    def with_k4_sign(self, sign: float) -> "DNLSLattice":
        """The lattice itself (the FPUT quartic sign, which runs set on every chain, has no
        meaning here).

        Parameters
        ----------
        sign : float
            Ignored.

        Returns
        -------
        DNLSLattice
            ``self``.
        """
        return self


def dnls_chain(seed: int, W: float, N: int, beta: float = 1.0) -> DNLSLattice:
    """The disordered DNLS lattice of disorder strength W drawn with ``seed``: eps_l =
    default_rng(seed).uniform(-W/2, W/2, N), nonlinearity beta (docs/conventions.md#dnls).

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``: the same seed gives the same lattice everywhere.
    W : float
        Disorder strength (> 0).
    N : int
        Number of sites (>= 2).
    beta : float, optional
        Nonlinearity (default 1).

    Returns
    -------
    DNLSLattice
        The lattice, in the DNLS Hamiltonian's units (hopping 1).

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, N < 2, W not finite and > 0, or beta not finite.

    Examples
    --------
    >>> from chainchaos import dnls_chain
    >>> lattice = dnls_chain(seed=1, W=4.0, N=64, beta=0.72)
    >>> lattice.N, bool(-2 <= lattice.eps.min() and lattice.eps.max() <= 2)
    (64, True)
    """
    require(isinstance(N, (int, np.integer)) and N >= 2, "N", N, "an integer >= 2")
    return dnls_lattice(seed, W, (int(N),), beta)


def dnls_lattice(seed: int, W: float, shape, beta: float = 1.0, boundary=None) -> DNLSLattice:
    """The disordered DNLS lattice of shape ``shape`` (a chain (N,) or a square lattice (Nx, Ny),
    ``system.geometry``) and disorder strength W drawn with ``seed``: eps =
    default_rng(seed).uniform(-W/2, W/2, N) in the geometry's flat order (lines one after the
    other), so a lattice of width 1 is the chain :func:`dnls_chain` draws with that seed.

    Parameters
    ----------
    seed : int
        Seed of ``numpy.random.default_rng``.
    W : float
        Disorder strength (> 0).
    shape : int or tuple of int
        (N,) or (Nx, Ny).
    beta : float, optional
        Nonlinearity (default 1).
    boundary : tuple of str, optional
        Per axis, "fixed" or "free" (default "fixed"; the hopping is the same either way).

    Returns
    -------
    DNLSLattice
        The lattice, in the DNLS Hamiltonian's units (hopping 1 on every bond).

    Raises
    ------
    ParameterError
        For a negative or non-integer seed, a bad shape or boundary, W not finite and > 0, or
        beta not finite.

    Examples
    --------
    >>> from chainchaos.system.chain import dnls_lattice
    >>> lattice = dnls_lattice(seed=1, W=10.0, shape=(5, 4), beta=1.0)
    >>> lattice.N, lattice.geometry.shape
    (20, (5, 4))
    """
    require(isinstance(seed, (int, np.integer)) and seed >= 0, "seed", seed, "an integer >= 0")
    require(isinstance(W, (int, float, np.floating)) and np.isfinite(W) and W > 0, "W", W,
            "a finite disorder strength W > 0")
    geometry = Geometry(shape, boundary)
    eps = np.random.default_rng(int(seed)).uniform(-0.5 * W, 0.5 * W, geometry.N)
    return DNLSLattice(eps, W, beta, int(seed), geometry)
