"""Linear normal modes of a chain and their participation numbers (docs/conventions.md#linear-modes).

The generalised eigenproblem K U = omega^2 M U, with K tridiagonal from the bond stiffness K2 and
M = diag(m), is solved as the symmetric tridiagonal problem S V = omega^2 V with
S = M^(-1/2) K M^(-1/2) and U = M^(-1/2) V, so that U^T M U = I.

The eigensolver (:func:`tridiagonal_eigh`, the implicit QL algorithm) and the projections onto the
modes (:func:`chainchaos.kernels.exactmath.matmul`) are Numba loops of IEEE operations and square roots in a
fixed order, not LAPACK/BLAS, whose kernels and hence last bits depend on the CPU.
"""

import math

import numpy as np
from numba import njit

from chainchaos.errors import require
from chainchaos.kernels.exactmath import matmul
from chainchaos.system.chain import Chain, random_radii

#: QL sweeps allowed per eigenvalue before the solver gives up (convergence is cubic: a few suffice).
QL_MAX_SWEEPS = 60


@njit(cache=True)
def _pythag(a, b):
    """sqrt(a^2 + b^2) without overflow or underflow of the squares."""
    a, b = abs(a), abs(b)
    big, small = (a, b) if a >= b else (b, a)
    if big == 0.0:
        return 0.0
    ratio = small / big
    return big * math.sqrt(1.0 + ratio * ratio)


@njit(cache=True)
def _ql_implicit(d, e, Z):
    """Diagonalise the symmetric tridiagonal matrix with diagonal d (n) and off-diagonal e[:n-1]
    in place: on return d holds the eigenvalues (unsorted) and row j of Z, which must enter as
    the identity, the eigenvector of d[j]. Implicit QL with Wilkinson shifts (EISPACK tql2, as in
    Numerical Recipes' tqli): sweeps of plane rotations from the bottom of each unreduced block,
    an off-diagonal element counting as zero when |e_m| + (|d_m| + |d_m+1|) == |d_m| + |d_m+1|.
    Returns 0, or 1 + the index of an eigenvalue that did not converge in QL_MAX_SWEEPS sweeps."""
    n = d.shape[0]
    e[n - 1] = 0.0
    for l in range(n):
        sweeps = 0
        while True:
            m = l
            while m < n - 1:
                dd = abs(d[m]) + abs(d[m + 1])
                if abs(e[m]) + dd == dd:
                    break
                m += 1
            if m == l:
                break
            sweeps += 1
            if sweeps > QL_MAX_SWEEPS:
                return l + 1
            g = (d[l + 1] - d[l]) / (2.0 * e[l])
            r = _pythag(g, 1.0)
            g = d[m] - d[l] + e[l] / (g + (r if g >= 0.0 else -r))
            s, c, p = 1.0, 1.0, 0.0
            deflated = False
            for i in range(m - 1, l - 1, -1):
                f = s * e[i]
                b = c * e[i]
                r = _pythag(f, g)
                e[i + 1] = r
                if r == 0.0:  # underflow: the block splits at i + 1
                    d[i + 1] -= p
                    e[m] = 0.0
                    deflated = True
                    break
                s = f / r
                c = g / r
                g = d[i + 1] - p
                r = (d[i] - g) * s + 2.0 * c * b
                p = s * r
                d[i + 1] = g + p
                g = c * r - b
                for k in range(n):  # rotate eigenvectors i and i + 1
                    f = Z[i + 1, k]
                    Z[i + 1, k] = s * Z[i, k] + c * f
                    Z[i, k] = c * Z[i, k] - s * f
            if deflated:
                continue
            d[l] -= p
            e[l] = g
            e[m] = 0.0
    return 0


@njit(cache=True)
def _eigh_sorted(diag, off, w, V):
    """Eigenvalues w (increasing) and orthonormal eigenvectors V[:, j] of the symmetric tridiagonal
    matrix (diag, off); returns _ql_implicit's status. Ties keep the solver's order."""
    n = diag.shape[0]
    d = diag.copy()
    e = np.zeros(n)
    for i in range(n - 1):  # a loop, not e[:n - 1] = off: see engine.integrators.put
        e[i] = off[i]
    Z = np.eye(n)
    status = _ql_implicit(d, e, Z)
    order = np.arange(n)
    for i in range(1, n):  # insertion sort by eigenvalue: stable, no library sort
        j = i
        while j > 0 and d[order[j - 1]] > d[order[j]]:
            order[j - 1], order[j] = order[j], order[j - 1]
            j -= 1
    for j in range(n):
        w[j] = d[order[j]]
        for k in range(n):
            V[k, j] = Z[order[j], k]
    return status


def tridiagonal_eigh(diag: np.ndarray, off: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (increasing) and orthonormal eigenvectors (columns) of the symmetric tridiagonal
    matrix with diagonal ``diag`` (n) and off-diagonal ``off`` (n - 1): the implicit QL algorithm,
    the same operations in the same order on every CPU (a drop-in for scipy's eigh_tridiagonal).

    Parameters
    ----------
    diag : array_like of shape (n,)
        The diagonal, finite, n >= 1.
    off : array_like of shape (n - 1,)
        The off-diagonal, finite.

    Returns
    -------
    w : numpy.ndarray of shape (n,)
        The eigenvalues, increasing (ties in the solver's order).
    V : numpy.ndarray of shape (n, n)
        The orthonormal eigenvectors, that of ``w[j]`` in column j.

    Raises
    ------
    ParameterError
        For shapes that do not fit or non-finite entries.
    numpy.linalg.LinAlgError
        When an eigenvalue does not converge in :data:`QL_MAX_SWEEPS` sweeps.
    """
    diag = np.ascontiguousarray(diag, dtype=np.float64)
    off = np.ascontiguousarray(off, dtype=np.float64)
    n = diag.size
    require(diag.ndim == 1 and n >= 1, "diag", diag.shape, "a vector of n >= 1 values")
    require(off.shape == (n - 1,), "off", off.shape, f"a vector of n - 1 = {n - 1} values")
    require(bool(np.all(np.isfinite(diag)) and np.all(np.isfinite(off))), "matrix", "non-finite entries",
            "finite entries")
    w, V = np.empty(n), np.empty((n, n))
    status = _eigh_sorted(diag, off, w, V)
    if status:
        raise np.linalg.LinAlgError(f"implicit QL: eigenvalue {status - 1} did not converge in "
                                    f"{QL_MAX_SWEEPS} sweeps")
    return w, V

CONVENTIONS = ("potential", "period_averaged")


def normal_modes(chain: Chain) -> tuple[np.ndarray, np.ndarray]:
    """Frequencies omega_k (increasing, units of omega_max of the homogeneous chain) and mode
    shapes U[n, k], mass-orthonormal (U^T M U = I), each with its largest component positive.
    A lattice with an on-site potential (``site_stiffness``, e.g. a KGLattice, in its own units)
    adds its linear on-site stiffness to the diagonal of K.

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice: its masses, bond stiffnesses K2 and (a KGLattice) on-site stiffnesses.

    Returns
    -------
    omega : numpy.ndarray
        (N,) frequencies, increasing: units of omega_max for a bead chain, of the KG
        Hamiltonian's 1 / time unit for a KGLattice.
    U : numpy.ndarray
        (N, N) mode shapes, mode k in column k (units of 1 / sqrt(mass)).

    Examples
    --------
    >>> import numpy as np
    >>> from chainchaos import normal_modes, random_chain
    >>> chain = random_chain(seed=879, alpha=5.0, N=40)
    >>> omega, U = normal_modes(chain)
    >>> bool(np.allclose(U.T @ (chain.mass[:, None] * U), np.eye(40)))  # mass-orthonormal
    True
    """
    K2 = chain.K2
    m = chain.mass
    onsite = getattr(chain, "site_stiffness", None)  # a lattice with a site law (KGLattice): w''(0)
    diag = (K2[:-1] + K2[1:]) / m if onsite is None else (K2[:-1] + K2[1:] + onsite) / m
    off = -K2[1:-1] / np.sqrt(m[:-1] * m[1:])
    w2, V = tridiagonal_eigh(diag, off)
    U = V / np.sqrt(m)[:, None]
    peak = np.argmax(np.abs(U), axis=0)
    U *= np.sign(U[peak, np.arange(U.shape[1])])
    return np.sqrt(np.clip(w2, 0.0, None)), U


def harmonic_bond_energy(chain: Chain, u: np.ndarray) -> np.ndarray:
    """K2_b y_b^2 / 2 for every bond b = 1..N+1, with y_b = u_b - u_{b-1} and fixed walls.

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice (its bond stiffnesses K2).
    u : numpy.ndarray of shape (N, ...)
        Displacements (units of delta_ref for a bead chain), the site as the first axis; further
        axes (e.g. modes) are carried along.

    Returns
    -------
    numpy.ndarray of shape (N + 1, ...)
        The harmonic energy of every bond (the model's energy unit).
    """
    padded = np.concatenate([np.zeros((1,) + u.shape[1:]), u, np.zeros((1,) + u.shape[1:])])
    y = np.diff(padded, axis=0)
    K2 = chain.K2.reshape((-1,) + (1,) * (u.ndim - 1))
    return 0.5 * K2 * y**2


def mode_energy_density(chain: Chain, omega: np.ndarray, U: np.ndarray, convention: str = "potential") -> np.ndarray:
    """Normalised energy density h[n, k] of each mode (sum over n is 1).

    ``potential``: u = mode shape, p = 0; each bond's harmonic energy split half-half to its two
    beads, the wall bonds' outer halves belonging to the walls (docs/conventions.md#mode-energy-density).
    ``period_averaged``: the mean over one period of that density and the kinetic one
    m_n omega_k^2 U_nk^2 / 2, i.e. the time-averaged energy density of the oscillating mode.

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice.
    omega : numpy.ndarray of shape (N,)
        The mode frequencies (:func:`normal_modes`).
    U : numpy.ndarray of shape (N, N)
        The mode shapes, mode k in column k (:func:`normal_modes`).
    convention : {"potential", "period_averaged"}, default "potential"
        How a mode's energy is shared among the beads.

    Returns
    -------
    numpy.ndarray of shape (N, N)
        h[n, k], dimensionless: each column sums to 1.

    Raises
    ------
    ParameterError
        For an unknown ``convention``.
    """
    require(convention in CONVENTIONS, "convention", convention, f"one of {CONVENTIONS}")
    bond = harmonic_bond_energy(chain, U)
    density = 0.5 * (bond[:-1] + bond[1:])
    if convention == "period_averaged":
        kinetic = 0.5 * chain.mass[:, None] * (omega[None, :] * U) ** 2
        density = density / density.sum(axis=0) + kinetic / kinetic.sum(axis=0)
    return density / density.sum(axis=0)


def participation_number(h: np.ndarray, axis: int = 0) -> np.ndarray:
    """P = 1 / sum_n h_n^2 of a normalised density h (sum_n h_n = 1); 1 <= P <= N.

    Parameters
    ----------
    h : numpy.ndarray
        Normalised densities, the sites along ``axis``.
    axis : int, default 0
        The axis of the sites.

    Returns
    -------
    numpy.ndarray
        P of every density: ``h``'s shape without ``axis``.
    """
    return 1.0 / np.sum(h**2, axis=axis)


def mode_participation(chain: Chain, convention: str = "potential") -> np.ndarray:
    """Participation number of every normal mode, ordered by increasing frequency.

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice whose normal modes (:func:`normal_modes`) are counted.
    convention : {"potential", "period_averaged"}, default "potential"
        How a mode's energy is shared among the beads (docs/conventions.md#mode-energy-density).

    Returns
    -------
    numpy.ndarray
        (N,) participation numbers.
    """
    omega, U = normal_modes(chain)
    return participation_number(mode_energy_density(chain, omega, U, convention))


def modal_coordinates(chain: Chain, U: np.ndarray, u: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Q = U^T M u and P = U^T p, Q_k = sum_n m_n u_n U_nk summed over n = 1..N in order
    (exactmath.matmul).

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice (its masses).
    U : numpy.ndarray of shape (N, N)
        The mode shapes, mode k in column k (:func:`normal_modes`).
    u, p : numpy.ndarray of shape (..., N)
        Displacements and momenta, the site on the last axis.

    Returns
    -------
    Q, P : numpy.ndarray of shape (..., N)
        Modal displacements and momenta, the mode on the last axis.
    """
    return matmul(u * chain.mass, U), matmul(p, U)


def modal_energies(chain: Chain, omega: np.ndarray, U: np.ndarray, u: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Harmonic energy E_k = (P_k^2 + omega_k^2 Q_k^2) / 2 of every mode
    (docs/conventions.md#modal-energies).

    Parameters
    ----------
    chain : Chain or KGLattice
        The lattice (its masses).
    omega : numpy.ndarray of shape (N,)
        The mode frequencies (:func:`normal_modes`).
    U : numpy.ndarray of shape (N, N)
        The mode shapes (:func:`normal_modes`).
    u, p : numpy.ndarray of shape (..., N)
        Displacements and momenta, the site on the last axis.

    Returns
    -------
    numpy.ndarray of shape (..., N)
        E_k, the mode on the last axis, in the model's energy unit.
    """
    Q, P = modal_coordinates(chain, U, u, p)
    return 0.5 * (P**2 + (omega * Q) ** 2)


def ensemble_participation(
    alphas, n_realizations: int, N: int = 40, first_seed: int = 0, convention: str = "potential"
) -> dict[str, np.ndarray]:
    """Statistics of the mode participation numbers, sorted in descending order per realization.

    Realization i of every alpha is ``random_radii(first_seed + i, alpha, N)`` (docs/conventions.md#disorder):
    the same seeds as the realization search, so any member can be rebuilt from its seed.

    Parameters
    ----------
    alphas : float or array_like
        Disorder strengths (each >= 1).
    n_realizations : int
        Realizations per alpha (>= 2).
    N : int, default 40
        Number of beads.
    first_seed : int, default 0
        Seed of the first realization.
    convention : {"potential", "period_averaged"}, default "potential"
        The mode energy density (docs/conventions.md#mode-energy-density).

    Returns
    -------
    dict of str to numpy.ndarray
        ``mean`` and ``std`` (ddof 1) over the realizations, of shape (len(alphas), N), indexed by
        rank k = 1..N; ``participation``, every realization's, of shape
        (len(alphas), n_realizations, N).

    Raises
    ------
    ParameterError
        For fewer than 2 realizations, or an alpha below 1.
    """
    alphas = np.atleast_1d(np.asarray(alphas, dtype=float))
    require(isinstance(n_realizations, (int, np.integer)) and n_realizations >= 2,
            "n_realizations", n_realizations, "an integer >= 2")
    P = np.empty((alphas.size, n_realizations, N))
    for a, alpha in enumerate(alphas):
        for i in range(n_realizations):
            chain = Chain(random_radii(first_seed + i, alpha, N), alpha)
            P[a, i] = np.sort(mode_participation(chain, convention))[::-1]
    return {"mean": P.mean(axis=1), "std": P.std(axis=1, ddof=1), "participation": P}
