"""Linear analysis against exact results."""

import numpy as np
import pytest

from chainchaos import mode_participation, normal_modes, random_chain
from chainchaos.observe.formulas import normalised_entropy, spectral_entropy
from chainchaos.records.io import ensemble_dataset
from chainchaos.studies.search.selection import (
    SelectionCriteria,
    qualifies,
    select_realization,
)
from chainchaos.system.linear import modal_energies, mode_energy_density


def test_homogeneous_chain_parameters(homogeneous):
    assert np.allclose(homogeneous.A, 1 / 6) and np.allclose(homogeneous.delta, 1.0)
    assert np.allclose(homogeneous.K2, 0.25) and np.allclose(homogeneous.mass, 1.0)


def test_homogeneous_spectrum_is_exact(homogeneous):
    N = homogeneous.N
    omega, U = normal_modes(homogeneous)
    k = np.arange(1, N + 1)
    assert np.allclose(omega, np.sin(k * np.pi / (2 * (N + 1))), atol=1e-14, rtol=0)
    n = np.arange(1, N + 1)[:, None]
    exact = np.sqrt(2 / (N + 1)) * np.sin(n * k * np.pi / (N + 1))
    assert np.allclose(np.abs(U), np.abs(exact), atol=1e-12)


def test_modes_are_mass_orthonormal_and_diagonalise_stiffness(chain):
    omega, U = normal_modes(chain)
    K2 = chain.K2
    K = np.diag(K2[:-1] + K2[1:]) - np.diag(K2[1:-1], 1) - np.diag(K2[1:-1], -1)
    assert np.allclose(U.T @ np.diag(chain.mass) @ U, np.eye(chain.N), atol=1e-12)
    assert np.allclose(U.T @ K @ U, np.diag(omega**2), atol=1e-12)
    assert np.all(np.diff(omega) > 0)


def test_single_pure_mode_has_zero_spectral_entropy(chain):
    omega, U = normal_modes(chain)
    u = 0.3 * U[:, 33]
    E = modal_energies(chain, omega, U, u, np.zeros(chain.N))
    assert E.argmax() == 33 and spectral_entropy(E) == pytest.approx(0.0, abs=1e-12)
    assert E[33] == pytest.approx(0.5 * (0.3 * omega[33]) ** 2, rel=1e-12)
    S = spectral_entropy(np.vstack([E, np.ones(chain.N)]))
    assert normalised_entropy(S, 0.25, chain.N)[1] == pytest.approx(0.0, abs=1e-12)


def test_participation_conventions_on_homogeneous_chain(homogeneous):
    P = mode_participation(homogeneous)
    P_avg = mode_participation(homogeneous, "period_averaged")
    assert np.all((1 <= P) & (P <= 40)) and np.all((1 <= P_avg) & (P_avg <= 40))
    # extended modes of the homogeneous chain spread over most of the chain
    assert np.median(P) > 25


def test_single_bead_displacement_participation_bounds(chain, homogeneous):
    """A displacement of one bead strains its two bonds; their energies e_l, e_r are split half-half,
    h = (e_l/2, (e_l + e_r)/2, e_r/2) / (e_l + e_r), so 2 <= P <= 8/3, with 8/3 exactly when the two
    bonds carry equal energy (docs/conventions.md#mode-energy-density)."""
    for c in (homogeneous, chain):
        u = np.zeros((c.N, 1))
        u[20, 0] = 1.0
        P = float(1 / np.sum(mode_energy_density(c, np.ones(1), u) ** 2))
        e_l, e_r = c.K2[20], c.K2[21]
        x = e_l / (e_l + e_r)
        assert P == pytest.approx(1 / ((x / 2) ** 2 + 0.25 + ((1 - x) / 2) ** 2), rel=1e-12)
        assert 2 <= P <= 8 / 3 + 1e-12
    assert float(1 / np.sum(mode_energy_density(homogeneous, np.ones(1), u) ** 2)) == pytest.approx(8 / 3)


def test_ensemble_of_homogeneous_chains_has_no_spread(homogeneous):
    ds = ensemble_dataset([1.0, 5.0], 20)
    assert np.allclose(ds.std_participation.sel(alpha=1.0), 0.0, atol=1e-10)
    assert np.allclose(ds.mean_participation.sel(alpha=1.0), np.sort(mode_participation(homogeneous))[::-1])
    assert ds.mean_participation.sel(alpha=5.0).values[-1] < 4  # strongly localised modes appear


def test_realization_search_returns_a_qualifying_chain():
    criteria = SelectionCriteria(n_seeds=1000)
    chain, record = select_realization(criteria)
    ok, P = qualifies(chain, criteria)
    assert ok and criteria.p_min <= P <= criteria.p_max
    assert np.array_equal(chain.radius, random_chain(record["selection_seed"], 5.0).radius)
    # no lower score among the qualifying seeds scanned
    for seed in range(criteria.n_seeds):
        other = random_chain(seed, 5.0)
        if qualifies(other, criteria)[0]:
            assert np.abs(other.delta[20:22] - 1.06).sum() >= record["selection_score"] - 1e-15
