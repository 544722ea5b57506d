"""The lattice as data: the shape of a lattice of sites, its bonds and what lies beyond its edges.

A :class:`Geometry` is a chain, ``shape = (N,)``, or a square lattice, ``shape = (Nx, Ny)``, whose
site (i, j) (0 <= i < Nx, 0 <= j < Ny) is number n = j Nx + i: the sites of a line j are
consecutive, so a lattice of width Ny = 1 is the chain of Nx sites, site for site. Bonds join
nearest neighbours: (i, j)-(i+1, j) along the first axis and (i, j)-(i, j+1) along the second.
Beyond each edge, per axis (``boundary``), a wall ("fixed": a bond to a site held at rest, as at
the ends of the bead chains and of the KG chain; psi = 0 beyond the edge of a DNLS lattice) or
nothing ("free": no bond). A DNLS lattice's hopping is the same either way (a site at rest adds
nothing to it); a Klein-Gordon lattice's coupling is not.

The engines read a geometry as ``shape2`` = (Nx, Ny), Ny = 1 for a chain: the flat order above
is the order of their arrays, lines one after the other.
"""

from dataclasses import dataclass

import numpy as np

from chainchaos.errors import require

#: What lies beyond the edges of an axis.
BOUNDARIES = {"fixed": "a wall: a bond to a site held at rest", "free": "no bond beyond the edge"}

#: The lattices a geometry describes, by their number of axes.
DIMENSIONS = {1: "a chain (N,)", 2: "a square lattice (Nx, Ny)"}


@dataclass(frozen=True)
class Geometry:
    """The shape of a lattice and its boundary (module docstring).

    Parameters
    ----------
    shape : tuple of int
        ``(N,)`` for a chain, ``(Nx, Ny)`` for a square lattice; every length >= 1 and at least
        2 sites in all.
    boundary : tuple of str, optional
        What lies beyond the edges of each axis, a key of :data:`BOUNDARIES` (default "fixed" on
        every axis).

    Attributes
    ----------
    N : int
        Number of sites.
    dimension : int
        Number of axes, 1 or 2.
    shape2 : tuple of int
        (Nx, Ny) as the engines read it (Ny = 1 for a chain).

    Raises
    ------
    ParameterError
        For a shape of another dimension, a length < 1, fewer than 2 sites, or a boundary not in
        :data:`BOUNDARIES` (each named with what is allowed).

    Examples
    --------
    >>> from chainchaos.system.geometry import Geometry
    >>> g = Geometry((4, 3), ("fixed", "free"))
    >>> g.N, g.shape2, g.site(1, 2)
    (12, (4, 3), 9)
    """

    shape: tuple
    boundary: tuple | None = None

    def __post_init__(self):
        shape = tuple(self.shape) if isinstance(self.shape, (tuple, list)) else (self.shape,)
        require(len(shape) in DIMENSIONS, "shape", list(shape), f"one of {list(DIMENSIONS.values())}")
        require(all(isinstance(n, (int, np.integer)) and not isinstance(n, bool) and n >= 1 for n in shape),
                "shape", list(shape), "integer lengths >= 1")
        shape = tuple(int(n) for n in shape)
        require(int(np.prod(shape)) >= 2, "shape", list(shape), "at least 2 sites")
        boundary = ("fixed",) * len(shape) if self.boundary is None else self.boundary
        boundary = (boundary,) if isinstance(boundary, str) else tuple(boundary)
        require(len(boundary) == len(shape) and all(b in BOUNDARIES for b in boundary), "boundary", list(boundary),
                f"one of {list(BOUNDARIES)} per axis ({len(shape)} here)")
        object.__setattr__(self, "shape", shape)
        object.__setattr__(self, "boundary", boundary)

    @property
    def N(self) -> int:
        """Number of sites."""
        return int(np.prod(self.shape))

    @property
    def dimension(self) -> int:
        """Number of axes."""
        return len(self.shape)

    @property
    def shape2(self) -> tuple[int, int]:
        """(Nx, Ny), Ny = 1 for a chain: the engines' view."""
        return (self.shape[0], self.shape[1] if self.dimension == 2 else 1)

    @property
    def fixed(self) -> tuple[bool, bool]:
        """Whether each of the two axes of :attr:`shape2` has walls (a chain's second axis has none)."""
        return (self.boundary[0] == "fixed", self.dimension == 2 and self.boundary[1] == "fixed")

    @property
    def n_bonds(self) -> int:
        """Number of bonds, walls included (the length of :meth:`bonds`)."""
        nx, ny = self.shape2
        fixed_x, fixed_y = self.fixed
        along = ny * (nx + 1 if fixed_x else nx - 1)
        across = 0 if self.dimension == 1 else nx * (ny + 1 if fixed_y else ny - 1)
        return along + across

    def site(self, i: int, j: int = 0) -> int:
        """The number of site (i, j): j Nx + i."""
        nx, ny = self.shape2
        require(0 <= i < nx and 0 <= j < ny, "site", [i, j], f"0 <= i < {nx} and 0 <= j < {ny}")
        return j * nx + i

    def coordinates(self) -> np.ndarray:
        """(N, dimension) integer coordinates (i) or (i, j) of every site, in the flat order."""
        nx, ny = self.shape2
        i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
        return np.stack([i.ravel(), j.ravel()], axis=1)[:, : self.dimension]

    def bonds(self) -> np.ndarray:
        """(B, 2) site numbers of every bond, -1 for a wall: along the first axis line by line
        (each line's wall bond first and last when that axis is fixed), then along the second."""
        nx, ny = self.shape2
        fixed_x, fixed_y = self.fixed
        pairs = []
        for j in range(ny):
            line = [j * nx + i for i in range(nx)]
            ends = [-1] if fixed_x else []
            chain = ends + line + ends
            pairs += list(zip(chain[:-1], chain[1:]))
        if self.dimension == 2:
            for i in range(nx):
                column = [j * nx + i for j in range(ny)]
                ends = [-1] if fixed_y else []
                chain = ends + column + ends
                pairs += list(zip(chain[:-1], chain[1:]))
        return np.array(pairs, dtype=np.int64).reshape(-1, 2)

    def window_bonds(self, span) -> np.ndarray:
        """Where the bonds of a window of this square lattice come from: the rectangle ``span`` =
        (lo_x, hi_x, lo_y, hi_y) of sites taken as a lattice of its own with walls on every side
        (``Geometry((hi_x - lo_x, hi_y - lo_y))``: a bond across the window's edge joins a site to
        one held at rest, which is what a wall is), the index in :meth:`bonds` of each of its
        bonds, in its own order; -1 where this lattice has no such bond (a free edge), whose
        parameters are then zero and whose force is none.

        Parameters
        ----------
        span : tuple of int
            (lo_x, hi_x, lo_y, hi_y): the sites lo_x <= i < hi_x, lo_y <= j < hi_y.

        Returns
        -------
        numpy.ndarray of shape (window bonds,), dtype int64
            Indices into :meth:`bonds`, or -1.
        """
        lo_x, hi_x, lo_y, hi_y = span
        nx, ny = self.shape2
        fixed_x, fixed_y = self.fixed
        per_line, per_column = (nx + 1 if fixed_x else nx - 1), (ny + 1 if fixed_y else ny - 1)

        def before(position, length, fixed):
            """The index along its line of the bond before ``position`` (0..length; length: after
            the last site), -1 where the line has none."""
            if fixed:
                return position
            return np.where((position >= 1) & (position <= length - 1), position - 1, -1)

        # the window's bonds along the first axis, line by line, each with its two walls ...
        i, j = np.meshgrid(np.arange(lo_x, hi_x + 1), np.arange(lo_y, hi_y), indexing="xy")
        k = before(i, nx, fixed_x)
        along = np.where(k >= 0, j * per_line + k, -1)
        # ... then along the second, column by column
        i, j = np.meshgrid(np.arange(lo_x, hi_x), np.arange(lo_y, hi_y + 1), indexing="ij")
        k = before(j, ny, fixed_y)
        across = np.where(k >= 0, ny * per_line + i * per_column + k, -1)
        return np.concatenate([along.ravel(), across.ravel()]).astype(np.int64)

    def as_attrs(self) -> dict:
        """The geometry as NetCDF attributes (``lattice_shape``, ``lattice_boundary``)."""
        return {"lattice_shape": list(self.shape), "lattice_boundary": " ".join(self.boundary)}


def chain_geometry(N: int) -> Geometry:
    """The chain of N sites with a wall beyond each end: the bead chains', the KG and DNLS chains'."""
    return Geometry((N,), ("fixed",))


def adjacency(geometry: Geometry) -> np.ndarray:
    """The (N, N) matrix with 1 for every pair of bonded sites (walls left out), for linear
    algebra on small lattices (the linear spectrum of a lattice: its tests)."""
    A = np.zeros((geometry.N, geometry.N))
    for a, b in geometry.bonds():
        if a >= 0 and b >= 0:
            A[a, b] = A[b, a] = 1.0
    return A
