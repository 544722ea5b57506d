"""Numerics study (issue 5): right-hand side, measured runs, orders, stability, Taylor-sign guard."""

import math

import numpy as np
import pytest
import xarray as xr

from chainchaos.engine.rhs import RightHandSide
from chainchaos.errors import ParameterError, SimulationError
from chainchaos.records.io import write_netcdf
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.studies.numerics import (
    energy_drift,
    largest_stable_dt,
    linear_instability_intervals,
    linear_stability_bound,
    observed_order,
    order_table,
    phase_space_error,
    run_scheme,
    run_solve_ivp,
    step_advice,
    taylor_sign_probe,
    work_precision,
)
from chainchaos.studies.numerics.stability import excitation_barrier, is_stable
from chainchaos.system.chain import chain_at_alpha, sonic_vacuum_chain
from chainchaos.system.initial import initial_state
from chainchaos.system.linear import normal_modes
from chainchaos.system.models import bond_forces, get_model, total_energy

HERTZ, FPUT = get_model("hertz"), get_model("fput")


def _state(chain, model, energy, seed=1):
    """A generic state: the single-site excitation plus a random perturbation of every bead."""
    u, p, _ = initial_state(model, chain, energy, 21)
    rng = np.random.default_rng(seed)
    return u + 0.05 * rng.standard_normal(chain.N), p + 0.05 * rng.standard_normal(chain.N)


@pytest.mark.parametrize("model", [HERTZ, FPUT])
def test_rhs_agrees_with_the_force_kernel_and_the_energy_gradient(chain, model):
    u, p = _state(chain, model, 1.8)
    N = chain.N
    dydt = RightHandSide(model, chain)(0.0, np.concatenate([u, p]))
    f, k = np.empty(N + 1), np.empty(N + 1)
    bond_forces(model, u, model.bond_parameters(chain), f, k, False)
    np.testing.assert_allclose(dydt[:N], p / chain.mass, rtol=1e-15, atol=0)
    np.testing.assert_allclose(dydt[N:], f[:-1] - f[1:], rtol=0, atol=1e-15)
    # -dV/du_n by central differences of the package's total energy
    h = 1e-6
    grad = np.array([(total_energy(model, chain, u + h * e, p) - total_energy(model, chain, u - h * e, p)) / (2 * h)
                     for e in np.eye(N)])
    np.testing.assert_allclose(dydt[N:], -grad, rtol=1e-6, atol=1e-8)


@pytest.mark.parametrize("model", [HERTZ, FPUT])
def test_tangent_rhs_is_the_derivative_of_the_force(chain, model):
    u, p = _state(chain, model, 1.8)
    N = chain.N
    rng = np.random.default_rng(2)
    du, dp = rng.standard_normal(N), rng.standard_normal(N)
    fun = RightHandSide(model, chain, tangent=True)
    out = fun(0.0, np.concatenate([u, p, du, dp]))
    plain = RightHandSide(model, chain)
    eps = 1e-6
    fd = (plain(0, np.concatenate([u + eps * du, p]))[N:] - plain(0, np.concatenate([u - eps * du, p]))[N:]) / (2 * eps)
    np.testing.assert_allclose(out[2 * N:3 * N], dp / chain.mass, rtol=1e-15)
    np.testing.assert_allclose(out[3 * N:], fd, rtol=1e-5, atol=1e-8)
    np.testing.assert_allclose(out[:2 * N], plain(0, np.concatenate([u, p])), rtol=0, atol=0)


def test_solve_ivp_and_splitting_agree_on_the_same_trajectory(chain):
    split = run_scheme(FPUT, chain, 0.25, "SRKN11b", 5e-3, 20.0, 10.0, repeats=1)
    ivp = run_solve_ivp(FPUT, chain, 0.25, "DOP853", 1e-12, 20.0, 10.0, repeats=1)
    assert ivp.stable and ivp.n_steps > 0 and ivp.force_evaluations > ivp.n_steps
    assert phase_space_error(ivp.state_probe, split.state_probe) < 1e-8
    assert abs(ivp.lambda_final - split.lambda_final) < 1e-8
    assert ivp.max_energy_error < 1e-8 and split.max_energy_error < 1e-10
    assert ivp.seconds > 0 and split.seconds > 0


def _orders(chain, model, energy, t, cases):
    ref = run_scheme(model, chain, energy, "SRKN11b", 1e-3, t, t, tangent=False, repeats=1, track_gaps=True)
    result = {}
    for scheme, dts in cases:
        errors = [phase_space_error(run_scheme(model, chain, energy, scheme, dt, t, t, tangent=False,
                                               repeats=1).state_probe, ref.state_probe) for dt in dts]
        result[scheme] = observed_order(dts, errors, 1e-12, 1.0, None)[0]
    return result, ref


SMOOTH_CASES = [("verlet", [0.05, 0.025, 0.0125]), ("SRKN6b", [0.2, 0.1, 0.05]), ("yoshida6", [0.2, 0.1, 0.05])]


@pytest.mark.parametrize("model, energy", [(FPUT, 0.25), (HERTZ, 0.05)])
def test_observed_order_on_a_smooth_case_is_the_nominal_order(chain, model, energy):
    """FPUT, and Hertz at an energy where no contact opens, are smooth: full order."""
    orders, ref = _orders(chain, model, energy, 10.0, SMOOTH_CASES)
    if model == HERTZ:
        assert ref.max_open_gaps == 0
    for scheme, nominal in (("verlet", 2), ("SRKN6b", 4), ("yoshida6", 6)):
        assert abs(orders[scheme] - nominal) < 0.25, (scheme, orders[scheme])


def test_opening_contacts_reduce_the_order(chain):
    """Hertz at H = 1.8 opens contacts (f ~ x^(3/2) is not smooth at x = 0): the sixth-order
    scheme measures well below 6, Verlet keeps 2."""
    orders, ref = _orders(chain, HERTZ, 1.8, 20.0, SMOOTH_CASES)
    assert ref.max_open_gaps >= 1
    assert orders["yoshida6"] < 4.0 and orders["SRKN6b"] < 3.6
    assert abs(orders["verlet"] - 2.0) < 0.25


def test_work_precision_dataset_and_order_table(chain, tmp_path):
    ds = work_precision(chain, [("fput", 0.25)], schemes=["verlet", "SRKN6b"], dts=[0.1, 0.05, 0.025],
                        tolerances={"DOP853": [1e-8], "RK45": [1e-6]}, t_final=20.0, t_probe=10.0,
                        reference={"scheme": "SRKN11b", "dt": {"fput": 2.5e-3}}, repeats=1)
    assert ds.sizes == {"case": 1, "run": 8}
    for name in ("seconds", "energy_error", "phase_space_error", "lambda_error"):
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
        assert np.all(np.isfinite(ds[name].values)), name
    assert ds.seconds.attrs["units"] == "s" and "parameters" in ds.attrs and "git_commit" in ds.attrs
    rows = {r["scheme"]: r for r in order_table(ds)}
    assert abs(rows["verlet"]["order_phase_space"] - 2) < 0.2
    assert abs(rows["SRKN6b"]["order_phase_space"] - 4) < 0.3
    assert not rows["SRKN6b"]["contacts_open"] and not rows["SRKN6b"]["reduced"]
    path = write_netcdf(ds, tmp_path / "wp.nc")
    with xr.open_dataset(path) as again:
        assert list(again.method.values[:3]) == ["verlet"] * 3


def test_linear_stability_bounds():
    assert linear_stability_bound("verlet") == pytest.approx(2.0, abs=1e-9)
    # SRKN6b: a narrow resonance interval near omega dt = pi before the wide one at ~5.03
    narrow, wide = linear_instability_intervals("SRKN6b")[:2]
    assert narrow[1] - narrow[0] < 0.01 and wide[1] - wide[0] > 1
    assert linear_stability_bound("SRKN6b") == pytest.approx(narrow[0], abs=1e-4)
    assert linear_stability_bound("SRKN6b", 0.1) == pytest.approx(wide[0], abs=1e-4)


def test_bisection_brackets_the_energy_error_bound(chain):
    r = largest_stable_dt(FPUT, chain, 1.0, "verlet", t_final=100.0, bound=1e-2, rel_tol=0.02)
    assert r["dt_max"] < r["dt_unstable"] <= r["dt_max"] * 1.02 * (1 + 1e-9)
    assert is_stable(FPUT, chain, 1.0, "verlet", r["dt_max"], 100.0, 1e-2)[0]
    ok, t_stop = is_stable(FPUT, chain, 1.0, "verlet", r["dt_unstable"], 100.0, 1e-2)
    assert not ok and 0 < t_stop <= 100.0 + r["dt_unstable"]
    # the energy error bound is met below the linear bound x_s / omega_max = 2 / omega_max
    assert r["dt_max"] * normal_modes(chain)[0][-1] < 2.0


def test_sonic_vacuum_chain_is_the_reference_chain_at_extreme_energy(chain):
    """F0 -> lam F0 maps onto the reference chain with u -> lam^(2/3) u, t -> lam^(-1/6) t,
    H -> lam^(5/3) H: the same trajectory, rescaled."""
    lam = 1e-6
    sonic = sonic_vacuum_chain(chain, lam)
    assert np.allclose(sonic.delta, chain.delta * lam ** (2 / 3)) and np.array_equal(sonic.A, chain.A)
    assert normal_modes(sonic)[0][-1] == pytest.approx(normal_modes(chain)[0][-1] * lam ** (1 / 6), rel=1e-12)
    assert sonic.with_k4_sign(-1).delta == pytest.approx(sonic.delta)
    H, dt, t = 0.5, 0.02, 20.0
    a = run_scheme(HERTZ, sonic, H, "SRKN6b", dt, t, t, tangent=False, repeats=1)
    b = run_scheme(HERTZ, chain, H * lam ** (-5 / 3), "SRKN6b", dt * lam ** (1 / 6), t * lam ** (1 / 6),
                   t * lam ** (1 / 6), tangent=False, repeats=1)
    N = chain.N
    np.testing.assert_allclose(a.state_probe[:N], lam ** (2 / 3) * b.state_probe[:N], rtol=0,
                               atol=1e-9 * np.abs(a.state_probe[:N]).max())
    np.testing.assert_allclose(a.state_probe[N:], lam ** (5 / 6) * b.state_probe[N:], rtol=0,
                               atol=1e-9 * np.abs(a.state_probe[N:]).max())


def test_chain_at_alpha_keeps_the_draws(chain):
    other = chain_at_alpha(chain, 20.0)
    R = other.radius * (20.0 + 1) / 2
    assert other.alpha == 20.0 and R.min() >= 1.0 and R.max() <= 20.0
    back = chain_at_alpha(other, 5.0)
    np.testing.assert_allclose(back.radius, chain.radius, rtol=1e-13)
    assert chain_at_alpha(chain, chain.alpha) is chain


def test_energy_drift_is_bounded(chain):
    r = energy_drift(HERTZ, chain, 1.8, "SRKN6b", 5e-3, 2e3, check_interval=1.0)
    assert r["time"][-1] == pytest.approx(2e3) and r["n_steps"] == 400000
    assert r["max_abs_error"].max() < 1e-5
    assert abs(r["growth_exponent"]) < 0.3


def test_taylor_sign_fput_is_stopped_with_a_clear_error(chain):
    taylor = chain.with_k4_sign(-1)
    barrier = excitation_barrier(FPUT, taylor)
    assert 1.8 < barrier < 8.7381
    # below the barrier the energy is reached, the state escapes, and the guard names scene and time
    with pytest.raises(SimulationError) as err:
        simulate(chain, SceneParameters(model="fput", energy=1.8, t_final=100.0, dt=5e-3, k4_sign=-1,
                                        observables=("energy_error",), check_every=100))
    assert err.value.scene == "fput_H1.8" and 0 < err.value.time < 100.0
    assert "fput_H1.8" in str(err.value) and f"t = {err.value.time:.6g}" in str(err.value)
    # above it the energy cannot be put into the excitation at all
    with pytest.raises(ParameterError, match=r"energy = 8.7381.*at most"):
        simulate(chain, SceneParameters(model="fput", energy=8.7381, t_final=100.0, dt=5e-3, k4_sign=-1,
                                        observables=("energy_error",)))
    rows = taylor_sign_probe(chain, [0.25, 1.8, 8.7381], 50.0, 5e-3, "SRKN6b")
    assert [r["outcome"] for r in rows] == ["bounded", "SimulationError", "ParameterError"]
    assert rows[0]["max_energy_error"] < 1e-6 and 0 < rows[1]["t_stopped"] < 50.0


def test_step_advice_reports_error_per_scene(chain):
    ds = step_advice(chain, [("hertz", 1.8), ("fput", 0.25)], "SRKN6b", dts=[5e-3, 2e-2], t_final=20.0,
                     paper_dt=5e-3)
    assert ds.energy_error.dims == ("scene", "dt") and list(ds.scene.values) == ["hertz_H1.8", "fput_H0.25"]
    e = ds.energy_error.sel(scene="hertz_H1.8").values
    assert 0 < e[0] < e[1] < 1e-2
    assert float(ds.speedup.sel(dt=5e-3).values[0]) == 1.0


def test_figures_are_byte_stable(chain, tmp_path):
    pytest.importorskip("matplotlib")
    from chainchaos.output.plotting.numerics import plot_work_precision

    ds = work_precision(chain, [("hertz", 0.05)], schemes=["verlet"], dts=[0.1, 0.05], tolerances={"RK45": [1e-5]},
                        t_final=10.0, t_probe=10.0, reference={"scheme": "SRKN6b", "dt": {"hertz": 0.01}},
                        repeats=1)
    first = plot_work_precision(ds, tmp_path / "a" / "wp")
    second = plot_work_precision(ds, tmp_path / "b" / "wp")
    for x, y in zip(first, second):
        assert x.read_bytes() == y.read_bytes()
    assert b"CreationDate" not in first[0].read_bytes()
    assert sorted(p.name for p in (tmp_path / "a").iterdir()) == ["wp.pdf", "wp.png"]
    assert math.isfinite(float(ds.phase_space_error.max()))
