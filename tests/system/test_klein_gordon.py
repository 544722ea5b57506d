"""The disordered Klein-Gordon lattice and site laws (models.klein_gordon, models.base.SiteLaw)
against exact results, not the code's own output: the linear chain's frequencies against the
eigenvalues of its tridiagonal matrix written here from the formula, the order of every scheme
and energy conservation on KG, the tangent map against finite differences of the flow (KG, and a
Hertz chain with a site law added), the linear limit of an ordered KG chain (every mode keeps its
energy), and both engines bit for bit.

Units: the KG Hamiltonian's own (docs/conventions.md#klein-gordon).
"""

import numpy as np
import pytest
from numba.core.errors import TypingError
from engine.test_dynamics import integrate as engine_run

from chainchaos.engine.batch import Batch
from chainchaos.engine.integrators import SCHEMES, advance, get_scheme
from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError
from chainchaos.system.chain import KGLattice, kg_chain, random_chain
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.linear import normal_modes
from chainchaos.system.models import (
    MODELS,
    energy_density,
    energy_kernel,
    get_model,
    hertz,
    klein_gordon,
    total_energy,
)
from chainchaos.system.models.base import Model

KG, LINEAR = get_model("kg"), get_model("kg_linear")
W, N = 4.0, 16
LATTICE = kg_chain(7, W, N)

# A Hertz chain with the KG site law added: site parameters eps_n from the bead chain's own size.
HERTZ_SITE = Model(
    name="hertz_with_kg_site", label="Hertz + KG site", colour="#000000", parameter_names=("A", "delta"),
    parameters=hertz.parameters, force=hertz.force, force_stiffness=hertz.force_stiffness,
    potential=hertz.potential, opening=hertz.opening,
    site=klein_gordon.SiteLaw(parameter_names=("eps",), parameters=lambda chain: (np.linspace(0.5, 1.5, chain.N),),
                              force=klein_gordon.quartic_force, force_stiffness=klein_gordon.quartic_force_stiffness,
                              potential=klein_gordon.quartic_potential))


def tridiagonal(lattice: KGLattice) -> np.ndarray:
    """The linear KG chain's matrix from the formula: diagonal eps_l + 2/W, off-diagonal -1/W."""
    n, w = lattice.N, lattice.W
    return np.diag(lattice.eps + 2.0 / w) - np.diag(np.full(n - 1, 1.0 / w), 1) - np.diag(np.full(n - 1, 1.0 / w), -1)


def integrate(model, chain, q, p, n_steps, dt, scheme="SRKN6b", dq=None, dp=None):
    """The single engine on copies of the state (test_dynamics.integrate): (q, p, dq, dp, log growth)."""
    return engine_run(chain, model, q, p, n_steps, dt, scheme, dq, dp)[:5]


# ---- the lattice and its site law ---------------------------------------------------------------


def test_the_kg_lattice_is_its_hamiltonian():
    lattice = kg_chain(3, 2.5, 30)
    np.testing.assert_array_equal(lattice.eps, np.random.default_rng(3).uniform(0.5, 1.5, 30))
    assert lattice.N == 30 and (lattice.mass == 1.0).all() and (lattice.K2 == 1.0 / 2.5).all()
    assert lattice.K2.shape == (31,) and 0.5 <= lattice.eps.min() and lattice.eps.max() <= 1.5
    assert "kg" in MODELS and "kg_linear" in MODELS and KG.has_site_law and not get_model("hertz").has_site_law
    np.testing.assert_array_equal(KG.bond_parameters(lattice)[0], lattice.K2)
    S = KG.site_parameters(lattice)
    assert S.shape == (1, 30) and (S[0] == lattice.eps).all()
    # H written out from its definition, fixed ends
    rng = np.random.default_rng(5)
    u, p = 0.3 * rng.standard_normal(30), 0.3 * rng.standard_normal(30)
    y = np.diff(np.concatenate([[0.0], u, [0.0]]))
    H = np.sum(p**2 / 2 + lattice.eps * u**2 / 2 + u**4 / 4) + np.sum(y**2) / (2 * 2.5)
    assert total_energy(KG, lattice, u, p) == pytest.approx(H, rel=1e-14)
    assert total_energy(LINEAR, lattice, u, p) == pytest.approx(H - np.sum(u**4) / 4, rel=1e-14)
    H_kernel = energy_kernel(KG, u, p, lattice.mass, KG.bond_parameters(lattice), np.empty(31), S)
    assert H_kernel == pytest.approx(H, rel=1e-14)


def test_the_energy_density_gives_each_site_its_own_on_site_energy():
    u, p = np.zeros(N), np.zeros(N)
    u[5], p[9] = 0.4, 0.2
    h = energy_density(KG, LATTICE, u, p)
    eps = LATTICE.eps
    bond = 0.4**2 / (2 * W)  # each of the two bonds of site 6
    H = np.zeros(N)
    H[5] = eps[5] * 0.4**2 / 2 + 0.4**4 / 4 + bond  # its on-site energy and half of each bond
    H[4] = H[6] = bond / 2
    H[9] = 0.2**2 / 2
    np.testing.assert_allclose(h, H / H.sum(), rtol=1e-14, atol=1e-17)


@pytest.mark.parametrize("model", [KG, LINEAR])
def test_the_site_force_is_the_derivative_of_the_potential_and_the_stiffness_that_of_the_force(model):
    law = model.site
    eps = LATTICE.eps
    u = np.random.default_rng(0).uniform(-1.5, 1.5, N)
    S = (eps, np.zeros(N))
    f, k = law.force_stiffness(S, u)
    quartic = 1.0 if model is KG else 0.0
    np.testing.assert_allclose(f, eps * u + quartic * u**3, rtol=1e-15)
    np.testing.assert_allclose(k, eps + 3 * quartic * u**2, rtol=1e-15)
    np.testing.assert_array_equal(law.force(S, u), f)
    h = 1e-5
    np.testing.assert_allclose((law.potential(S, u + h) - law.potential(S, u - h)) / (2 * h), f, rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose((law.force(S, u + h) - law.force(S, u - h)) / (2 * h), k, rtol=1e-8)
    assert (law.potential(S, np.zeros(N)) == 0).all()


def test_a_single_site_excitation_solves_its_energy_equation():
    """u0 on one site with everything else at rest: eps u^2/2 + u^4/4 + u^2/W = E (the two
    bonds' energy counted in full)."""
    site, E = N // 2, 0.4
    q, p, u0 = initial_state(KG, LATTICE, E, site)
    eps = LATTICE.eps[site - 1]
    assert eps * u0**2 / 2 + u0**4 / 4 + u0**2 / W == pytest.approx(E, rel=1e-14)
    assert q[site - 1] == u0 and np.count_nonzero(q) == 1 and not p.any()


def test_a_model_needs_its_lattice_and_a_site_law_its_parameters():
    with pytest.raises(ParameterError, match="chains"):
        Problem("kg", [random_chain(1, 5.0, N)])
    with pytest.raises(ParameterError, match="chains"):
        Problem("hertz", [LATTICE])
    with pytest.raises(TypingError, match="site law"):
        energy_kernel(KG, np.zeros(N), np.zeros(N), LATTICE.mass, KG.bond_parameters(LATTICE), np.empty(N + 1))


# ---- the linear chain ---------------------------------------------------------------------------


def test_the_linear_frequencies_are_the_eigenvalues_of_the_tridiagonal_matrix():
    for seed, w in ((7, 4.0), (8, 1.0), (9, 10.0)):
        lattice = kg_chain(seed, w, 40)
        omega2 = np.linalg.eigvalsh(tridiagonal(lattice))
        omega, U = normal_modes(lattice)
        np.testing.assert_allclose(omega**2, omega2, rtol=1e-12)
        assert 0.5 <= omega2.min() and omega2.max() <= 1.5 + 4.0 / w  # the band of the note
        np.testing.assert_allclose(U.T @ U, np.eye(40), atol=1e-12)  # masses 1


@pytest.mark.parametrize("k", [0, N // 2, N - 1])
def test_the_linear_chain_oscillates_in_a_mode_at_its_eigenfrequency(k):
    """Integrate kg_linear from eigenvector k of the matrix (numpy's); the frequency read from the
    zero crossings of the mode's amplitude over ~50 periods is sqrt of its eigenvalue, and nothing
    leaks into the other modes."""
    omega2, V = np.linalg.eigh(tridiagonal(LATTICE))
    omega = np.sqrt(omega2[k])
    q, p = 0.1 * V[:, k], np.zeros(N)
    dt, per_sample = 0.01, 5
    samples = int(50 * 2 * np.pi / omega / (dt * per_sample))
    Q = np.empty(samples + 1)
    Q[0] = V[:, k] @ q
    for i in range(samples):
        q, p, *_ = integrate(LINEAR, LATTICE, q, p, per_sample, dt)
        Q[i + 1] = V[:, k] @ q
    t = np.arange(samples + 1) * dt * per_sample
    i = np.flatnonzero(np.sign(Q[:-1]) != np.sign(Q[1:]))
    crossings = t[i] - Q[i] * (t[i + 1] - t[i]) / (Q[i + 1] - Q[i])
    half_period = np.polyfit(np.arange(crossings.size), crossings, 1)[0]
    assert np.pi / half_period == pytest.approx(omega, rel=1e-6)
    others = np.delete(V.T @ q, k)
    assert np.abs(others).max() < 1e-12


# ---- dynamics of the nonlinear lattice ------------------------------------------------------------


def test_the_measured_order_of_every_scheme_on_kg():
    q0, p0, _ = initial_state(KG, LATTICE, 0.4, N // 2)
    T = 10.0
    ref = np.concatenate(integrate(KG, LATTICE, q0, p0, 5000, T / 5000, "SRKN11b")[:2])
    for name, scheme in SCHEMES.items():
        dts = [0.1, 0.05] if scheme.order >= 4 else [0.01, 0.005]
        errors = [np.abs(np.concatenate(integrate(KG, LATTICE, q0, p0, round(T / dt), dt, name)[:2]) - ref).max()
                  for dt in dts]
        order = np.log2(errors[0] / errors[1])
        assert abs(order - scheme.order) < 0.3, (name, errors, order)


@pytest.mark.parametrize("integrator", sorted(SCHEMES))
def test_the_energy_is_conserved_to_the_order_of_every_scheme(integrator):
    """The relative energy error over t = 200 (E = 1.5, the self-trapping energy) falls as
    dt^order and stays small."""
    scheme = get_scheme(integrator)
    q0, p0, _ = initial_state(KG, LATTICE, 1.5, N // 2)
    H0 = total_energy(KG, LATTICE, q0, p0)
    dts = [0.1, 0.05] if scheme.order >= 4 else [0.02, 0.01]
    worst = []
    for dt in dts:
        q, p, err = q0, p0, 0.0
        for _ in range(40):
            q, p, *_ = integrate(KG, LATTICE, q, p, round(5.0 / dt), dt, integrator)
            err = max(err, abs(total_energy(KG, LATTICE, q, p) / H0 - 1))
        worst.append(err)
    assert worst[1] < 1e-4
    assert worst[0] / worst[1] > 2**scheme.order * 0.6, worst


@pytest.mark.parametrize("model, chain, energy, site", [(KG, LATTICE, 0.4, N // 2), (KG, LATTICE, 1.5, N // 2),
                                                        (HERTZ_SITE, random_chain(879, 5.0), 0.25, 21)])
def test_the_tangent_map_matches_finite_differences_of_the_flow(model, chain, energy, site):
    n = chain.N
    q0, p0, _ = initial_state(model, chain, energy, site)
    v = np.random.default_rng(3).normal(size=2 * n)
    v /= np.linalg.norm(v)
    steps, dt = 500, 0.01
    _, _, dq, dp, log_growth = integrate(model, chain, q0, p0, steps, dt, dq=v[:n], dp=v[n:])
    tangent = np.concatenate([dq, dp]) * np.exp(log_growth)
    h = 1e-6
    plus = integrate(model, chain, q0 + h * v[:n], p0 + h * v[n:], steps, dt)
    minus = integrate(model, chain, q0 - h * v[:n], p0 - h * v[n:], steps, dt)
    difference = np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * h)
    assert np.abs(difference - tangent).max() < 1e-6 * np.abs(tangent).max()
    # without its site law the same chain has another tangent flow: the check is not vacuous
    if model is HERTZ_SITE:
        bare = integrate("hertz", chain, q0, p0, steps, dt, dq=v[:n], dp=v[n:])
        assert np.abs(np.concatenate(bare[2:4]) * np.exp(bare[4]) - tangent).max() > 1e-3 * np.abs(tangent).max()


def test_an_ordered_kg_chain_at_tiny_energy_keeps_every_mode_energy():
    """eps_l = 1 on every site: the modes are sin(pi k n / (N+1)) with omega_k^2 =
    1 + (4/W) sin^2(pi k / (2(N+1))); at E = 1e-8 (u ~ 1e-4) the quartic term is 1e-8 of the
    quadratic one and every mode's harmonic energy stays what it was over t = 500, to 1e-6 of E."""
    ordered = KGLattice(np.ones(N), W)
    n, k = np.arange(1, N + 1), np.arange(1, N + 1)
    modes = np.sqrt(2.0 / (N + 1)) * np.sin(np.pi * np.outer(n, k) / (N + 1))  # orthonormal columns
    omega2 = 1.0 + (4.0 / W) * np.sin(np.pi * k / (2 * (N + 1))) ** 2

    def modal(q, p):
        Q, P = modes.T @ q, modes.T @ p
        return (P**2 + omega2 * Q**2) / 2

    q0, p0, _ = initial_state(KG, ordered, 1e-8, 5)  # one site: every mode excited
    E0 = modal(q0, p0)
    assert (E0 > 1e-3 * E0.max()).sum() >= N // 2
    q, p, *_ = integrate(KG, ordered, q0, p0, 25000, 0.02)
    assert np.abs(modal(q, p) - E0).max() < 1e-6 * E0.sum()
    # at E = 1 the same chain exchanges energy between its modes: the check is not vacuous
    q0, p0, _ = initial_state(KG, ordered, 1.0, 5)
    q, p, *_ = integrate(KG, ordered, q0, p0, 25000, 0.02)
    E1 = modal(q0, p0)
    assert np.abs(modal(q, p) - E1).max() > 1e-2 * E1.sum()


# ---- both engines ---------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["kg", "kg_linear"])
@pytest.mark.parametrize("integrator", ["SRKN6b", "ABA864", "verlet"])
def test_both_engines_agree_bit_for_bit_on_kg(name, integrator):
    """Five lattices, energies and sites, tangent map on, two calls: every lane of the batch
    engine equals the single engine (and the kind 'single' and 'auto' of Problem.engine)."""
    lattices = [kg_chain(s, W, N) for s in (1, 2, 3, 4, 5)]
    energies, sites = [0.05, 0.4, 1.5, 4.0, 0.4], [8, 8, 5, 12, 8]
    states = [initial_state(name, c, E, s)[:2] for c, E, s in zip(lattices, energies, sites)]
    q, p = np.stack([s[0] for s in states], 1), np.stack([s[1] for s in states], 1)
    dq, dp = initial_deviation(N, 3)
    dq, dp = np.tile(dq[:, None], (1, 5)), np.tile(dp[:, None], (1, 5))
    problem = Problem(name, lattices, integrator=integrator, dt=0.05, check_every=37)
    runs = {}
    for kind in ("batch", "single", "auto"):
        b = problem.engine(q, p, dq, dp, kind)
        b.advance(600)
        b.advance(400)
        runs[kind] = b
    for j in range(5):
        sq, sp, sdq, sdp, log_growth = q[:, j], p[:, j], dq[:, j], dp[:, j], 0.0
        for steps in (600, 400):
            s = get_scheme(integrator)
            sq, sp, sdq, sdp = sq.copy(), sp.copy(), sdq.copy(), sdp.copy()
            diagnostics = np.array([log_growth, 0.0])
            assert advance(get_model(name), sq, sp, sdq, sdp, *problem.lane(j), s.kicks, s.drifts, 0.05, steps,
                           True, 37, False, np.zeros(N + 1, dtype=np.int64), diagnostics, np.empty(N + 1),
                           np.empty(N + 1), problem.lane_sites(j)) == -1
            log_growth = diagnostics[0]
        for b in runs.values():
            for got, want in ((b.q, sq), (b.p, sp), (b.dq, sdq), (b.dp, sdp)):
                np.testing.assert_array_equal(got[:, j].view(np.int64), want.view(np.int64))
            assert b.log_growth[j] == log_growth and b.bad[j] == -1
    H0 = problem.energies(q.T, p.T)  # and the orbits are the KG lattice's (dt = 0.05: verlet to 1e-2)
    tolerance = 1e-2 if get_scheme(integrator).order == 2 else 1e-4
    assert np.abs(problem.energies(runs["batch"].q.T, runs["batch"].p.T) / H0 - 1).max() < tolerance


def test_an_extra_deviation_vector_equal_to_the_first_stays_equal_on_kg():
    """The batch engine's extra vectors (GALI's) take the site law's w''(u) as the block's own
    vector does: started equal to it they stay equal, to the bit."""
    lattices = [kg_chain(s, W, N) for s in (1, 2, 3)]
    states = [initial_state(KG, c, 1.5, 8)[:2] for c in lattices]
    q, p = np.stack([s[0] for s in states], 1), np.stack([s[1] for s in states], 1)
    dq, dp = initial_deviation(N, 3)
    dq, dp = np.tile(dq[:, None], (1, 3)), np.tile(dp[:, None], (1, 3))
    problem = Problem(KG, lattices, dt=0.05, check_every=50, gali=2)
    b = Batch(problem, q, p, dq, dp, xq=dq[None], xp=dp[None])
    b.advance(500)
    b.advance(300)
    np.testing.assert_array_equal(b.xq[0], b.dq)
    np.testing.assert_array_equal(b.xp[0], b.dp)
    np.testing.assert_array_equal(b.x_growth[0], b.log_growth)


def test_simulate_runs_the_kg_lattice_and_records_its_disorder_strength():
    """The README's KG scene through chainchaos.simulate (it failed on the bead chain's alpha):
    the scene file records W, P stays between one site and the lattice, and the energy is kept
    to the scheme's error."""
    from chainchaos import SceneParameters, kg_chain, simulate

    ds = simulate(kg_chain(seed=1, W=4.0, N=64), SceneParameters(model="kg", energy=0.4, excited_site=32,
                                                                  t_final=10.0, dt=0.1,
                                                                  observables=("participation",)))
    assert ds.attrs["W"] == 4.0 and "alpha" not in ds.attrs and ds.attrs["model"] == "kg"
    P = ds["participation"].values
    assert np.all((P >= 1.0) & (P <= 64.0))
    assert ds.attrs["max_energy_error"] < 1e-6


@pytest.mark.parametrize("model", ["kg", "kg_linear"])
def test_the_right_hand_side_is_hamilton_s_equations(model):
    """``engine.rhs`` (scipy's integrators and the kernels' warm-up run it) of a model with a site
    law: u' = p / m and p' = -dH/du, against central differences of the Hamiltonian."""
    from chainchaos.engine.rhs import rhs

    lattice = kg_chain(2, 4.0, 12)
    rng = np.random.default_rng(6)
    u, p = 0.3 * rng.normal(size=12), 0.3 * rng.normal(size=12)
    out = rhs(model, lattice)(0.0, np.concatenate([u, p]))
    np.testing.assert_array_equal(out[:12], p / lattice.mass)
    h = 1e-5
    gradient = [(total_energy(model, lattice, u + h * e, p) - total_energy(model, lattice, u - h * e, p)) / (2 * h)
                for e in np.eye(12)]
    np.testing.assert_allclose(out[12:], -np.array(gradient), rtol=0, atol=1e-8)
