"""The Klein-Gordon lattice in two dimensions (engine.lattice) against exact results: a normal mode
of the harmonic lattice oscillating at its frequency, the energy against the Hamiltonian written
out, each scheme's order on the energy, the tangent map against finite differences, a lattice of
width 1 with free transverse edges equal to the chain's engines to the bit, a lattice equal to
its transpose, and a study of one's own on the square lattice from one spec."""

import itertools

import numpy as np
import pytest

from chainchaos.engine.integrators import SCHEMES
from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError
from chainchaos.system.chain import KGLattice, kg_chain, kg_lattice
from chainchaos.system.geometry import Geometry, adjacency
from chainchaos.system.initial import Excitation
from chainchaos.system.models import energy_density, total_energy


def run(lattice, q, p, scheme, dt, steps, model="kg", dq=None, dp=None):
    """(q, p, dq, dp, ln growth) of one trajectory after ``steps`` steps."""
    tangent = dq is not None
    state = [np.array(a, dtype=float)[:, None] for a in (q, p)]
    deviation = [np.array(a, dtype=float)[:, None] for a in (dq, dp)] if tangent else [None, None]
    engine = Problem(model, [lattice], integrator=scheme, dt=dt, tangent=tangent, check_every=10**9).engine(
        *state, *deviation)
    engine.advance(steps)
    return engine.q[:, 0], engine.p[:, 0], engine.dq[:, 0], engine.dp[:, 0], engine.log_growth[0]


def packet(N, seed, amplitude=1.0):
    rng = np.random.default_rng(seed)
    return amplitude * rng.normal(size=N), amplitude * rng.normal(size=N)


def stiffness(lattice):
    """The harmonic lattice's stiffness matrix: eps_l on the diagonal, 1/W for each of a site's
    bonds (a wall's too) on it and -1/W between bonded sites."""
    g = lattice.geometry
    degree = np.zeros(g.N)
    for a, b in g.bonds():
        degree[[s for s in (a, b) if s >= 0]] += 1
    return np.diag(lattice.eps + degree / lattice.W) - adjacency(g) / lattice.W


def test_a_normal_mode_of_the_harmonic_square_lattice_oscillates_at_its_frequency():
    lattice = kg_lattice(3, 4.0, (6, 5), ("fixed", "free"))
    omega2, V = np.linalg.eigh(stiffness(lattice))
    k, t, dt = 11, 20.0, 0.01
    v, omega = V[:, k], np.sqrt(omega2[k])
    q, p, *_ = run(lattice, 0.1 * v, np.zeros(lattice.N), "SRKN6b", dt, int(t / dt), model="kg_linear")
    assert np.abs(q - 0.1 * v * np.cos(omega * t)).max() < 1e-9
    assert np.abs(p + 0.1 * omega * v * np.sin(omega * t)).max() < 1e-9


def test_the_energy_is_the_hamiltonian_of_the_square_lattice():
    """H = sum p^2/2 + eps u^2/2 + u^4/4 + (1/2W) sum over bonds (u_a - u_b)^2, a wall's u zero;
    the energy density sums to 1 and gives each bond half to each of its sites."""
    for boundary in [("fixed", "fixed"), ("free", "fixed"), ("free", "free")]:
        lattice = kg_lattice(4, 3.0, (5, 4), boundary)
        u, p = packet(lattice.N, 4, 0.5)
        bonds = lattice.geometry.bonds()
        ua = np.where(bonds[:, 0] >= 0, u[bonds[:, 0]], 0.0)
        ub = np.where(bonds[:, 1] >= 0, u[bonds[:, 1]], 0.0)
        expected = np.sum(p**2 / 2 + lattice.eps * u**2 / 2 + u**4 / 4) + np.sum((ua - ub) ** 2) / (2 * lattice.W)
        assert abs(total_energy("kg", lattice, u, p) - expected) < 1e-13 * expected
        h = energy_density("kg", lattice, u, p)
        assert abs(h.sum() - 1.0) < 1e-14 and h.shape == (lattice.N,)


@pytest.mark.parametrize("scheme", ["verlet", "SRKN6b", "ABA864"])
def test_every_scheme_has_its_order_on_the_square_lattice(scheme):
    lattice = kg_lattice(5, 4.0, (4, 4))
    q0, p0 = packet(lattice.N, 5, 0.5)
    H0 = total_energy("kg", lattice, q0, p0)
    errors = []
    dt0 = {2: 0.02, 4: 0.05, 6: 0.1, 8: 0.2}[SCHEMES[scheme].order]
    for dt in (dt0, dt0 / 2):
        q, p, worst = q0, p0, 0.0
        for _ in range(20):
            q, p, *_ = run(lattice, q, p, scheme, dt, int(round(0.5 / dt)))
            worst = max(worst, abs(total_energy("kg", lattice, q, p) - H0))
        errors.append(worst)
    assert abs(np.log2(errors[0] / errors[1]) - SCHEMES[scheme].order) < 0.5


def test_tangent_map_is_the_derivative_of_the_flow_on_the_square_lattice():
    lattice = kg_lattice(2, 4.0, (4, 3), ("fixed", "free"))
    q0, p0 = packet(lattice.N, 2, 0.8)
    vq, vp = packet(lattice.N, 9)
    scale = np.sqrt(np.sum(vq**2 + vp**2))
    vq, vp = vq / scale, vp / scale
    q, p, dq, dp, growth = run(lattice, q0, p0, "SRKN6b", 0.05, 40, dq=vq, dp=vp)
    h = 1e-6
    plus = run(lattice, q0 + h * vq, p0 + h * vp, "SRKN6b", 0.05, 40)
    minus = run(lattice, q0 - h * vq, p0 - h * vp, "SRKN6b", 0.05, 40)
    fd = np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * h)
    tangent = np.concatenate([dq, dp]) * np.exp(growth)
    assert np.abs(tangent - fd).max() < 1e-7 * np.abs(fd).max()


@pytest.mark.parametrize("kind", ["single", "batch"])
def test_a_lattice_of_width_1_with_free_edges_is_the_chain_to_the_bit(kind):
    chain = kg_chain(7, 4.0, 30)
    strip = kg_lattice(7, 4.0, (30, 1), ("fixed", "free"))
    rng = np.random.default_rng(7)
    q, p, dq, dp = (0.4 * rng.normal(size=(30, 3)) for _ in range(4))
    on_chain = Problem("kg", [chain] * 3, dt=0.05, check_every=30).engine(q, p, dq, dp, kind)
    on_strip = Problem("kg", [strip] * 3, dt=0.05, check_every=30).engine(q, p, dq, dp)
    for engine in (on_chain, on_strip):
        engine.advance(300)
    for name in ("q", "p", "dq", "dp", "log_growth"):
        np.testing.assert_array_equal(getattr(on_strip, name), getattr(on_chain, name), err_msg=name)


def test_a_lattice_and_its_transpose_give_the_same_orbit():
    lattice = kg_lattice(8, 5.0, (5, 3))
    transposed = KGLattice(lattice.eps.reshape(3, 5).T.ravel(), W=5.0, geometry=Geometry((3, 5)))
    q0, p0 = packet(15, 8, 0.5)
    a = run(lattice, q0, p0, "SRKN6b", 0.05, 200)
    b = run(transposed, q0.reshape(3, 5).T.ravel(), p0.reshape(3, 5).T.ravel(), "SRKN6b", 0.05, 200)
    np.testing.assert_allclose(b[0], a[0].reshape(3, 5).T.ravel(), rtol=0, atol=1e-12)


def test_a_square_block_on_the_kg_lattice_has_the_energy_asked_for():
    lattice = kg_lattice(0, 4.0, (9, 9))
    u, p, a = Excitation(kind="block", site=(5, 5), width=3).state("kg", lattice, 0.9)
    assert np.count_nonzero(u) == 9 and not p.any()
    assert abs(total_energy("kg", lattice, u, p) - 0.9) < 1e-12


def test_a_kg_study_on_the_square_lattice_runs_from_one_spec():
    from chainchaos.studies.study import run_study

    spec = {"lattice": {"model": "kg", "shape": [11, 11], "W": 4.0, "realizations": 2},
            "excitation": {"kind": "block", "width": 3, "energies": [0.9]},
            "integration": {"dt": 0.05, "t_final": 30.0, "samples_per_decade": 5},
            "observables": ["participation", "second_moment", "mlce"]}
    ds = run_study(spec)
    assert (ds["valid"] == 1).all() and list(np.ravel(ds.attrs["lattice_shape"])) == [11, 11]
    assert np.isfinite(ds["mlce"].isel(time=-1)).all() and float(ds["energy_error"].max()) < 1e-5
    # the same study on a growing window: the same orbits, to within what the cut leaves
    windowed = run_study({**spec, "integration": {**spec["integration"], "window": {"margin": 2}}})
    np.testing.assert_allclose(windowed["mean_log10_participation"], ds["mean_log10_participation"], rtol=1e-9)


def test_lanes_of_one_problem_share_their_lattice_shape():
    with pytest.raises(ParameterError, match="one lattice shape"):
        Problem("kg", [kg_lattice(0, 4.0, (4, 3)), kg_lattice(1, 4.0, (3, 4))])


@pytest.mark.parametrize("model, boundary", [("kg", ("fixed", "fixed")), ("kg", ("fixed", "free")),
                                             ("kg", ("free", "fixed")), ("kg", ("free", "free")),
                                             ("kg_linear", ("fixed", "free"))])
def test_the_simd_blocks_give_the_single_loop_s_numbers_to_the_bit(model, boundary):
    """LANES + 3 lanes of different lattices of 7 x 5 sites, each boundary: every lane in SIMD
    blocks (the last padded), every lane on the single loop, and blocks with the rest on the loop
    give the same bits, checks (renormalisations) inside and at the end of each call."""
    from chainchaos.kernels.simd import LANES

    lanes = LANES + 3
    lattices = [kg_lattice(seed, 6.0, (7, 5), boundary) for seed in range(lanes)]
    rng = np.random.default_rng(3)
    q, p, dq, dp = (0.3 * rng.normal(size=(35, lanes)) for _ in range(4))
    single = assert_every_kind_gives_the_same_bits(Problem(model, lattices, integrator="ABA864", dt=0.1,
                                                           check_every=7), (q, p, dq, dp), (40, 13))
    assert np.all(single.log_growth != 0.0)


def assert_every_kind_gives_the_same_bits(problem, state, calls):
    """The problem's engines of every kind ("single", "batch", "auto") from ``state`` (q, p, dq,
    dp), each advanced by ``calls`` steps per call, end with the same bits; returns the single one."""
    engines = {kind: problem.engine(*state, kind=kind) for kind in ("single", "batch", "auto")}
    for engine in engines.values():
        for steps in calls:
            engine.advance(steps)
    for kind in ("batch", "auto"):
        for name in ("q", "p", "dq", "dp", "log_growth", "bad"):
            np.testing.assert_array_equal(getattr(engines[kind], name), getattr(engines["single"], name),
                                          err_msg=f"{kind} {name}")
    return engines["single"]


@pytest.mark.parametrize("boundary, site", [(("fixed", "fixed"), (31, 31)), (("free", "fixed"), (2, 31))],
                         ids=["centre", "at a free edge"])
def test_the_growing_window_follows_a_packet_on_the_square_kg_lattice(boundary, site):
    """A rectangle of sites that widens on each side the packet nears, its bonds across the edge
    walls with their own parameters (none where the lattice's edge is free): the orbit and the
    mLCE vector of the whole lattice, to within what the cut leaves, while the window stays smaller
    than the lattice; in SIMD blocks and lane by lane alike."""
    from chainchaos.run.window import Window, WindowedEngine, restricted_deviation

    lattices = [kg_lattice(seed, 10.0, (61, 61), boundary) for seed in range(3)]
    states = [Excitation(kind="block", site=site, width=3).state("kg", lattice, 0.4)[:2] for lattice in lattices]
    q, p = (np.stack([s[k] for s in states], axis=1) for k in (0, 1))
    rng = np.random.default_rng(0)
    dq, dp = rng.normal(size=q.shape), rng.normal(size=q.shape)
    problem = Problem("kg", lattices, integrator="ABA864", dt=0.1, check_every=50)
    runs = {kind: WindowedEngine(problem, Window(threshold=1e-10, margin=4, every=20), q, p, dq, dp, kind)
            for kind in ("batch", "single")}
    for run in runs.values():
        run.advance(1500)
    start = restricted_deviation(dq, dp, *Window.excited(q, p, lattices[0].geometry), geometry=lattices[0].geometry)
    whole = problem.engine(q.copy(), p.copy(), *start)
    whole.advance(1500)
    windowed = runs["batch"]
    for name in ("q", "p", "log_growth"):
        np.testing.assert_array_equal(getattr(windowed, name), getattr(runs["single"], name), err_msg=name)
    _, lo_x, hi_x, lo_y, hi_y = windowed.spans[-1]
    assert len(windowed.spans) > 1 and hi_x < 61 and 0 < lo_y and hi_y < 61 and (lo_x > 0) == (site[0] > 2)
    assert np.abs(windowed.q - whole.q).max() < 1e-6 and np.abs(windowed.p - whole.p).max() < 1e-6
    assert np.abs(windowed.log_growth - whole.log_growth).max() < 1e-6


@pytest.mark.parametrize("boundary", [("fixed", "fixed"), ("fixed", "free"), ("free", "fixed"), ("free", "free")])
def test_every_window_bond_is_the_lattice_s_bond_between_the_same_sites(boundary):
    """Geometry.window_bonds against the lattice's own list of bonds: each bond of a window (walls
    on every side) is the lattice's bond along the same axis between the same two sites (a wall
    stands for the site across the window's edge, or for the lattice's own wall), -1 where the
    lattice has none; every rectangle of a 7 x 5 lattice."""
    geometry = Geometry((7, 5), boundary)
    nx, ny = geometry.shape2
    ends = geometry.bonds()
    first_axis = ny * (nx + 1 if geometry.fixed[0] else nx - 1)
    lookup = {(k >= first_axis, int(a), int(b)): k for k, (a, b) in enumerate(ends)}
    for lo_x, hi_x, lo_y, hi_y in itertools.product(range(7), range(1, 8), range(5), range(1, 6)):
        if hi_x <= lo_x or hi_y <= lo_y or (hi_x - lo_x) * (hi_y - lo_y) < 2:
            continue
        wx = hi_x - lo_x
        window = Geometry((wx, hi_y - lo_y))
        window_first_axis = (hi_y - lo_y) * (wx + 1)

        def full(site, step, other):
            if site >= 0:
                return (lo_y + site // wx) * nx + lo_x + site % wx
            i, j = lo_x + other % wx + step[0], lo_y + other // wx + step[1]
            return j * nx + i if 0 <= i < nx and 0 <= j < ny else -1

        expected = []
        for k, (a, b) in enumerate(window.bonds()):
            step = (1, 0) if k < window_first_axis else (0, 1)
            pair = (full(a, (-step[0], -step[1]), b), full(b, step, a))
            expected.append(lookup.get((k >= window_first_axis, *pair), -1))
        np.testing.assert_array_equal(geometry.window_bonds((lo_x, hi_x, lo_y, hi_y)), expected)
