"""Chaos indicators from many deviation vectors (Lyapunov spectrum, SALI, GALI_k) against exact
results: the tangent map of the extra vectors is that of the mLCE vector, the harmonic chain's
exponents vanish and its GALI_2N stays away from zero, the integrable Toda chain's GALI_k follow
their power laws, a chaotic Hertz orbit's spectrum pairs and sums to zero and sets the decay
rates of SALI and GALI_k, and the tangent map needs no correction where a Hertz contact opens."""

import numpy as np
import pytest

from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError
from chainchaos.kernels import exactmath
from chainchaos.kernels.simd import LANES
from chainchaos.observe import formulas, reductions
from chainchaos.run import driver
from chainchaos.run.settings import RunSettings
from chainchaos.system.chain import chain_from_radii, random_chain
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import get_model


def _run(model, chain, q, p, t_final, dt, spectrum=1, gali=1, per_decade=5, t_first=1.0, seed=0, check_every=10):
    """One orbit with its mLCE vector, ``spectrum - 1`` orthonormalised and ``gali - 1``
    normalised extra vectors, sampled log-spaced to t_final."""
    N = chain.N
    problem = Problem(model, [chain], integrator="SRKN6b", dt=dt, tangent=True, track_gaps=False,
                      check_every=check_every, spectrum=spectrum, gali=gali)
    dq, dp = initial_deviation(N, seed)
    xq, xp = (x[:, :, None] for x in RunSettings(t_final=t_final, dt=dt, deviation_seed=seed).extra_deviations(problem))
    steps = driver.sample_steps(t_final, dt, per_decade, t_first)
    return driver.sample(problem, q[:, None], p[:, None], dq[:, None], dp[:, None], steps, xq0=xq, xp0=xp)


def _excited(model, chain, energy, site=None):
    q, p, _ = initial_state(model, chain, energy, site or chain.N // 2 + 1)
    return q, p


def test_an_extra_vector_equal_to_the_mlce_vector_stays_equal_to_the_bit():
    """The extra vectors go through the same tangent map as the mLCE vector, operation for
    operation: started equal, a normalised (GALI) vector stays equal to it to the bit, and the
    orbit and mLCE vector are those of a run without extra vectors."""
    chain = random_chain(879, 5.0)
    model = get_model("hertz")
    q, p = _excited(model, chain, 3.0, 21)
    dq, dp = initial_deviation(chain.N, 0)
    steps = driver.sample_steps(50.0, 0.01, 4, 1.0)
    plain = driver.sample(Problem(model, [chain], dt=0.01, track_gaps=True, check_every=7),
                          q[:, None], p[:, None], dq[:, None], dp[:, None], steps)
    problem = Problem(model, [chain], dt=0.01, track_gaps=True, check_every=7, gali=3)
    xq = np.stack([dq, np.zeros_like(dq)])[:, :, None]
    xp = np.stack([dp, np.ones_like(dp) / np.sqrt(chain.N)])[:, :, None]
    engine = problem.engine(q[:, None], p[:, None], dq[:, None], dp[:, None], xq=xq, xp=xp)
    for interval in np.diff(steps):
        engine.advance(int(interval))
    assert np.array_equal(engine.xq[0], engine.dq) and np.array_equal(engine.xp[0], engine.dp)
    assert np.array_equal(engine.q[:, 0], plain.Q[0, -1]) and np.array_equal(engine.dq[:, 0], plain.DQ[0, -1])
    assert engine.log_growth[0] == plain.log_growth[0, -1] == engine.x_growth[0, 0]


def test_the_first_exponent_is_the_mlce_of_one_vector():
    chain = random_chain(879, 5.0)
    q, p = _excited("hertz", chain, 3.0, 21)
    one = _run("hertz", chain, q, p, 100.0, 0.01)
    many = _run("hertz", chain, q, p, 100.0, 0.01, spectrum=6)
    assert np.array_equal(many.log_growth, one.log_growth)  # the spectrum's vectors leave it alone
    assert np.array_equal(many.spectrum_growth[0, :, 0], one.log_growth[0])


@pytest.mark.parametrize("N", [5, 8])
def test_the_harmonic_chain_has_zero_exponents_and_a_bounded_gali(N):
    """A linear flow: deviation vectors stay bounded, so every finite-time exponent is O(1/t)
    (t lambda_i bounded), and with no twist the normalised vectors keep a volume away from 0."""
    chain = random_chain(5, 3.0, N)
    q, p = _excited("harmonic", chain, 1.0, 2)
    run = _run("harmonic", chain, q, p, 1e4, 0.02, spectrum=2 * N, gali=2 * N)
    t = run.times
    spectrum = formulas.lyapunov_spectrum(run.spectrum_growth[0], t)
    late = t >= 100.0
    bound = np.abs(spectrum[late] * t[late, None]).max(axis=1)
    assert bound.max() < 20.0 and bound[-1] < 2.0 * bound[:3].max() + 1.0  # t lambda_i does not grow
    assert np.abs(spectrum[-1]).max() < 20.0 / t[-1]
    # GALI_2N bounded away from zero: it oscillates without a trend (no twist, no power law; an
    # integrable chain's GALI_2N decays as t^(-2N)), so its log-log slope is flat
    use = t >= 10.0
    slope = exactmath.line_slope(exactmath.log10(t[use]), run.log_gali[0, use] / np.log(10.0))
    assert abs(slope) < 0.3 and run.log_gali[0, use][-10:].min() > run.log_gali[0, use][:10].min() - 2.0
    assert np.abs(run.spectrum_growth[0, -1].sum()) < 1e-9  # sum of exponents: ln det = 0


def _loglog_slope(t, y, t0, t1):
    use = (t >= t0) & (t <= t1)
    return exactmath.line_slope(exactmath.log10(t[use]), exactmath.log10(y[use]))


def test_gali_of_the_integrable_toda_chain_follows_its_power_laws():
    """A generic orbit of an integrable chain of N beads lies on an N-torus: GALI_k stays near
    a constant for k <= N and decays as t^(-2(k-N)) for N < k <= 2N (Skokos, Bountis &
    Antonopoulos 2007); every exponent tends to 0. The laws need twist: every mode strongly
    excited (beta u ~ 1), the slopes fitted over the last decade."""
    N = 3
    chain = chain_from_radii(np.ones(N))
    rng = np.random.default_rng(3)
    q, p = 2.0 * rng.uniform(-1, 1, N), 2.0 * rng.uniform(-1, 1, N)
    for k in range(N, 2 * N + 1):
        run = _run("toda", chain, q, p, 1e4, 0.01, gali=k, per_decade=10)
        slope = _loglog_slope(run.times, np.exp(run.log_gali[0]), 1e3, 1e4)
        assert slope == pytest.approx(-2.0 * max(k - N, 0), abs=0.1 * (k - N) + 0.25), (k, slope)
    run = _run("toda", chain, q, p, 1e4, 0.01, spectrum=2 * N)
    lam = formulas.lyapunov_spectrum(run.spectrum_growth[0], run.times)
    late = run.times >= 1e2
    assert np.abs(lam[late] * run.times[late, None] / np.log(run.times[late, None])).max() < 5.0  # O(ln t / t)


@pytest.fixture(scope="module")
def hertz_orbit():
    """A chaotic Hertz orbit (H = 3, the highest of the paper's Hertz energies) of a chain of 10
    beads (alpha = 5, seed 879), the excitation at its centre."""
    chain = random_chain(879, 5.0, 10)
    return chain, *_excited("hertz", chain, 3.0, 5)


def test_a_chaotic_spectrum_pairs_and_sums_to_zero(hertz_orbit):
    chain, q, p = hertz_orbit
    spec = _run("hertz", chain, q, p, 2e3, 0.01, spectrum=2 * chain.N, per_decade=20)
    lam = formulas.lyapunov_spectrum(spec.spectrum_growth[0], spec.times)[-1]
    assert lam[0] > 0.01  # chaotic
    assert np.all(np.diff(lam) <= 1e-3)  # the QR orders them
    assert abs(lam.sum()) < 1e-12  # symplectic: phase-space volume preserved
    assert np.abs(lam + lam[::-1]).max() < 0.1 * lam[0]  # lambda_i = -lambda_(2N+1-i)
    assert formulas.ks_entropy(lam[None])[0] == pytest.approx(lam[lam > 0].sum())


def test_sali_and_gali_decay_at_the_rates_the_spectrum_sets(hertz_orbit):
    """SALI ~ exp(-(lambda_1 - lambda_2) t), GALI_3 ~ exp(-((lambda_1 - lambda_2) + (lambda_1 -
    lambda_3)) t), the exponents taken from the computed spectrum (its first three, to t = 1e4);
    the rates fitted while the indicator falls from e^-3 to e^-30."""
    chain, q, p = hertz_orbit
    spec = _run("hertz", chain, q, p, 1e4, 0.01, spectrum=3, per_decade=20)
    lam = formulas.lyapunov_spectrum(spec.spectrum_growth[0], spec.times)[-1]
    for k, rate in ((2, lam[0] - lam[1]), (3, 2 * lam[0] - lam[1] - lam[2])):
        run = _run("hertz", chain, q, p, 1e4, 0.01, gali=k, per_decade=40, t_first=0.1)
        values = np.log(run.sali[0]) if k == 2 else run.log_gali[0]
        use = (values < -3.0) & (values > -30.0)
        assert use.sum() >= 20
        assert -exactmath.line_slope(run.times[use], values[use]) == pytest.approx(rate, rel=0.15)
        if k == 2:  # GALI_2 and SALI measure the same angle
            assert np.allclose(run.log_gali[0, use], np.log(run.sali[0, use]), atol=0.05)


def test_the_tangent_map_needs_no_correction_where_a_contact_opens():
    """Hertz force and stiffness are continuous where an overlap reaches zero (k ~ x^(1/2) -> 0),
    so the saltation matrix is the identity: over steps in which a contact opens, the tangent
    map equals the derivative of the flow, measured by finite differences."""
    chain = random_chain(879, 5.0, 6)
    model = get_model("hertz")
    N = chain.N
    q = np.zeros(N)
    p = np.zeros(N)
    p[2], p[3] = -1.0, 1.0  # beads 3 and 4 fly apart: bond 4 opens within the first steps
    dq, dp = initial_deviation(N, 2)
    dt, n = 0.002, 400
    problem = Problem(model, [chain], dt=dt, tangent=True, track_gaps=True, check_every=10**9)
    base = problem.engine(q[:, None], p[:, None], dq[:, None], dp[:, None], kind="single")
    base.advance(n)
    assert base.gap_steps[:, 0].max() > 0  # a contact did open
    scale = np.exp(base.log_growth[0])  # the engine normalised the vector at the end
    tangent = np.concatenate([base.dq[:, 0], base.dp[:, 0]]) * scale
    errors = []
    for eps in (1e-5, 1e-6):
        plus = problem.engine((q + eps * dq)[:, None], (p + eps * dp)[:, None], kind="single")
        minus = problem.engine((q - eps * dq)[:, None], (p - eps * dp)[:, None], kind="single")
        plus.advance(n)
        minus.advance(n)
        fd = np.concatenate([plus.q[:, 0] - minus.q[:, 0], plus.p[:, 0] - minus.p[:, 0]]) / (2 * eps)
        errors.append(np.abs(fd - tangent).max() / np.abs(tangent).max())
    assert max(errors) < 1e-8  # central differences to round-off: no jump where the contact opened


def _regular_and_chaotic(lanes_each=LANES):
    """A batch of Hertz orbits: lanes 0..lanes_each-1 at H = 3 (chaotic), the rest at H = 0.05
    (near-linear, regular), with GALI_3's vectors; (problem, state, extra vectors, steps)."""
    chain = random_chain(879, 5.0)
    model = get_model("hertz")
    energies = [3.0] * lanes_each + [0.05] * lanes_each
    problem = Problem(model, [chain] * len(energies), integrator="SRKN6b", dt=0.01, tangent=True, track_gaps=False,
                      check_every=10, gali=3)
    N, B = chain.N, len(energies)
    Q, P, DQ, DP = (np.zeros((N, B)) for _ in range(4))
    for j, H in enumerate(energies):
        Q[:, j], P[:, j] = _excited(model, chain, H, 21)
        DQ[:, j], DP[:, j] = initial_deviation(N, j)
    xq, xp = RunSettings(t_final=1.0, dt=0.01).extra_deviations(problem)
    XQ, XP = np.repeat(xq[:, :, None], B, axis=2), np.repeat(xp[:, :, None], B, axis=2)
    return problem, (Q, P, DQ, DP), (XQ, XP), driver.sample_steps(2e3, 0.01, 10, 1.0)


def test_gali_vectors_stop_once_decided_and_nothing_else_changes():
    """driver.sample's gali_stop: a lane's ln GALI_k is recorded up to the first sample below the
    threshold and NaN after; the orbits, mLCE vectors and the records of undecided lanes are those
    of the run without a stop, bit for bit; the vectors of a block whose lanes all stopped stay
    as they were (the saved work)."""
    problem, state, (XQ, XP), steps = _regular_and_chaotic()
    full = driver.sample(problem, *state, steps, xq0=XQ, xp0=XP)
    stop = np.log(1e-5)
    stopped = driver.sample(problem, *state, steps, xq0=XQ, xp0=XP, gali_stop=stop)
    for key in ("Q", "P", "DQ", "DP", "log_growth"):
        assert np.array_equal(getattr(full, key), getattr(stopped, key)), key
    chaotic, regular = slice(0, LANES), slice(LANES, 2 * LANES)
    assert np.all(full.log_gali[chaotic, -1] < stop) and np.all(full.log_gali[regular] > np.log(1e-2))
    assert np.array_equal(full.log_gali[regular], stopped.log_gali[regular])
    for j in range(LANES):
        first = np.flatnonzero(full.log_gali[j] < stop)[0]
        assert np.array_equal(full.log_gali[j, :first + 1], stopped.log_gali[j, :first + 1])
        assert np.all(np.isnan(stopped.log_gali[j, first + 1:]))
    # the stopped block's vectors are left where the last chaotic lane crossed
    engine = problem.engine(*state, xq=XQ, xp=XP)
    engine.stop_vectors(range(LANES))
    before = engine.xq.copy()
    engine.advance(100)
    assert np.array_equal(engine.xq[:, :, chaotic], before[:, :, chaotic])
    assert not np.array_equal(engine.xq[:, :, regular], before[:, :, regular])


def test_a_stop_needs_gali_vectors_and_no_spectrum():
    chain = random_chain(879, 5.0)
    q, p = _excited("hertz", chain, 0.1, 21)
    dq, dp = initial_deviation(chain.N, 0)
    steps = driver.sample_steps(10.0, 0.01, 2, 1.0)
    with pytest.raises(ParameterError, match="gali_stop"):
        driver.sample(Problem("hertz", [chain], dt=0.01), q[:, None], p[:, None], dq[:, None], dp[:, None], steps,
                      gali_stop=-18.0)


def test_gali_crossing_reads_the_first_sample_below_the_threshold():
    t = np.array([1.0, 10.0, 100.0, 1000.0])
    log_gali = np.log([0.5, 1e-3, 1e-9, np.nan])
    assert reductions.gali_crossing(t, log_gali, 1e-8) == 100.0
    assert np.isnan(reductions.gali_crossing(t, log_gali, 1e-8, end=50.0))
    assert np.isnan(reductions.gali_crossing(t, log_gali, 1e-12))  # NaN is not below
    with pytest.raises(ParameterError, match="threshold"):
        reductions.gali_crossing(t, log_gali, 2.0)


def test_scene_spectra_pair_sum_to_zero_and_start_with_each_orbits_mlce():
    """The spectra product (studies.indicators.spectra): per perturbed orbit all 2N exponents,
    summing to zero (symplectic flow; their pairing is tested above, on a longer run), and
    lambda_1(t) equal to the finite-time mLCE of the same orbit run by orbits.integrate (the
    verdicts' driver) to the bit."""
    from chainchaos.run.orbits import Orbit, OrbitSettings, integrate
    from chainchaos.studies.indicators.report import pairing_error, spectra_macros
    from chainchaos.studies.indicators.spectra import scene_spectra

    chain = random_chain(879, 5.0)
    settings = OrbitSettings(t_final=300.0, dt=0.01, samples_per_decade=5, t_first_sample=1.0, check_every=100,
                             exponents=0)
    ds = scene_spectra(chain, "hertz", 3.0, 21, settings, 3)
    assert ds["lyapunov_spectrum"].shape == (3, ds.sizes["time"], 2 * chain.N)
    final = ds["lyapunov_spectrum"].isel(time=-1).values
    assert np.all(np.abs(final.sum(axis=1)) < 1e-12)
    assert pairing_error(np.array([2.0, 1.0, -1.0, -2.0])) == 0.0
    assert pairing_error(np.array([2.0, 1.0, -0.5, -2.0])) == 0.25
    orbits = [Orbit(model="hertz", energy=3.0, chain=chain, site=21, lane=lane) for lane in range(3)]
    t, runs = integrate(orbits, settings)
    for j, r in enumerate(runs):
        assert np.array_equal(ds["lyapunov_spectrum"].values[j, 1:, 0], formulas.finite_time_mlce(r["log_growth"], t)[1:])
    macros = spectra_macros({"hertz_H3": ds})
    assert macros["spectra.exponents"] == "80" and "Hertz" in macros["spectra.summary"]
