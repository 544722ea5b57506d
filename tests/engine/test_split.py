"""The split engines (engine.split) of the DNLS chain against exact results: the linear chain's
eigenvectors, the norm of each part's flow, the order of every scheme, the tangent map against
finite differences of the flow, the dimer against an independent integrator, standing waves of
the ordered chain; and the batch engine equal to the single one, lane by lane, to the bit."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from chainchaos.engine.problem import Problem
from chainchaos.engine.split import _hop, _rotate, advance_split
from chainchaos.engine.split_schemes import SPLIT_SCHEMES
from chainchaos.system.chain import DNLSLattice, dnls_chain
from chainchaos.system.models import MODELS
from chainchaos.system.models.split import norm, split_energy

DNLS = MODELS["dnls"]


def run(lattice, q, p, scheme, dt, steps, model=DNLS, dq=None, dp=None):
    """(q, p, dq, dp, ln growth) after ``steps`` steps on the single engine."""
    q, p = np.array(q, dtype=float), np.array(p, dtype=float)
    tangent = dq is not None
    dq = np.zeros_like(q) if dq is None else np.array(dq, dtype=float)
    dp = np.zeros_like(p) if dp is None else np.array(dp, dtype=float)
    s = SPLIT_SCHEMES[scheme]
    diagnostics = np.zeros(2)
    assert advance_split(model, q, p, dq, dp, model.site_parameters(lattice), lattice.geometry.shape2, s.parts,
                         s.coefficients, dt, steps, tangent, 10**9, diagnostics) == -1
    return q, p, dq, dp, diagnostics[0]


def packet(N, seed, amplitude=1.0):
    rng = np.random.default_rng(seed)
    return amplitude * rng.normal(size=N), amplitude * rng.normal(size=N)


@pytest.mark.parametrize("scheme", ["ABC2", "s9ABC6"])
def test_linear_eigenvector_rotates_at_its_eigenvalue(scheme):
    """beta = 0: psi = v exp(-i lambda t) for an eigenvector v of tridiag(eps, -1); its norm
    density v^2 stays."""
    lattice = dnls_chain(3, 4.0, 24, beta=0.0)
    lam, V = np.linalg.eigh(np.diag(lattice.eps) - np.eye(24, k=1) - np.eye(24, k=-1))
    v, t, dt = V[:, 10], 20.0, 0.01
    q, p, *_ = run(lattice, np.sqrt(2) * v, np.zeros(24), scheme, dt, int(t / dt))
    exact_q, exact_p = np.sqrt(2) * v * np.cos(lam[10] * t), -np.sqrt(2) * v * np.sin(lam[10] * t)
    error = np.abs(q - exact_q).max() + np.abs(p - exact_p).max()
    assert error < {"ABC2": 1e-3, "s9ABC6": 1e-9}[scheme]
    assert np.abs((q**2 + p**2) / 2 - v**2).max() < {"ABC2": 1e-3, "s9ABC6": 1e-9}[scheme]


def test_the_rotation_keeps_every_site_s_norm_and_the_hopping_parts_do_not():
    lattice = dnls_chain(1, 4.0, 16, beta=2.0)
    q, p = packet(16, 1)
    x0 = q**2 + p**2
    dq = dp = np.zeros(16)
    _rotate(DNLS, False, q, p, dq, dp, DNLS.site_parameters(lattice), 0.7)
    np.testing.assert_allclose(q**2 + p**2, x0, rtol=4e-16, atol=0)
    S0 = norm(q, p)
    _hop(p, q, 0.3, (16, 1))  # B alone
    assert abs(norm(q, p) - S0) > 1e-3
    q2, p2 = packet(16, 1)
    _hop(q2, p2, -0.3, (16, 1))  # C alone
    assert abs(norm(q2, p2) - norm(*packet(16, 1))) > 1e-3


def observed_order(scheme, quantity, lattice=None):
    """log2 of the ratio of the largest errors of H or S over t <= 10 at steps dt and dt/2, on
    ``lattice`` (default a DNLS chain of 12 sites)."""
    lattice = dnls_chain(5, 4.0, 12, beta=1.0) if lattice is None else lattice
    q0, p0 = packet(lattice.N, 5, 0.6)
    reference = {"energy": lambda q, p: split_energy(DNLS, lattice, q, p), "norm": norm}[quantity]
    dt0 = {2: 0.02, 4: 0.05, 6: 0.1, 8: 0.1}[SPLIT_SCHEMES[scheme].order]
    errors = []
    for dt in (dt0, dt0 / 2):
        q, p, worst = q0, p0, 0.0
        chunk = int(round(0.5 / dt))
        for _ in range(20):
            q, p, *_ = run(lattice, q, p, scheme, dt, chunk)
            worst = max(worst, abs(reference(q, p) - reference(q0, p0)))
        errors.append(worst)
    return np.log2(errors[0] / errors[1])


@pytest.mark.parametrize("scheme", sorted(SPLIT_SCHEMES))
@pytest.mark.parametrize("quantity", ["energy", "norm"])
def test_every_scheme_has_its_order_on_energy_and_norm(scheme, quantity):
    order = SPLIT_SCHEMES[scheme].order
    assert abs(observed_order(scheme, quantity) - order) < 0.5


def test_tangent_map_is_the_derivative_of_the_flow():
    """The deviation after a few steps against central differences of the flow (h = 1e-6)."""
    lattice = dnls_chain(2, 4.0, 10, beta=3.0)
    q0, p0 = packet(10, 2, 0.8)
    vq, vp = packet(10, 9)
    scale = np.sqrt(np.sum(vq**2 + vp**2))
    vq, vp = vq / scale, vp / scale
    q, p, dq, dp, growth = run(lattice, q0, p0, "s9ABC6", 0.05, 40, dq=vq, dp=vp)
    h = 1e-6
    plus = run(lattice, q0 + h * vq, p0 + h * vp, "s9ABC6", 0.05, 40)
    minus = run(lattice, q0 - h * vq, p0 - h * vp, "s9ABC6", 0.05, 40)
    fd = np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * h)
    tangent = np.concatenate([dq, dp]) * np.exp(growth)
    assert np.abs(tangent - fd).max() < 1e-7 * np.abs(fd).max()


def test_nonlinear_dimer_against_an_independent_integrator():
    """N = 2 (integrable): the orbit at t = 20 against DOP853 at rtol 1e-13 on the complex DNLS."""
    lattice = DNLSLattice(np.array([0.3, -0.4]), W=1.0, beta=2.5)
    psi0 = np.array([1.0 + 0.2j, 0.1 - 0.3j])

    def rhs(t, y):
        psi = y[:2] + 1j * y[2:]
        d = -1j * ((lattice.eps + lattice.beta * np.abs(psi) ** 2) * psi - psi[::-1])
        return np.concatenate([d.real, d.imag])

    ref = solve_ivp(rhs, (0, 20), np.concatenate([psi0.real, psi0.imag]), method="DOP853", rtol=1e-13, atol=1e-13)
    psi_ref = ref.y[:2, -1] + 1j * ref.y[2:, -1]
    q, p, *_ = run(lattice, np.sqrt(2) * psi0.real, np.sqrt(2) * psi0.imag, "s9ABC6", 0.005, 4000)
    assert np.abs((q + 1j * p) / np.sqrt(2) - psi_ref).max() < 1e-9


def test_ordered_chain_keeps_each_standing_wave_s_norm_at_tiny_amplitude():
    """eps = 0, amplitude 1e-4: the nonlinearity (beta x ~ 1e-8) barely couples the standing
    waves sin(pi k l / (N + 1)), so each keeps its norm."""
    N = 20
    l = np.arange(1, N + 1)
    modes = np.sqrt(2 / (N + 1)) * np.sin(np.pi * np.outer(np.arange(1, N + 1), l) / (N + 1))
    amplitudes = np.zeros(N)
    amplitudes[[2, 7, 12]] = [1e-4, 0.5e-4, 0.8e-4]
    q0 = np.sqrt(2) * amplitudes @ modes
    q, p, *_ = run(DNLSLattice(np.zeros(N), W=1.0, beta=1.0), q0, np.zeros(N), "s9ABC6", 0.05, 2000)
    psi = (q + 1j * p) / np.sqrt(2)
    np.testing.assert_allclose(np.abs(modes @ psi) ** 2, amplitudes**2, rtol=1e-6, atol=1e-20)


@pytest.mark.parametrize("lanes", [1, 7, 19])
def test_batch_engine_gives_each_lane_the_single_engine_s_bits(lanes):
    N = 13
    chains = [dnls_chain(s, 4.0, N, beta=1.5) for s in range(lanes)]
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


def test_extra_vectors_follow_the_tangent_map_of_the_first():
    """An extra deviation vector equal to the mLCE vector stays equal to it, to the bit; GALI's
    vectors stop without changing the orbit."""
    N, B = 9, 5
    chains = [dnls_chain(s, 4.0, N, beta=2.0) for s in range(B)]
    rng = np.random.default_rng(0)
    q, p, dq, dp = (rng.normal(size=(N, B)) for _ in range(4))
    scale = np.sqrt(np.sum(dq**2 + dp**2, axis=0))
    dq, dp = dq / scale, dp / scale
    problem = Problem("dnls", chains, dt=0.05, check_every=10, gali=2)
    engine = problem.engine(q, p, dq, dp, "batch", dq[None].copy(), dp[None].copy())
    alone = problem.engine(q, p, dq, dp, "batch", rng.normal(size=(1, N, B)), rng.normal(size=(1, N, B)))
    alone.stop_vectors(range(B))
    engine.advance(100)
    alone.advance(100)
    np.testing.assert_array_equal(engine.xq[0], engine.dq)
    np.testing.assert_array_equal(engine.xp[0], engine.dp)
    np.testing.assert_array_equal(engine.x_growth[0], engine.log_growth)
    np.testing.assert_array_equal(alone.q, engine.q)
    np.testing.assert_array_equal(alone.log_growth, engine.log_growth)


def test_a_split_model_refuses_a_bond_scheme_and_bond_parameters():
    lattice = dnls_chain(0, 4.0, 8)
    with pytest.raises(Exception, match="integrator"):
        Problem("dnls", [lattice], integrator="SRKN6b")
    problem = Problem("dnls", [lattice])
    assert problem.integrator == "s9ABC6"
    with pytest.raises(Exception, match="bond model"):
        problem.lane_parameters
    with pytest.raises(Exception, match="DNLSLattice"):
        Problem("hertz", [lattice])
