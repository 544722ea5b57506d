"""The batch engine (chainchaos.engine.batch) against the single-trajectory engine, lane by lane."""

import numpy as np
import pytest

from chainchaos import random_chain
from chainchaos.engine.batch import SERIAL_REMAINDER, Batch
from chainchaos.engine.integrators import SCHEMES, advance, get_scheme
from chainchaos.engine.problem import Problem
from chainchaos.kernels.simd import LANES
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import BEAD_MODELS, get_model

N = 40


def single_run(name, chain, q, p, dq, dp, integrator, dt, n_steps, tangent, check_every, gaps, log_growth=0.0):
    model = get_model(name)
    scheme = get_scheme(integrator)
    q, p, dq, dp = q.copy(), p.copy(), dq.copy(), dp.copy()
    diag, gap_steps = np.array([log_growth, 0.0]), np.zeros(N + 1, dtype=np.int64)
    f, k = np.empty(N + 1), np.empty(N + 1)
    bad = advance(model, q, p, dq, dp, 1.0 / chain.mass, model.bond_parameters(chain), scheme.kicks,
                  scheme.drifts, dt, n_steps, tangent, check_every, gaps, gap_steps, diag, f, k)
    return q, p, dq, dp, diag, gap_steps, bad


def lanes(name, chains, energies, sites):
    model = get_model(name)
    states = [initial_state(model, c, E, s)[:2] for c, E, s in zip(chains, energies, sites)]
    q = np.stack([s[0] for s in states], 1)
    p = np.stack([s[1] for s in states], 1)
    dq, dp = initial_deviation(N, 3)
    B = len(chains)
    return q, p, np.tile(dq[:, None], (1, B)), np.tile(dp[:, None], (1, B))


def assert_lanes_match_single_runs(name, chains, batch, q, p, dq, dp, integrator, calls, check_every, gaps):
    """Every lane of ``batch`` (advanced by ``calls`` steps per call) equals, bit for bit, the
    single engine run with the same call pattern (renormalisation at the end of each call)."""
    for j in range(len(chains)):
        sq, sp, sdq, sdp = q[:, j], p[:, j], dq[:, j], dp[:, j]
        log_growth, max_gaps = 0.0, 0
        gsum = np.zeros(N + 1, dtype=np.int64)
        for n in calls:
            sq, sp, sdq, sdp, diag, gap_steps, bad = single_run(name, chains[j], sq, sp, sdq, sdp, integrator,
                                                                0.01, n, True, check_every, gaps, log_growth)
            log_growth = diag[0]  # accumulated in the engine's order
            max_gaps = max(max_gaps, int(diag[1]))
            gsum += gap_steps
            assert bad == -1
        for got, want in ((batch.q, sq), (batch.p, sp), (batch.dq, sdq), (batch.dp, sdp)):
            np.testing.assert_array_equal(got[:, j], want)
        assert batch.log_growth[j] == log_growth
        if gaps:
            assert batch.max_gaps[j] == max_gaps
            np.testing.assert_array_equal(batch.gap_steps[:, j], gsum)


@pytest.mark.parametrize("name", sorted(BEAD_MODELS))  # the KG lattice's: tests/system/test_klein_gordon.py
@pytest.mark.parametrize("integrator", ["SRKN6b", "ABA864", "verlet"])
def test_every_lane_matches_the_single_engine(name, integrator):
    """Different chains, energies and excited beads per lane, with the tangent map and (where bonds
    open) gap counting, for every model of the registry: states, deviation vectors, log growth and gap counts are those of the single
    engine to the last bit (the same IEEE operations in the same order, lane by lane)."""
    chains = [random_chain(s, 5.0) for s in (879, 5346, 11, 12, 13)]
    energies = [0.25, 0.5, 1.8, 4.0, 9.0]
    sites = [21, 21, 15, 30, 20]
    gaps = get_model(name).has_gaps
    q, p, dq, dp = lanes(name, chains, energies, sites)
    batch = Batch(Problem(name, chains, integrator=integrator, dt=0.01, tangent=True, track_gaps=gaps, check_every=37),
                  q, p, dq, dp)
    batch.advance(600)
    batch.advance(400)
    assert_lanes_match_single_runs(name, chains, batch, q, p, dq, dp, integrator, (600, 400), 37, gaps)
    assert (batch.bad == -1).all()
    if gaps:
        assert batch.max_gaps.max() >= 2  # the high energies do open gaps: the check is not vacuous


@pytest.mark.parametrize("kind, block_lanes", [("batch", 2 * LANES + SERIAL_REMAINDER), ("auto", 2 * LANES),
                                               ("single", 0)])
def test_a_batch_of_several_blocks_matches_lane_by_lane(kind, block_lanes):
    """B = 2 * LANES + SERIAL_REMAINDER trajectories: two full blocks and a padded one ("batch"),
    the remainder on the single engine ("auto") or every lane there ("single"); each lane exact."""
    B = 2 * LANES + SERIAL_REMAINDER
    chains = [random_chain(s, 5.0) for s in range(100, 100 + B)]
    energies = np.geomspace(0.2, 10.0, B)
    q, p, dq, dp = lanes("hertz", chains, energies, [21] * B)
    batch = Problem("hertz", chains, dt=0.01, track_gaps=True, check_every=50).engine(q, p, dq, dp, kind)
    assert batch.block_lanes == block_lanes
    batch.advance(300)
    assert_lanes_match_single_runs("hertz", chains, batch, q, p, dq, dp, "SRKN6b", (300,), 50, True)


def test_without_tangent_the_deviation_stays_zero_and_states_match():
    chains = [random_chain(879, 5.0)] * 3
    q, p, _, _ = lanes("fput", chains, [0.5, 2.9, 8.7381], [21, 21, 21])
    batch = Batch(Problem("fput", chains, tangent=False, dt=0.02), q, p)
    batch.advance(500)
    assert not batch.dq.any() and not batch.dp.any() and not batch.log_growth.any()
    for j in range(3):
        z = np.zeros(N)
        sq, sp, *_ = single_run("fput", chains[j], q[:, j], p[:, j], z, z, "SRKN6b", 0.02, 500, False, 1000, False)
        np.testing.assert_allclose(batch.q[:, j], sq, rtol=0, atol=1e-13)


def test_a_diverging_lane_is_reported_and_leaves_the_others_alone():
    """FPUT with the Taylor sign of K4 escapes at high energy; one such lane goes non-finite."""
    chain = random_chain(879, 5.0).with_k4_sign(-1)
    q = np.zeros((N, 2))
    q[20, 0] = 0.3
    q[20, 1] = 40.0  # far beyond the barrier of the quartic: escapes to infinity
    batch = Batch(Problem("fput", [chain, chain], dt=0.01, check_every=10), q, np.zeros((N, 2)), dp=np.full((N, 2), 0.1))
    with np.errstate(all="ignore"):
        batch.advance(2000)
    assert batch.bad[0] == -1 and batch.bad[1] > 0
    assert np.isfinite(batch.q[:, 0]).all()
    z = np.zeros(N)
    dp = np.full(N, 0.1)
    sq, *_ = single_run("fput", chain, q[:, 0], np.zeros(N), z, dp, "SRKN6b", 0.01, 2000, True, 10, False)
    np.testing.assert_allclose(batch.q[:, 0], sq, rtol=0, atol=1e-12)


def test_lane_parameters_are_trajectory_innermost():
    chains = [random_chain(s, 5.0) for s in range(3)]
    inv_mass, bonds = Problem("hertz", chains).lane_parameters
    assert bonds.shape == (2, N + 1, 3) and inv_mass.shape == (N, 3)
    assert inv_mass.flags.c_contiguous and bonds.flags.c_contiguous
    np.testing.assert_array_equal(bonds[1, :, 2], chains[2].delta)  # Hertz: (A, delta)
    np.testing.assert_array_equal(inv_mass[:, 1], 1.0 / chains[1].mass)


def test_every_scheme_runs_in_the_batch_engine():
    chain = random_chain(879, 5.0)
    q, p, dq, dp = lanes("hertz", [chain], [1.0], [21])
    for name in SCHEMES:
        b = Batch(Problem("hertz", [chain], integrator=name, dt=0.01), q, p, dq, dp)
        b.advance(50)
        assert np.isfinite(b.q).all() and b.bad[0] == -1
