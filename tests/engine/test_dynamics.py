"""Integrators and dynamics against exact results: order, energy, tangent map, limits."""

import numpy as np
import pytest

from chainchaos.engine.integrators import SCHEMES, advance, get_scheme
from chainchaos.run.driver import sample_steps
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.system.initial import initial_state
from chainchaos.system.models import get_model, open_bonds, total_energy

HERTZ, FPUT, TODA = get_model("hertz"), get_model("fput"), get_model("toda")


def integrate(chain, model, q, p, n_steps, dt, scheme="SRKN6b", dq=None, dp=None, track_gaps=False):
    """Run the engine on copies of the state; returns (q, p, dq, dp, log growth, gap steps, max gaps)."""
    N = chain.N
    q, p = q.copy(), p.copy()
    tangent = dq is not None
    dq = np.zeros(N) if dq is None else dq.copy()
    dp = np.zeros(N) if dp is None else dp.copy()
    s = get_scheme(scheme)
    diagnostics, gaps = np.zeros(2), np.zeros(N + 1, dtype=np.int64)
    model = get_model(model)
    bad = advance(model, q, p, dq, dp, 1 / chain.mass, model.bond_parameters(chain), s.kicks, s.drifts,
                  dt, n_steps, tangent, 10**9, track_gaps, gaps, diagnostics, np.empty(N + 1),
                  np.empty(N + 1), model.site_parameters(chain))
    assert bad == -1
    return q, p, dq, dp, diagnostics[0], gaps, diagnostics[1]


@pytest.mark.parametrize("model, energy", [(FPUT, 0.25), (HERTZ, 0.05), (TODA, 0.25)])
def test_measured_order_of_every_scheme(chain, model, energy):
    q0, p0, _ = initial_state(model, chain, energy, 21)
    T = 10.0
    ref = np.concatenate(integrate(chain, model, q0, p0, 5000, T / 5000, "SRKN11b")[:2])
    if model == HERTZ:
        *_, max_gaps = integrate(chain, model, q0, p0, 1000, T / 1000, "verlet", track_gaps=True)
        assert max_gaps == 0  # smooth case: no contact opens
    for name, scheme in SCHEMES.items():
        dts = [0.1, 0.05] if scheme.order >= 4 else [0.01, 0.005]
        errors = [np.abs(np.concatenate(integrate(chain, model, q0, p0, round(T / dt), dt, name)[:2]) - ref).max()
                  for dt in dts]
        order = np.log2(errors[0] / errors[1])
        assert abs(order - scheme.order) < 0.3, (name, errors, order)


@pytest.mark.parametrize("model, energy", [(FPUT, 1.0), (HERTZ, 0.25), (HERTZ, 1.8), (TODA, 1.0)])
def test_tangent_map_matches_finite_differences(chain, model, energy):
    N = chain.N
    q0, p0, _ = initial_state(model, chain, energy, 21)
    v = np.random.default_rng(3).normal(size=2 * N)
    v /= np.linalg.norm(v)
    n, dt = 500, 0.01
    _, _, dq, dp, log_growth, *_ = integrate(chain, model, q0, p0, n, dt, dq=v[:N], dp=v[N:])
    tangent = np.concatenate([dq, dp]) * np.exp(log_growth)
    eps = 1e-6
    plus = integrate(chain, model, q0 + eps * v[:N], p0 + eps * v[N:], n, dt)
    minus = integrate(chain, model, q0 - eps * v[:N], p0 - eps * v[N:], n, dt)
    difference = np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * eps)
    assert np.abs(difference - tangent).max() < 1e-6 * np.abs(tangent).max()


@pytest.mark.parametrize("model", ["hertz", "fput", "toda"])
def test_energy_is_conserved_to_scheme_accuracy(chain, model):
    errors = []
    for dt in (0.02, 0.01):
        ds = simulate(chain, SceneParameters(model=model, energy=0.5, t_final=1000.0, dt=dt, observables=("participation",)))
        errors.append(ds.attrs["max_energy_error"])
    assert errors[1] < 1e-6
    assert errors[0] / errors[1] > 2**4 * 0.7  # fourth order in the energy error too


def test_mlce_times_t_is_bounded_for_the_harmonic_chain(chain):
    """For a linear chain the tangent flow is the (quasi-periodic) flow itself: ln|v(t)| is bounded
    by half the log of the condition number of the energy norm against the Euclidean norm."""
    ds = simulate(chain, SceneParameters(model="harmonic", energy=0.25, t_final=3000.0, dt=0.02, observables=("mlce",)))
    K2 = chain.K2
    K = np.diag(K2[:-1] + K2[1:]) - np.diag(K2[1:-1], 1) - np.diag(K2[1:-1], -1)
    ev = np.linalg.eigvalsh(K)
    bound = 0.5 * np.log(max(ev.max(), 1 / chain.mass.min()) / min(ev.min(), 1 / chain.mass.max()))
    growth = (ds.mlce * ds.time).values[1:]
    assert np.all(growth <= bound + 1e-3)
    assert ds.mlce.values[-1] < bound / 3000.0 + 1e-6


def test_hertz_and_fput_agree_at_small_energy(chain):
    """At H = 1e-6 (strains ~1e-3 delta) the FPUT chain with the Taylor sign of K4 is the Hertz chain
    up to fifth-order terms, over t = 100; with the paper's sign the quartic term differs."""
    common = dict(t_final=100.0, dt=0.01, observables=("energy_density",), samples_per_decade=5)
    h = simulate(chain, SceneParameters(model="hertz", energy=1e-6, **common)).energy_density
    taylor = simulate(chain, SceneParameters(model="fput", energy=1e-6, k4_sign=-1, **common)).energy_density
    paper = simulate(chain, SceneParameters(model="fput", energy=1e-6, **common)).energy_density
    assert float(np.abs(h - taylor).max()) < 1e-9
    assert float(np.abs(h - paper).max()) < 1e-4


def test_eta_starts_at_one(chain):
    ds = simulate(chain, SceneParameters(model="hertz", energy=0.25, t_final=10.0, dt=0.01, observables=("eta",)))
    assert ds.eta.values[0] == 1.0
    assert 0 < ds.eta.attrs["equipartition_value"] < 1


def test_initial_state_has_requested_energy(chain):
    for model in (HERTZ, FPUT):
        q, p, u0 = initial_state(model, chain, 0.25, 21)
        assert total_energy(model, chain, q, p) == pytest.approx(0.25, rel=1e-12)
        assert u0 > 0 and np.count_nonzero(q) == 1 and q[20] == u0


def test_gap_detection_on_constructed_state(chain):
    u = np.zeros(chain.N)
    u[20] = chain.delta[20] + 0.01  # bead 21 moves right past the static overlap of bond 21
    gaps = open_bonds(HERTZ, chain, u)
    assert np.flatnonzero(gaps).tolist() == [20]  # bond 21 (joins beads 20 and 21) is open
    u[20] = chain.delta[20] - 0.01
    assert not open_bonds(HERTZ, chain, u).any()
    u[:] = 0.0
    u[0] = chain.delta[0] + 0.01  # bead 1 moves away from the left wall
    assert np.flatnonzero(open_bonds(HERTZ, chain, u)).tolist() == [0]
    assert not open_bonds(FPUT, chain, u).any()  # polynomial bonds never open


def test_gap_bookkeeping_counts_open_steps(chain):
    # a large kick on bead 21 opens bond 21 at once
    q0, p0, u0 = initial_state(HERTZ, chain, 1.8, 21)
    assert u0 > chain.delta[20]
    *_, gap_steps, max_gaps = integrate(chain, HERTZ, q0, p0, 1, 1e-4, track_gaps=True)
    assert gap_steps[20] == 1 and max_gaps >= 1


def test_sample_times_include_powers_of_ten_on_the_step_grid():
    steps = sample_steps(1e5, 5e-4, 40, 0.1)
    t = steps * 5e-4
    assert steps[0] == 0 and t[-1] == 1e5
    for power in range(-1, 6):
        assert 10.0**power in t
    assert np.all(np.diff(steps) > 0)
