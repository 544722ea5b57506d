"""The split engines on the square DNLS lattice (system.geometry) against exact results: an
eigenvector of the 2D Anderson model rotating at its eigenvalue (beta = 0), the energy from the
kernel against the Hamiltonian written with the lattice's adjacency matrix, each scheme's order,
the tangent map against finite differences, a lattice of width 1 equal to the chain to the bit,
a lattice equal to its transpose, and the batch engine equal to the single one, lane by lane."""

import numpy as np
import pytest
from engine.test_split import DNLS, observed_order, packet, run  # the chain's helpers: they read the lattice's shape

from chainchaos.engine.problem import Problem
from chainchaos.engine.split_schemes import SPLIT_SCHEMES
from chainchaos.errors import ParameterError
from chainchaos.system.chain import DNLSLattice, dnls_chain, dnls_lattice
from chainchaos.system.geometry import Geometry, adjacency
from chainchaos.system.models.split import norm, split_energy


def linear_matrix(lattice):
    """The Anderson Hamiltonian diag(eps) - adjacency: i dpsi/dt = H psi at beta = 0."""
    return np.diag(lattice.eps) - adjacency(lattice.geometry)


def test_a_square_lattice_s_bonds_and_sites():
    g = Geometry((3, 2), ("fixed", "free"))
    assert g.N == 6 and g.site(2, 1) == 5 and g.shape2 == (3, 2)
    # along the lines with their walls, then across them without
    assert g.bonds().tolist() == [[-1, 0], [0, 1], [1, 2], [2, -1], [-1, 3], [3, 4], [4, 5], [5, -1],
                                  [0, 3], [1, 4], [2, 5]]
    assert adjacency(g).sum() == 2 * 7  # 4 bonds along, 3 across
    assert Geometry((5,)).bonds().shape == (6, 2)


@pytest.mark.parametrize("shape, boundary, match", [((0, 3), None, "integer lengths >= 1"),
                                                     ((2, 2, 2), None, "a chain"),
                                                     ((4, 4), ("fixed", "open"), "'fixed', 'free'"),
                                                     ((1,), None, "at least 2 sites"),
                                                     ((4, 4), ("fixed",), "per axis")])
def test_a_bad_shape_or_boundary_is_named_with_what_is_allowed(shape, boundary, match):
    with pytest.raises(ParameterError, match=match):
        Geometry(shape, boundary)
    with pytest.raises(ParameterError, match="geometry"):
        DNLSLattice(np.zeros(10), W=1.0, geometry=Geometry((3, 3)))


@pytest.mark.parametrize("scheme", ["ABC2", "s9ABC6"])
def test_an_anderson_eigenvector_of_the_square_lattice_rotates_at_its_eigenvalue(scheme):
    """beta = 0: psi = v exp(-i lambda t) for an eigenvector v of the 2D Anderson model."""
    lattice = dnls_lattice(3, 6.0, (7, 5), beta=0.0)
    lam, V = np.linalg.eigh(linear_matrix(lattice))
    k = 17
    v, t, dt = V[:, k], 20.0, 0.01
    q, p, *_ = run(lattice, np.sqrt(2) * v, np.zeros(lattice.N), scheme, dt, int(t / dt))
    exact_q, exact_p = np.sqrt(2) * v * np.cos(lam[k] * t), -np.sqrt(2) * v * np.sin(lam[k] * t)
    error = np.abs(q - exact_q).max() + np.abs(p - exact_p).max()
    assert error < {"ABC2": 1e-3, "s9ABC6": 1e-9}[scheme]


def test_the_energy_kernel_is_the_hamiltonian_of_the_lattice():
    """H = sum eps |psi|^2 + beta/2 |psi|^4 - psi^* A psi, A the adjacency matrix of the lattice."""
    for shape, boundary in [((6, 4), None), ((5, 5), ("free", "fixed")), ((9,), None)]:
        lattice = dnls_lattice(4, 5.0, shape, beta=1.7, boundary=boundary)
        q, p = packet(lattice.N, 4)
        psi = (q + 1j * p) / np.sqrt(2)
        expected = (np.sum(lattice.eps * np.abs(psi) ** 2 + 0.5 * lattice.beta * np.abs(psi) ** 4)
                    - np.real(np.conj(psi) @ adjacency(lattice.geometry) @ psi))
        assert abs(split_energy(DNLS, lattice, q, p) - expected) < 1e-12 * abs(expected)


@pytest.mark.parametrize("scheme", ["ABC2", "s9ABC6", "s11ABC6", "s17ABC8"])
@pytest.mark.parametrize("quantity", ["energy", "norm"])
def test_every_scheme_has_its_order_on_the_square_lattice(scheme, quantity):
    lattice = dnls_lattice(5, 4.0, (4, 3), beta=1.0)
    assert abs(observed_order(scheme, quantity, lattice) - SPLIT_SCHEMES[scheme].order) < 0.5


def test_tangent_map_is_the_derivative_of_the_flow_on_the_square_lattice():
    """The deviation after a few steps against central differences of the flow (h = 1e-6)."""
    lattice = dnls_lattice(2, 4.0, (4, 4), beta=3.0)
    q0, p0 = packet(lattice.N, 2, 0.8)
    vq, vp = packet(lattice.N, 9)
    scale = np.sqrt(np.sum(vq**2 + vp**2))
    vq, vp = vq / scale, vp / scale
    q, p, dq, dp, growth = run(lattice, q0, p0, "s9ABC6", 0.05, 40, dq=vq, dp=vp)
    h = 1e-6
    plus = run(lattice, q0 + h * vq, p0 + h * vp, "s9ABC6", 0.05, 40)
    minus = run(lattice, q0 - h * vq, p0 - h * vp, "s9ABC6", 0.05, 40)
    fd = np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * h)
    tangent = np.concatenate([dq, dp]) * np.exp(growth)
    assert np.abs(tangent - fd).max() < 1e-7 * np.abs(fd).max()


def test_a_lattice_of_width_1_is_the_chain_to_the_bit():
    chain = dnls_chain(7, 4.0, 30, beta=1.2)
    strip = dnls_lattice(7, 4.0, (30, 1), beta=1.2, boundary=("fixed", "free"))
    np.testing.assert_array_equal(chain.eps, strip.eps)
    q0, p0 = packet(30, 7)
    dq0, dp0 = packet(30, 8)
    a = run(chain, q0, p0, "s11ABC6", 0.05, 300, dq=dq0, dp=dp0)
    b = run(strip, q0, p0, "s11ABC6", 0.05, 300, dq=dq0, dp=dp0)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    assert split_energy(DNLS, chain, a[0], a[1]) == split_energy(DNLS, strip, b[0], b[1])


def test_a_lattice_and_its_transpose_give_the_same_orbit():
    """(Nx, Ny) and (Ny, Nx) with the disorder transposed: the same dynamics, sites renumbered
    (the sums run in another order: equal to rounding)."""
    lattice = dnls_lattice(8, 5.0, (5, 3), beta=1.0)
    grid = lattice.eps.reshape(3, 5)  # [j, i]
    transposed = DNLSLattice(grid.T.ravel(), W=5.0, beta=1.0, geometry=Geometry((3, 5)))
    q0, p0 = packet(15, 8)
    a = run(lattice, q0, p0, "s9ABC6", 0.05, 200)
    b = run(transposed, q0.reshape(3, 5).T.ravel(), p0.reshape(3, 5).T.ravel(), "s9ABC6", 0.05, 200)
    np.testing.assert_allclose(b[0], a[0].reshape(3, 5).T.ravel(), rtol=0, atol=1e-11)
    np.testing.assert_allclose(b[1], a[1].reshape(3, 5).T.ravel(), rtol=0, atol=1e-11)


@pytest.mark.parametrize("lanes", [1, 11])
def test_batch_engine_gives_each_lane_the_single_engine_s_bits_on_the_square_lattice(lanes):
    shape = (6, 4)
    chains = [dnls_lattice(s, 4.0, shape, beta=1.5) for s in range(lanes)]
    N = chains[0].N
    rng = np.random.default_rng(lanes)
    q, p, dq, dp = (rng.normal(size=(N, lanes)) for _ in range(4))
    problem = Problem("dnls", chains, integrator="s11ABC6", dt=0.05, check_every=7)
    batch, single = problem.engine(q, p, dq, dp, "batch"), problem.engine(q, p, dq, dp, "single")
    for n in (30, 5):
        batch.advance(n)
        single.advance(n)
    for a, b in zip((batch.q, batch.p, batch.dq, batch.dp, batch.log_growth),
                    (single.q, single.p, single.dq, single.dp, single.log_growth)):
        np.testing.assert_array_equal(a, b)


def test_lanes_of_one_problem_share_their_lattice_shape():
    chains = [dnls_lattice(0, 4.0, (4, 3)), dnls_lattice(1, 4.0, (3, 4))]
    rng = np.random.default_rng(0)
    q, p = (rng.normal(size=(12, 2)) for _ in range(2))
    with pytest.raises(ParameterError, match="one lattice shape"):
        Problem("dnls", chains).engine(q, p, kind="batch")


def test_a_square_block_carries_the_norm_on_width_squared_sites_as_a_checkerboard():
    from chainchaos.system.initial import Excitation

    lattice = dnls_lattice(0, 4.0, (9, 7))
    q, p, a = Excitation(kind="block", site=(5, 4), width=3).split_state(lattice, 2.25)
    grid = q.reshape(7, 9)  # [j, i]
    assert np.count_nonzero(q) == 9 and not p.any() and np.isclose(norm(q, p), 2.25)
    np.testing.assert_array_equal(grid[2:5, 3:6], a * np.array([[1, -1, 1], [-1, 1, -1], [1, -1, 1]]))
    # a strip of width 1 gets the chain's block, to the bit
    strip = dnls_lattice(0, 4.0, (9, 1), boundary=("fixed", "free"))
    on_strip = Excitation(kind="block", site=(5, 1), width=1, phases="random", seed=3).split_state(strip, 1.0)
    on_chain = Excitation(kind="block", site=5, width=1, phases="random", seed=3).split_state(dnls_chain(0, 4.0, 9), 1.0)
    for x, y in zip(on_strip, on_chain):
        np.testing.assert_array_equal(x, y)
    with pytest.raises(ParameterError, match="excitation block"):
        Excitation(kind="block", site=(1, 4), width=3).split_state(lattice, 1.0)
    with pytest.raises(ParameterError, match=r"\(i, j\)"):
        Excitation(kind="site", site=5).split_state(lattice, 1.0)


def test_second_moment_of_a_uniform_square_is_twice_that_of_its_side():
    """h = 1/L^2 on an L x L square: m2 = 2 (L^2 - 1)/12, about its centre wherever it lies;
    on a chain the positions 1..N give the chain's m2, to the bit."""
    from chainchaos.observe.formulas import second_moment, site_positions

    g = Geometry((10, 8))
    h = np.zeros(g.N)
    for j in range(2, 7):
        h[j * 10 + 3: j * 10 + 8] = 1 / 25
    assert np.isclose(second_moment(h, site_positions(g)), 2 * (25 - 1) / 12, rtol=1e-14)
    chain = np.random.default_rng(1).random(17)
    chain /= chain.sum()
    assert second_moment(chain, site_positions(Geometry((17,)))) == second_moment(chain)


def test_the_growing_window_follows_a_packet_on_the_square_lattice():
    """A rectangle of sites that widens on each side the packet nears: the orbit and the mLCE
    vector of the whole lattice, to within what the cut leaves (tails below the threshold), while
    the window stays smaller than the lattice."""
    from chainchaos.run.window import Window, WindowedEngine, restricted_deviation
    from chainchaos.system.initial import Excitation

    lattice = dnls_lattice(2, 10.0, (201, 201), beta=1.0)
    q, p, _ = Excitation(kind="block", site=(101, 101), width=3).split_state(lattice, 4.5)
    rng = np.random.default_rng(0)
    dq, dp = rng.normal(size=lattice.N), rng.normal(size=lattice.N)
    problem = Problem("dnls", [lattice], dt=0.05, check_every=100)
    windowed = WindowedEngine(problem, Window(), q[:, None], p[:, None], dq[:, None], dp[:, None])
    windowed.advance(800)
    start = restricted_deviation(dq[:, None], dp[:, None], *Window.excited(q[:, None], p[:, None], lattice.geometry),
                                 geometry=lattice.geometry)
    whole = problem.engine(q[:, None].copy(), p[:, None].copy(), *start)
    whole.advance(800)
    _, lo_x, hi_x, lo_y, hi_y = windowed.spans[-1]
    assert len(windowed.spans) > 1 and 0 < lo_x and hi_x < 201 and 0 < lo_y and hi_y < 201
    assert np.abs(windowed.q - whole.q).max() < 1e-6 and np.abs(windowed.p - whole.p).max() < 1e-6
    assert abs(windowed.log_growth[0] - whole.log_growth[0]) < 1e-8
