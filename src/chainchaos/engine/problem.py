"""The problem every integration algorithm reuses: model, chains, scheme, step and what runs beside.

A :class:`Problem` holds what stays fixed while states change (the split of scipy.integrate and
DynamicalSystems.jl between a problem and the algorithms that solve it): the force law (a model of
``chainchaos.system.models``), one chain per lane (a bead ``Chain``, or a ``KGLattice`` for a model
of that lattice: its masses, bond parameters and, with a site law, site parameters per lane), the splitting scheme (``integrators.SCHEMES``) and its
step dt (units of 1/omega_max, docs/conventions.md#units), and what runs beside the orbit: the
tangent map with its renormalisation every ``check_every`` steps, and the counting of open gaps.
The engine (``batch.Batch``: SIMD blocks, or the single-trajectory engine lane by lane), the
sampling driver (``chainchaos.run.driver``), the measured runs of ``chainchaos.studies.numerics`` and the batch
benchmark all start from one.
"""

from dataclasses import KW_ONLY, dataclass
from functools import cached_property

import numpy as np

from chainchaos.engine.integrators import get_scheme
from chainchaos.engine.split_schemes import get_split_scheme
from chainchaos.errors import require
from chainchaos.system.models import get_model, total_energy
from chainchaos.system.models.base import LATTICES
from chainchaos.system.models.split import norm

#: The scheme of a bond model's problem that names none.
DEFAULT_SCHEME = "SRKN6b"

#: The engines a problem runs on (:meth:`Problem.engine`).
ENGINES = ("auto", "batch", "single")


def check_step(dt: float, t_final: float | None = None) -> None:
    """Require a step to be a finite number > 0 (and, given the run's length, at most ``t_final``).

    Parameters
    ----------
    dt : float
        The time step, in the model's time unit.
    t_final : float, optional
        The run's length, in the same unit (None: not checked against it).

    Raises
    ------
    ParameterError
        For a step that is not a finite number > 0, or longer than ``t_final``.
    """
    require(isinstance(dt, (int, float, np.floating)) and np.isfinite(dt) and dt > 0, "dt", dt, "a finite step > 0")
    if t_final is not None:
        require(dt <= t_final, "dt", dt, f"dt <= t_final = {t_final}")


@dataclass(frozen=True, eq=False)
class Problem:
    """A model on one chain per lane, integrated by ``integrator`` at step ``dt``.

    Parameters
    ----------
    model : str or Model
        A model of the registry ``MODELS`` (or the Model itself).
    chains : sequence of Chain or KGLattice
        One lattice per lane, all of the model's kind and of one N.
    integrator : str, optional
        A splitting scheme of ``SCHEMES`` for a bond model, of ``SPLIT_SCHEMES`` for a split
        model (default None: ``"SRKN6b"``, or the split model's own ``integrator``).
    dt : float, optional
        Time step, in the model's time unit (default 5e-4).
    tangent : bool, optional
        Whether the tangent map runs beside the orbit (default True).
    track_gaps : bool, optional
        Whether open bonds are counted (only for a model whose bonds open; default False).
    check_every : int, optional
        Steps between finiteness checks and renormalisations of the deviation vectors (default 1000).
    spectrum : int, optional
        Lyapunov exponents: the mLCE vector and ``spectrum - 1`` more, kept orthonormal (default 1).
    gali : int, optional
        k of GALI_k: the mLCE vector and ``gali - 1`` more vectors (default 1: none).
    sites : tuple of int, optional
        ``(lo, hi)``: only beads lo..hi-1 move, the others held at rest (default: all move); on a
        square lattice ``(lo_x, hi_x, lo_y, hi_y)``, the rectangle of sites (i, j) with
        lo_x <= i < hi_x and lo_y <= j < hi_y.

    Raises
    ------
    ParameterError
        For a value outside what is allowed (the message names it), e.g. a lattice of the wrong
        kind for the model.

    Examples
    --------
    >>> from chainchaos import Problem, random_chain
    >>> problem = Problem("fput", [random_chain(seed, 5.0, 16) for seed in range(4)], dt=0.01)
    >>> problem.lanes, problem.N
    (4, 16)
    """

    model: object
    chains: tuple
    _: KW_ONLY
    integrator: str | None = None
    dt: float = 5e-4
    tangent: bool = True
    track_gaps: bool = False
    check_every: int = 1000
    spectrum: int = 1  # Lyapunov exponents: the mLCE vector and spectrum - 1 vectors kept orthonormal to it
    gali: int = 1  # k of GALI_k: the mLCE vector and gali - 1 more vectors, each only normalised
    sites: tuple | None = None  # (lo, hi) or (lo_x, hi_x, lo_y, hi_y): only those sites move (restricted)

    def __post_init__(self):
        object.__setattr__(self, "model", get_model(self.model))
        object.__setattr__(self, "chains", tuple(self.chains))
        if self.integrator is None:
            object.__setattr__(self, "integrator", self.model.integrator if self.model.is_split else DEFAULT_SCHEME)
        self.scheme
        require(len(self.chains) >= 1, "chains", len(self.chains), "at least one chain")
        wrong = sorted({type(c).__name__ for c in self.chains if getattr(c, "kind", None) != self.model.lattice})
        require(not wrong, "chains", wrong, f"for model {self.model.name!r}, {LATTICES[self.model.lattice]}")
        Ns = sorted({c.N for c in self.chains})
        require(len(Ns) == 1, "N", Ns, "one N per problem")
        shapes = sorted({c.geometry.shape for c in self.chains})
        require(len(shapes) == 1, "chains", shapes, "one lattice shape for every lane")
        if self.sites is not None:
            spans = [int(i) for i in self.sites]
            lengths = self.chains[0].geometry.shape
            require(len(spans) == 2 * len(lengths)
                    and all(0 <= spans[2 * a] < spans[2 * a + 1] <= n for a, n in enumerate(lengths)),
                    "sites", self.sites, f"(lo, hi) per axis, 0 <= lo < hi <= the lattice's {list(lengths)}")
            object.__setattr__(self, "sites", tuple(spans))
        check_step(self.dt)
        require(int(self.check_every) >= 1, "check_every", self.check_every, "an integer >= 1")
        require(not self.track_gaps or self.model.has_gaps, "track_gaps", self.track_gaps,
                f"gap counting only for a model whose bonds open, not {self.model.name!r}")
        object.__setattr__(self, "dt", float(self.dt))
        object.__setattr__(self, "check_every", int(self.check_every))
        object.__setattr__(self, "tangent", bool(self.tangent))
        object.__setattr__(self, "track_gaps", bool(self.track_gaps))
        for key in ("spectrum", "gali"):
            value = getattr(self, key)
            require(isinstance(value, (int, np.integer)) and 1 <= value <= 2 * self.N, key, value,
                    f"an integer from 1 to 2N = {2 * self.N} deviation vectors")
            require(value == 1 or self.tangent, key, value, "1 without the tangent map")
            object.__setattr__(self, key, int(value))

    @property
    def N(self) -> int:
        """Sites that move: the chains' N, or those of ``sites``."""
        return self.geometry.N

    @cached_property
    def geometry(self):
        """The lattice of the moving sites (``system.geometry``): the chains', or the window of
        ``sites`` with a wall beyond each of its edges (the sites beyond are at rest)."""
        full = self.chains[0].geometry
        if self.sites is None:
            return full
        from chainchaos.system.geometry import Geometry

        return Geometry(tuple(self.sites[2 * a + 1] - self.sites[2 * a] for a in range(full.dimension)))

    def restricted(self, *span: int) -> "Problem":
        """This problem on the sites of ``span`` of its chains, the others held at rest: its
        first and last bonds join a moving bead to one at zero displacement (the window of
        ``chainchaos.run.window``); on a square lattice the rectangle ``span``, whose hopping to
        the sites beyond is to sites at rest.

        Parameters
        ----------
        *span : int
            ``lo, hi``: the moving beads, lo..hi-1 (0-based), 0 <= lo < hi <= N; on a square
            lattice ``lo_x, hi_x, lo_y, hi_y``.

        Returns
        -------
        Problem
            A copy with ``sites = (lo, hi)``.

        Raises
        ------
        ParameterError
            For a problem already restricted, or a window outside the chain.
        """
        from dataclasses import replace

        require(self.sites is None, "sites", self.sites, "None: a restricted problem is not restricted again")
        return replace(self, sites=tuple(span))

    @property
    def lanes(self) -> int:
        """Number of lanes: one orbit per chain."""
        return len(self.chains)

    @property
    def extra_vectors(self) -> int:
        """Deviation vectors beyond the mLCE vector: the spectrum's, then GALI's."""
        return self.spectrum - 1 + self.gali - 1

    @property
    def scheme(self):
        """The splitting scheme of ``integrator``: an entry of ``SCHEMES``, or of ``SPLIT_SCHEMES``
        for a split model."""
        return get_split_scheme(self.integrator) if self.model.is_split else get_scheme(self.integrator)

    @property
    def _span(self):
        """The moving sites, as an index of the chains' arrays: a slice, or on a square lattice
        the rectangle's site numbers in its own flat order."""
        if self.sites is None:
            return slice(None)
        if len(self.sites) == 2:
            return slice(*self.sites)
        lo_x, hi_x, lo_y, hi_y = self.sites
        nx = self.chains[0].geometry.shape[0]
        return (np.arange(lo_y, hi_y)[:, None] * nx + np.arange(lo_x, hi_x)[None, :]).ravel()

    @cached_property
    def lane_parameters(self) -> tuple[np.ndarray, np.ndarray]:
        """inv_mass (N, B) and the model's bond parameters (parameters, N+1, B), C-contiguous
        (a bond model's: a split model has neither)."""
        require(not self.model.is_split, "model", self.model.name, "a bond model (a split model has no masses and "
                "bonds: its site_parameters are all its engines read)")
        full = self.chains[0].geometry
        if full.dimension == 2:  # a square lattice's bonds: geometry.bonds(), of the window's own lattice
            inv_mass = np.ascontiguousarray(np.stack([1.0 / c.mass[self._span] for c in self.chains], axis=1))
            bonds = np.stack([self.model.bond_parameters(c) for c in self.chains], axis=2)
            if self.sites is not None:
                index = full.window_bonds(self.sites)
                bonds = bonds[:, index]
                bonds[:, index < 0] = 0.0  # no bond there: a free edge of the lattice
            return inv_mass, np.ascontiguousarray(bonds)
        lo, hi = self.sites or (0, self.chains[0].N)
        inv_mass = np.ascontiguousarray(np.stack([1.0 / c.mass[lo:hi] for c in self.chains], axis=1))
        bonds = np.ascontiguousarray(np.stack([self.model.bond_parameters(c)[:, lo:hi + 1] for c in self.chains],
                                              axis=2))
        return inv_mass, bonds

    @cached_property
    def site_parameters(self) -> np.ndarray | None:
        """The model's site parameters (parameters, N, B), C-contiguous, next to
        ``lane_parameters``; None for a model without a site law."""
        if not (self.model.has_site_law or self.model.is_split):
            return None
        return np.ascontiguousarray(np.stack([self.model.site_parameters(c)[:, self._span] for c in self.chains],
                                             axis=2))

    def lane_sites(self, j: int) -> np.ndarray | None:
        """Lane j's site parameters (parameters, N), contiguous (None without a site law):
        the single-trajectory engine's ``sites``.

        Parameters
        ----------
        j : int
            The lane, 0-based.

        Returns
        -------
        numpy.ndarray or None
            The site parameters of lane j's lattice (of the moving sites), or None for a model
            without a site law.
        """
        sites = self.site_parameters
        return None if sites is None else np.ascontiguousarray(sites[:, :, j])

    def lane(self, j: int) -> tuple[np.ndarray, np.ndarray]:
        """Lane j's inverse masses (N,) and bond parameters (parameters, N+1), contiguous:
        the arguments of the single-trajectory engine.

        Parameters
        ----------
        j : int
            The lane, 0-based.

        Returns
        -------
        inv_mass : numpy.ndarray of shape (N,)
            1 / m of the moving beads (units of 1 / the reference bead's mass).
        bonds : numpy.ndarray of shape (parameters, N + 1)
            The model's bond parameters (``Model.bond_parameters``) of their bonds.
        """
        inv_mass, bonds = self.lane_parameters
        return np.ascontiguousarray(inv_mass[:, j]), np.ascontiguousarray(bonds[:, :, j])

    def energies(self, Q: np.ndarray, P: np.ndarray) -> np.ndarray:
        """H of every lane's state (docs/conventions.md#hamiltonian).

        Parameters
        ----------
        Q, P : numpy.ndarray of shape (B, N)
            Displacements and momenta of the B lanes, lane first (units of docs/conventions.md#units).

        Returns
        -------
        numpy.ndarray of shape (B,)
            The total energy of every lane, in the model's energy unit.

        Raises
        ------
        ParameterError
            For a restricted problem (``sites`` set): its energy is that of the full states.
        """
        require(self.sites is None, "sites", self.sites, "None (the energy of a restricted problem's chain "
                "is that of its full states)")
        return np.array([float(total_energy(self.model, c, Q[j], P[j])) for j, c in enumerate(self.chains)])

    def norms(self, Q: np.ndarray, P: np.ndarray) -> np.ndarray:
        """The norm S = sum_l (q_l^2 + p_l^2)/2 of every lane's state (a split model's second
        conserved quantity).

        Parameters
        ----------
        Q, P : numpy.ndarray of shape (B, N)
            The lanes' real canonical coordinates, lane first.

        Returns
        -------
        numpy.ndarray of shape (B,)
            The norm of every lane.

        Raises
        ------
        ParameterError
            For a bond model, which conserves no norm.
        """
        require(self.model.is_split, "model", self.model.name, "a split model (a bond model conserves no norm)")
        return np.atleast_1d(norm(Q, P))

    def engine(self, q, p, dq=None, dp=None, kind: str = "auto", xq=None, xp=None):
        """The engine of this problem from the states q, p (and deviations dq, dp), each (N, B),
        and its ``extra_vectors`` deviation vectors xq, xp (K, N, B): ``kind`` "batch" (every
        lane in SIMD blocks of the batch engine, the last block padded), "single" (the
        single-trajectory engine, lane after lane) or "auto" (blocks, and a remainder of up to
        ``batch.SERIAL_REMAINDER`` lanes beyond them on the single engine); every kind gives the
        same numbers. Extra deviation vectors run on the batch engine only.

        Parameters
        ----------
        q, p : numpy.ndarray of shape (N, B)
            Displacements and momenta of the lanes (units of docs/conventions.md#units).
        dq, dp : numpy.ndarray of shape (N, B), optional
            The deviation vectors of the tangent map (needed when ``tangent``).
        kind : {"auto", "batch", "single"}, default "auto"
            Which engine runs the lanes.
        xq, xp : numpy.ndarray of shape (K, N, B), optional
            The ``extra_vectors`` further deviation vectors (the spectrum's, GALI's).

        Returns
        -------
        chainchaos.engine.batch.Batch
            The engine, holding the states; it advances them in place.

        Raises
        ------
        ParameterError
            For an unknown ``kind``, or "single" with extra deviation vectors.
        """
        from chainchaos.engine.batch import SERIAL_REMAINDER, Batch
        from chainchaos.engine.split import SplitBatch
        from chainchaos.kernels.simd import LANES

        require(kind in ENGINES, "engine", kind, f"one of {ENGINES}")
        require(kind != "single" or not self.extra_vectors, "engine", kind,
                "'batch' or 'auto' with several deviation vectors per orbit")
        remainder = self.lanes % LANES
        serial = {"batch": 0, "single": self.lanes,
                  "auto": remainder if remainder <= SERIAL_REMAINDER and not self.extra_vectors else 0}[kind]
        if self.model.is_split:
            engine = SplitBatch
        elif self.geometry.dimension == 2:
            from chainchaos.engine.lattice import LatticeBatch as engine
        else:
            engine = Batch
        return engine(self, q, p, dq, dp, serial_lanes=serial, xq=xq, xp=xp)
