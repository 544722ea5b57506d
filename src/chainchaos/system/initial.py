"""Initial conditions: one displaced bead (the paper's), an :class:`Excitation` of a site, a
linear mode or a block in displacement or momentum (the studies'), and random deviation vectors
(docs/conventions.md#initial-conditions)."""

import math
from dataclasses import dataclass

import numpy as np

from chainchaos.errors import ParameterError, require
from chainchaos.kernels.exactmath import gram_schmidt, norm
from chainchaos.system.models import get_model, total_energy

U0_LIMIT = 1e6


def excitation_energy(model: int, chain, site: int, u0: float) -> float:
    """Energy of the state with only bead ``site`` (1-based) displaced by u0, all momenta zero."""
    u = np.zeros(chain.N)
    u[site - 1] = u0
    return float(total_energy(model, chain, u, np.zeros(chain.N)))


def initial_displacement(model: int, chain, energy: float, site: int) -> float:
    """The smallest u0 > 0 with excitation_energy(u0) = energy, from the model's exact potential.

    Raises ParameterError naming the energy when no u0 reaches it (the FPUT potential with the
    Taylor sign of K4 has a maximum along this excitation).
    """
    require(np.isfinite(energy) and energy > 0, "energy", energy, "a finite energy > 0")
    require(isinstance(site, (int, np.integer)) and 1 <= site <= chain.N, "excited_site", site,
            f"an integer bead index 1..{chain.N}")
    return _amplitude(lambda u0: excitation_energy(model, chain, site, u0), energy)


def _amplitude(energy_at, energy: float) -> float:
    """The smallest a > 0 with energy_at(a) = energy (energy_at(0) = 0, growing from 0), bracketed
    by doubling from 1e-3 and found by Brent's method; ParameterError where the energy along the
    path peaks below ``energy`` or no a < U0_LIMIT reaches it."""
    from scipy.optimize import (  # here: a job that starts no orbit does not import it
        brentq,
        minimize_scalar,
    )

    def residual(a):
        return energy_at(a) - energy

    lo, e_lo, hi = 0.0, 0.0, 1e-3
    while hi < U0_LIMIT:
        e_hi = residual(hi) + energy
        if e_hi >= energy:
            return brentq(residual, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        if e_hi < e_lo:
            peak = minimize_scalar(lambda x: -energy_at(x), bounds=(0.0, hi), method="bounded",
                                   options={"xatol": 1e-12})
            e_max = -peak.fun
            if e_max >= energy:
                return brentq(residual, 0.0, peak.x, xtol=1e-15, rtol=4 * np.finfo(float).eps)
            raise ParameterError("energy", energy,
                                 f"at most {e_max:.6g}: the potential along this excitation peaks there")
        lo, e_lo, hi = hi, e_hi, 2.0 * hi
    raise ParameterError("energy", energy, f"an energy reached with u0 < {U0_LIMIT:g}")


def initial_state(model: int, chain, energy: float, site: int) -> tuple[np.ndarray, np.ndarray, float]:
    """(u, p, u0): bead ``site`` displaced by u0 > 0 so that H = energy, all momenta zero."""
    u0 = initial_displacement(model, chain, energy, site)
    u = np.zeros(chain.N)
    u[site - 1] = u0
    return u, np.zeros(chain.N), u0


#: What an :class:`Excitation` may excite, in which variable, and the phases of a block.
EXCITATION_KINDS = ("site", "mode", "block")
EXCITATION_VARIABLES = ("displacement", "momentum")
EXCITATION_PHASES = ("alternating", "random")
#: The stream of ``numpy.random.default_rng([seed, PHASE_STREAM])`` a block's random phases come from.
PHASE_STREAM = 3


@dataclass(frozen=True)
class Excitation:
    """A localized initial state of total energy H (of norm S for a split model), everything else
    at rest.

    ``kind``: ``site`` (bead ``site`` alone), ``mode`` (linear mode ``mode``, 1-based by increasing
    frequency, its shape U_k of ``linear.normal_modes``), or ``block`` (``width`` beads centred on
    ``site``, the extra one to the right for an even width, with alternating signs + - + ...);
    ``variable``: the pattern is given to the displacements u (momenta 0) or to the momenta p
    (displacements 0; a mode's momenta are M U_k, a block's p_n = +-sqrt(m_n) so that every bead
    of the block gets the same kinetic energy). The amplitude a > 0 is fixed by H(a pattern) =
    energy: in momentum exactly, a = sqrt(2 H / sum_n s_n^2 / m_n); in displacement by the
    root-finder of :func:`initial_displacement`, which the paper's single displaced bead (kind
    ``site``, ``displacement``) gives to the bit. ``phases`` ``random`` gives a block random
    signs instead (a bond model) from ``default_rng([seed, PHASE_STREAM])``.

    A split model (DNLS) takes the amount as the norm S: a site psi_site = sqrt(S) (q = sqrt(2 S),
    p = 0); a block of ``width`` sites the norm density S / width on each, psi_l = sqrt(S / width)
    exp(i phi_l) with phases phi_l alternating 0, pi, 0, ... or (``random``) uniform in [0, 2 pi)
    from the same generator (their cosine and sine from ``exactmath.sin_cos``: the same bits
    everywhere); ``variable`` does not apply, and a mode is not offered (its shape would need the
    DNLS eigenvectors). On a square lattice (``system.geometry``) ``site`` is (i, j), 1-based, and a
    block is the square of ``width`` x ``width`` sites centred on it as on a chain along each axis,
    its phases alternating as a checkerboard (0 at its first site) or random, in the lattice's
    flat order.
    """

    kind: str = "site"
    variable: str = "displacement"
    site: int = 1
    mode: int = 1
    width: int = 1
    phases: str = "alternating"
    seed: int = 0

    def __post_init__(self):
        require(self.kind in EXCITATION_KINDS, "excitation kind", self.kind, f"one of {list(EXCITATION_KINDS)}")
        require(self.variable in EXCITATION_VARIABLES, "excitation variable", self.variable,
                f"one of {list(EXCITATION_VARIABLES)}")
        require(self.phases in EXCITATION_PHASES, "excitation phases", self.phases,
                f"one of {list(EXCITATION_PHASES)}")
        require(isinstance(self.seed, (int, np.integer)) and self.seed >= 0, "excitation seed", self.seed,
                "an integer >= 0")
        for key in ("mode", "width"):
            value = getattr(self, key)
            require(isinstance(value, (int, np.integer)) and value >= 1, f"excitation {key}", value,
                    "an integer >= 1")
        site = self.site if isinstance(self.site, (tuple, list)) else (self.site,)
        require(len(site) in (1, 2) and all(isinstance(v, (int, np.integer)) and not isinstance(v, bool) and v >= 1
                                            for v in site),
                "excitation site", self.site, "an integer >= 1, or (i, j) of integers >= 1 on a square lattice")
        object.__setattr__(self, "site", site[0] if len(site) == 1 else tuple(int(v) for v in site))

    def check(self, N: int) -> None:
        """ParameterError where the excitation does not fit a chain of N beads."""
        if self.kind == "mode":
            require(self.mode <= N, "excitation mode", self.mode, f"a mode number 1..N = {N}")
            return
        first, last = self.beads()
        require(1 <= first and last <= N, "excitation site" if self.kind == "site" else "excitation block",
                self.site if self.kind == "site" else f"beads {first}..{last}", f"beads within 1..N = {N}")

    def beads(self) -> tuple[int, int]:
        """First and last excited bead (1-based) of a site or block excitation."""
        width = self.width if self.kind == "block" else 1
        first = self.site - (width - 1) // 2
        return first, first + width - 1

    def pattern(self, chain) -> np.ndarray:
        """The unscaled pattern s (N,) on the excited variable."""
        if chain.geometry.dimension == 1:
            self.check(chain.N)
        if self.kind == "mode":
            from chainchaos.system.linear import (
                normal_modes,  # the eigensolver: only for mode excitations
            )

            shape = normal_modes(chain)[1][:, self.mode - 1]
            shape = shape / np.max(np.abs(shape))
            return chain.mass * shape if self.variable == "momentum" else shape
        s = np.zeros(chain.N)
        if chain.geometry.dimension == 2:
            require(self.kind != "mode", "excitation kind", self.kind, "site or block on a square lattice")
            numbers, signs = self.lattice_sites(chain.geometry)
            if self.phases == "random":
                signs = np.where(self._generator().uniform(size=numbers.size) < 0.5, 1.0, -1.0)
            s[numbers] = signs * (np.sqrt(chain.mass[numbers]) if self.variable == "momentum" else 1.0)
            return s
        first, last = self.beads()
        signs = np.where(np.arange(last - first + 1) % 2 == 0, 1.0, -1.0)
        if self.phases == "random":
            signs = np.where(self._generator().uniform(size=last - first + 1) < 0.5, 1.0, -1.0)
        s[first - 1:last] = signs * (np.sqrt(chain.mass[first - 1:last]) if self.variable == "momentum" else 1.0)
        return s

    def _generator(self) -> np.random.Generator:
        return np.random.default_rng([int(self.seed), PHASE_STREAM])

    def lattice_sites(self, geometry) -> tuple[np.ndarray, np.ndarray]:
        """(numbers, signs): the excited sites of a site or block excitation on ``geometry``
        (``system.geometry``), 0-based in its flat order, and their alternating signs (a
        checkerboard on a square lattice). A chain's are :meth:`beads`' range."""
        site = self.site if isinstance(self.site, tuple) else (self.site,)
        require(len(site) == geometry.dimension, "excitation site", self.site,
                f"{'an integer' if geometry.dimension == 1 else '(i, j)'} on a lattice of shape {list(geometry.shape)}")
        width = self.width if self.kind == "block" else 1
        firsts = [s - (width - 1) // 2 for s in site]
        for axis, (first, length) in enumerate(zip(firsts, geometry.shape)):
            require(1 <= first and first + width - 1 <= length,
                    "excitation site" if self.kind == "site" else "excitation block",
                    self.site if self.kind == "site" else f"sites {first}..{first + width - 1} along axis {axis}",
                    f"sites within 1..{length} along axis {axis}")
        offsets = np.arange(width)
        if geometry.dimension == 1:
            return firsts[0] - 1 + offsets, np.where(offsets % 2 == 0, 1.0, -1.0)
        di, dj = np.meshgrid(offsets, offsets, indexing="xy")  # the block's lines in the flat order
        numbers = (firsts[1] - 1 + dj.ravel()) * geometry.shape[0] + (firsts[0] - 1 + di.ravel())
        return numbers, np.where((di + dj).ravel() % 2 == 0, 1.0, -1.0)

    def split_state(self, chain, norm: float) -> tuple[np.ndarray, np.ndarray, float]:
        """(q, p, a) of a split model's lattice: norm S = ``norm`` on the site or block, a = its
        amplitude sqrt(2 S / sites) in q, p (the class docstring)."""
        require(self.kind != "mode", "excitation kind", self.kind, "site or block for a split model (DNLS)")
        numbers, signs = self.lattice_sites(chain.geometry)
        a = math.sqrt(2.0 * norm / numbers.size)
        q, p = np.zeros(chain.N), np.zeros(chain.N)
        if self.phases == "random":
            from chainchaos.kernels.exactmath import sin_cos

            sine, cosine = sin_cos(self._generator().uniform(0.0, 2.0 * math.pi, numbers.size))
            q[numbers], p[numbers] = a * cosine, a * sine
        else:
            q[numbers] = a * signs
        return q, p, a

    def state(self, model, chain, energy: float) -> tuple[np.ndarray, np.ndarray, float]:
        """(u, p, a): the excited state with H = ``energy`` (norm S = ``energy`` for a split
        model) and its amplitude a."""
        require(np.isfinite(energy) and energy > 0, "energy", energy, "a finite energy > 0")
        if get_model(model).is_split:
            return self.split_state(chain, energy)
        s = self.pattern(chain)
        zeros = np.zeros(chain.N)
        if self.variable == "momentum":
            a = math.sqrt(2.0 * energy / float(np.sum(s * s / chain.mass)))
            return zeros, a * s, a
        a = _amplitude(lambda x: float(total_energy(model, chain, x * s, zeros)), energy)
        return a * s, zeros, a


def extra_deviations(N: int, seed: int, count: int, stream: int) -> tuple[np.ndarray, np.ndarray]:
    """``count`` more deviation vectors (du, dp), each (count, N): du and dp uniform in [-1, 1]
    from default_rng([seed, stream, i]), each normalised to 1 (docs/conventions.md#deviation-vector);
    ``stream`` 1 for the Lyapunov spectrum's, 2 for GALI's."""
    du, dp = np.zeros((count, N)), np.zeros((count, N))
    for i in range(count):
        v = np.random.default_rng([int(seed), int(stream), i + 1]).uniform(-1.0, 1.0, 2 * N)
        v = v / norm(v)
        du[i], dp[i] = v[:N], v[N:]
    return du, dp


def orthonormalised(first: np.ndarray, others: np.ndarray) -> np.ndarray:
    """``others`` (k, 2N) made orthogonal to the unit deviation vector ``first`` (2N,) and to each
    other and normalised (``kernels.exactmath.gram_schmidt``): the start of a Lyapunov spectrum, whose
    first QR then measures the dynamics only."""
    W = np.vstack([first, others]).astype(float)
    gram_schmidt(W, 1, W.shape[0], np.zeros(W.shape[0]))
    return W[1:]


def initial_deviation(N: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """Deviation vector (du, dp) with du = 0 and dp uniform in [-1, 1] from default_rng(seed),
    normalised to |(du, dp)| = 1 (the paper's choice, docs/conventions.md#deviation-vector)."""
    dp = np.random.default_rng(seed).uniform(-1.0, 1.0, N)
    return np.zeros(N), dp / norm(dp)
