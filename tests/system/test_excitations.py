"""Block excitations (chainchaos.system.initial.Excitation) with random phases or signs, for a split
model (the DNLS: given norm density, random phases) and a bond model (given energy, random signs)."""

import numpy as np
import pytest

from chainchaos.errors import ParameterError
from chainchaos.system.chain import dnls_chain, kg_chain
from chainchaos.system.initial import Excitation
from chainchaos.system.models import total_energy
from chainchaos.system.models.split import norm


def test_a_dnls_block_has_its_norm_density_on_each_site_with_random_phases():
    lattice = dnls_chain(4, 4.0, 64, beta=0.72)
    block = Excitation(kind="block", site=32, width=21, phases="random", seed=4)
    q, p, a = block.state("dnls", lattice, 21.0)
    density = (q**2 + p**2) / 2
    first, last = block.beads()
    np.testing.assert_allclose(density[first - 1:last], 1.0, rtol=1e-15)
    assert np.all(density[:first - 1] == 0) and np.all(density[last:] == 0) and last - first + 1 == 21
    assert norm(q, p) == pytest.approx(21.0, rel=1e-15)
    phases = np.angle(q + 1j * p)[first - 1:last]
    assert np.unique(np.round(phases, 12)).size == 21 and np.ptp(phases) > 3  # spread over the circle
    again = Excitation(kind="block", site=32, width=21, phases="random", seed=4).state("dnls", lattice, 21.0)
    other = Excitation(kind="block", site=32, width=21, phases="random", seed=5).state("dnls", lattice, 21.0)
    assert np.array_equal(again[0], q) and not np.array_equal(other[0], q)  # seeded by the realization


def test_a_dnls_site_and_an_alternating_block():
    lattice = dnls_chain(0, 4.0, 16)
    q, p, _ = Excitation(site=8).state("dnls", lattice, 2.5)
    assert norm(q, p) == pytest.approx(2.5, rel=1e-15) and np.count_nonzero(q) == 1 and not p.any()
    q, p, _ = Excitation(kind="block", site=8, width=3).state("dnls", lattice, 3.0)
    assert np.sign(q[6:9]).tolist() == [1.0, -1.0, 1.0] and not p.any()
    with pytest.raises(ParameterError, match="site or block"):
        Excitation(kind="mode", mode=2).state("dnls", lattice, 1.0)


def test_a_kg_block_with_random_momentum_signs_has_its_energy():
    lattice = kg_chain(2, 4.0, 64)
    block = Excitation(kind="block", variable="momentum", site=32, width=21, phases="random", seed=2)
    u, p, _ = block.state("kg", lattice, 21 * 0.37)
    assert not u.any() and total_energy("kg", lattice, u, p) == pytest.approx(21 * 0.37, rel=1e-14)
    signs = np.sign(p[np.flatnonzero(p)])
    assert signs.size == 21 and 0 < np.sum(signs > 0) < 21
    np.testing.assert_allclose(p[np.flatnonzero(p)] ** 2 / 2, 0.37, rtol=1e-14)  # the same energy on every site
    alternating = Excitation(kind="block", variable="momentum", site=32, width=21).state("kg", lattice, 1.0)[1]
    assert np.array_equal(np.sign(alternating[alternating != 0]), np.where(np.arange(21) % 2 == 0, 1.0, -1.0))


def test_bad_phases_are_named():
    with pytest.raises(ParameterError, match="excitation phases"):
        Excitation(kind="block", phases="spiral")
