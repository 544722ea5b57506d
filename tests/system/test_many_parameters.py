"""A model of one's own with as many parameters per bond and per site as its law needs.

The engines read a bond's parameters as a tuple whose length is the model's (``Model.parameter_names``),
fixed when the model's kernels compile. The Morse bond of ``examples/morse.py`` carries four
(K2, a, K2/a, K2/(2a^2)), the derived constants that kernels without division need; a
Klein-Gordon lattice of one's own below carries the same bond and a site law of three parameters.
Each runs on every engine: the SIMD lanes give the single engine's bits (chains and square
lattices), the energy is conserved to the scheme's order, and the Morse chain's small-amplitude
limit is the harmonic chain of the same K2.
"""

from pathlib import Path

import numpy as np
import pytest
from engine.test_lattice_2d import assert_every_kind_gives_the_same_bits
from numba import njit

from chainchaos import Model, check_model, kg_chain, random_chain
from chainchaos.engine.model_checks import ModelCheckError, _module_of_file
from chainchaos.engine.problem import Problem
from chainchaos.kernels.simd import LANES
from chainchaos.system.chain import kg_lattice
from chainchaos.system.models import total_energy
from chainchaos.system.models.base import SiteLaw

# examples/morse.py as load_model imports it (under the file's stem, as Numba's cache names its
# kernels), without adding its model to the registry
MORSE = _module_of_file(Path(__file__).parents[2] / "examples" / "morse.py").MORSE
THIRD = 1.0 / 3.0


@njit
def _cubic_quartic_force(S, u):
    return u * (S[0] + u * (S[1] + u * S[2]))


@njit
def _cubic_quartic_force_stiffness(S, u):
    return u * (S[0] + u * (S[1] + u * S[2])), S[0] + u * (S[1] * 2.0 + u * (S[2] * 3.0))


@njit
def _cubic_quartic_potential(S, u):
    return u * u * (S[0] * 0.5 + u * (S[1] * THIRD + u * (S[2] * 0.25)))


def _site_rows(lattice):
    """(eps, c3, c4): the KG lattice's eps, a cubic term of a tenth of it, a unit quartic."""
    return lattice.eps, 0.1 * lattice.eps, np.ones_like(lattice.eps)


def _bond_rows(lattice):
    """The Morse bond's four rows on a KG lattice: K2 = 1/W and a = 1 + K2 (one per bond)."""
    return MORSE.parameters(lattice, a=1.0 + np.asarray(lattice.K2))


MORSE_KG = Model(
    name="morse_kg", label="Morse KG", colour="#6a1b9a", parameter_names=("K2", "a", "K2/a", "K2/(2a^2)"),
    parameters=_bond_rows, force=MORSE.force, force_stiffness=MORSE.force_stiffness, potential=MORSE.potential,
    lattice="kg",
    site=SiteLaw(parameter_names=("eps", "c3", "c4"), parameters=_site_rows, force=_cubic_quartic_force,
                 force_stiffness=_cubic_quartic_force_stiffness, potential=_cubic_quartic_potential))


def test_a_model_s_parameter_arrays_have_one_row_per_name():
    chain = random_chain(879, 5.0, 20)
    P = MORSE.bond_parameters(chain)
    assert P.shape == (4, 21)
    np.testing.assert_array_equal(P[2], chain.K2 / 2.0)  # K2 / a, a = 2
    lattice = kg_chain(3, 4.0, 20)
    assert MORSE_KG.bond_parameters(lattice).shape == (4, 21) and MORSE_KG.site_parameters(lattice).shape == (3, 20)


def test_both_models_pass_the_checks_and_a_row_short_of_the_names_is_refused():
    check_model(MORSE)
    check_model(MORSE_KG)
    short = Model(name="short", label="short", colour="#000000", parameter_names=MORSE.parameter_names,
                  parameters=lambda chain: MORSE.parameters(chain)[:3], force=MORSE.force,
                  force_stiffness=MORSE.force_stiffness, potential=MORSE.potential)
    with pytest.raises(ModelCheckError, match=r"check 'parameters'.*3 rows"):
        check_model(short)


def _random_states(N, B, scale, seed=3):
    rng = np.random.default_rng(seed)
    return (scale * rng.normal(size=(N, B)) for _ in range(4))


@pytest.mark.parametrize("model, lattices, scale", [
    (MORSE, [random_chain(s, 5.0, 30) for s in range(LANES + 3)], 0.02),
    (MORSE_KG, [kg_chain(s, 4.0, 30) for s in range(LANES + 3)], 0.3),
    (MORSE_KG, [kg_lattice(s, 4.0, (7, 5), ("fixed", "free")) for s in range(LANES + 3)], 0.3),
], ids=["morse chain", "morse_kg chain", "morse_kg square"])
def test_the_simd_lanes_give_the_single_engine_s_bits(model, lattices, scale):
    """LANES + 3 lanes of different lattices with the tangent map: in SIMD blocks (the last
    padded), one by one, and blocks with the rest one by one, the same bits."""
    q, p, dq, dp = _random_states(lattices[0].N, len(lattices), scale)
    single = assert_every_kind_gives_the_same_bits(Problem(model, lattices, integrator="ABA864", dt=0.05,
                                                           check_every=7), (q, p, dq, dp), (60, 13))
    assert (single.bad == -1).all() and np.all(single.log_growth != 0.0)


@pytest.mark.parametrize("lattice", [kg_chain(5, 4.0, 30), kg_lattice(5, 4.0, (6, 6), ("fixed", "fixed"))],
                         ids=["chain", "square"])
def test_the_energy_error_falls_at_the_scheme_s_order(lattice):
    """ABA864 is of order 4: halving dt divides the largest energy error by about 2^4 (the site
    law's and the bond law's three and four parameters all enter H)."""
    q, p, _, _ = _random_states(lattice.N, 1, 0.4, seed=8)
    H0 = total_energy(MORSE_KG, lattice, q[:, 0], p[:, 0])
    errors = []
    for dt in (0.1, 0.05):
        engine = Problem(MORSE_KG, [lattice], integrator="ABA864", dt=dt, tangent=False).engine(q, p, kind="single")
        worst = 0.0
        for _ in range(20):
            engine.advance(int(round(1.0 / dt)))
            worst = max(worst, abs(total_energy(MORSE_KG, lattice, engine.q[:, 0], engine.p[:, 0]) - H0) / H0)
        errors.append(worst)
    assert errors[0] < 1e-5 and 2.0 ** 3.5 < errors[0] / errors[1] < 2.0 ** 4.5, errors


def test_the_morse_chain_at_small_amplitude_is_the_harmonic_chain():
    """V = K2 D^2 / 2 + O(a K2 D^3): the same orbit of the Morse and the harmonic chain (same K2,
    same scheme and steps) differs by a relative O(a amplitude), ten times less at a tenth of it."""
    chain = random_chain(879, 5.0, 30)
    rng = np.random.default_rng(4)
    shape = rng.normal(size=(30, 1)) * np.asarray(chain.delta).mean()
    differences = []
    for amplitude in (1e-3, 1e-4):
        runs = {}
        for model in (MORSE, "harmonic"):
            engine = Problem(model, [chain], dt=0.02, tangent=False).engine(amplitude * shape, np.zeros((30, 1)),
                                                                            kind="single")
            engine.advance(2000)
            runs[getattr(model, "name", model)] = engine.q[:, 0]
        differences.append(np.linalg.norm(runs["morse"] - runs["harmonic"]) / np.linalg.norm(runs["harmonic"]))
    assert differences[0] < 0.05 and 8.0 < differences[0] / differences[1] < 12.0, differences
