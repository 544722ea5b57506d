"""Power-law fits of ensemble means (chainchaos.studies.study.laws) on series whose laws are exact.

x_r(t) = c_r t^a over realizations r: <log10 x> = a log10 t + <log10 c>, so every fit and every
bootstrap resample gives a (resampling moves only the intercept). A law that bends (flat, then
t^a) must be fitted where it has settled, by the rule, not over the bend; one that saturates at
a finite chain's walls, before them."""

import numpy as np
import pytest

from chainchaos.studies.study.laws import fit_law, fit_window, walls_time
from chainchaos.studies.study.statistics import log10, running_slope

RULE = {"window_decades": 1.0, "min_decades": 1.0, "band": 0.1, "t_min": 100.0, "bootstrap": 200, "seed": 0}


def _times():
    return 10.0 ** (np.arange(0, 141) / 20)  # 1 .. 1e7, 20 samples per decade


def test_an_exact_power_law_is_fitted_exactly_with_a_zero_width_interval():
    t = _times()
    c = np.random.default_rng(1).uniform(0.5, 2.0, 32)
    fit = fit_law(t, c[:, None] * t[None, :] ** (1 / 3), **RULE)
    assert fit["exponent"] == pytest.approx(1 / 3, abs=1e-12)
    assert fit["lower"] == pytest.approx(1 / 3, abs=1e-12) and fit["upper"] == pytest.approx(1 / 3, abs=1e-12)
    assert fit["t_start"] == pytest.approx(100.0) and fit["t_end"] == pytest.approx(1e7)
    assert fit["settled"] and fit["realizations"] == 32


def test_the_window_starts_where_a_bending_law_has_settled():
    t = _times()
    x = np.where(t < 1e4, 1.0, (t / 1e4) ** 0.3)  # flat up to 1e4, then t^0.3
    noise = np.random.default_rng(2).normal(0.0, 0.02, (16, t.size))
    fit = fit_law(t, x[None, :] * 10.0 ** noise, **RULE)
    # the running slope over one decade reaches 0.3 +- 0.1 about a third of a decade after the bend
    assert 1e4 <= fit["t_start"] <= 1e4 * 10 ** 0.5
    assert fit["lower"] <= 0.3 <= fit["upper"] and fit["upper"] - fit["lower"] < 0.05


def test_a_slope_that_still_drifts_is_not_settled():
    t = _times()
    log_t = log10(t)
    y = 0.02 * log_t ** 2  # slope 0.04 log10 t: drifts by 0.04 a decade
    slope = running_slope(log_t, y, 1.0)
    first, last, settled = fit_window(log_t, slope, min_decades=1.0, band=0.01, t_min=100.0)
    assert not settled and log_t[last] - log_t[first] == pytest.approx(1.0)


def test_realizations_left_out_do_not_enter():
    t = _times()
    x = np.vstack([t ** 0.25, 3 * t ** 0.25, np.full(t.size, np.nan)])
    fit = fit_law(t, x, **RULE)
    assert fit["exponent"] == pytest.approx(0.25, abs=1e-12) and fit["realizations"] == 2


def test_the_walls_time_is_the_first_sample_above_the_bound():
    t = _times()
    mean_log10 = np.where(t < 1e3, np.nan, log10(t) - 6.0)  # NaN (nothing at the ends yet), then rising
    assert walls_time(t, mean_log10, 1e-3) == pytest.approx(10 ** 3.05)  # first sample with log10 t - 6 > -3
    assert walls_time(t, mean_log10, None) == np.inf and walls_time(t, mean_log10, 100.0) == np.inf


def test_a_law_that_saturates_at_the_walls_is_fitted_before_them():
    t = _times()
    x = np.minimum(t, 1e5) ** 0.3  # t^0.3, then flat: the packet fills the chain at t = 1e5
    c = np.random.default_rng(3).uniform(0.5, 2.0, 16)
    after = fit_law(t, c[:, None] * x[None, :], **RULE)
    assert after["exponent"] == pytest.approx(0.0, abs=1e-12)  # without the cut: the flat end is fitted
    before = fit_law(t, c[:, None] * x[None, :], **RULE, t_walls=1e5)
    assert before["exponent"] == pytest.approx(0.3, abs=1e-12) and before["t_end"] < 1e5
    assert before["t_walls"] == 1e5


def test_a_chain_too_short_for_the_law_gives_no_exponent():
    t = np.concatenate([[0.0], _times()])  # a run's grid starts at t = 0
    fit = fit_law(t, np.vstack([t ** 0.3, 2 * t ** 0.3]), **RULE, t_walls=10 ** 2.9)  # 0.9 decade after t_min
    assert np.isnan(fit["exponent"]) and np.isnan(fit["lower"]) and not fit["settled"]


class _Grid:
    """The settings a laws file reads: the step and the log-spaced sample steps."""

    dt = 1e-3

    def __init__(self, t):
        self._steps = np.rint(t / self.dt).astype(np.int64)

    def sample_steps(self):
        return self._steps


def test_laws_cut_m2_at_the_tail_and_every_law_at_the_filled_chain():
    """laws() on a merged study whose laws are exact: P = c t^0.5 fills a tenth of N = 1000 near
    t = 1e4, the edge energy appears at 10^3.5 (one realization only at 10^3.6), m2 = c t^1.5 and
    Lambda = t^-0.25; an invalid realization with a huge energy error is left out."""
    import xarray as xr

    from chainchaos.studies.study.laws import laws

    t = np.concatenate([[0.0], _times()[:101]])  # 0, then 1 .. 1e5
    R = 8
    c = 10.0 ** np.linspace(-0.1, 0.12, R)[:, None]
    edge = np.where(t >= 10 ** 3.5, 1e-3, 0.0) * np.ones((R, 1))
    edge[0, t < 10 ** 3.6] = 0.0
    series = {"participation": c * t ** 0.5, "second_moment": c * t ** 1.5, "edge_energy": edge,
              "mlce": np.where(t > 0, t, 1.0) ** -0.25 * np.ones((R, 1))}
    dims = ("model", "energy", "realization", "lane")
    merged = xr.Dataset({name: (dims + ("time",), x[None, None, :, None, :]) for name, x in series.items()},
                        coords={"model": ["hertz"], "energy": [1.8], "time": t})
    valid = np.ones((1, 1, R, 1), dtype=np.int8)
    valid[0, 0, -1, 0] = 0
    error = np.full((1, 1, R, 1), 1e-6)
    error[0, 0, -1, 0] = 1.0
    merged["valid"], merged["energy_error_max"] = (dims, valid), (dims, error)
    spec = {"criteria": {"slope_window_decades": 1.0},
            "laws": {"fits": [{"series": s, "expected": 0.0, "reference": "-"}
                              for s in ("second_moment", "participation", "mlce")],
                     "min_decades": 1.0, "band": 0.1, "t_min": 100.0, "bootstrap": 100, "seed": 0,
                     "walls": {"edge_energy": 1e-6, "participation_fraction": 0.1}}}
    ds = laws(merged, spec, _Grid(t), N=1000)
    fit = ds.isel(model=0, energy=0)
    mean_p = np.mean(np.log10(c[:-1]) + 0.5 * np.log10(np.where(t > 0, t, 1.0)), axis=0)
    filled = t[np.flatnonzero((t > 0) & (mean_p > 2.0))[0]]
    assert 10 ** 3.9 < filled < 10 ** 4.1
    assert fit["t_walls"].sel(law="m2") == pytest.approx(10 ** 3.6)  # every realization has energy at the ends
    assert fit["t_walls"].sel(law="P") == fit["t_walls"].sel(law="Lambda") == pytest.approx(filled)
    for law, exponent in (("m2", 1.5), ("P", 0.5), ("Lambda", -0.25)):
        assert fit["exponent"].sel(law=law) == pytest.approx(exponent, abs=1e-12)
        assert fit["t_end"].sel(law=law) < fit["t_walls"].sel(law=law)
    assert float(fit["energy_error_max"]) == 1e-6 and ds.attrs["walls_participation_fraction"] == 0.1


def test_a_study_that_names_no_law_gets_a_laws_file_without_laws(tmp_path):
    """study_statistics writes laws.nc for every study: with no law named, its law dimension is
    empty, and the file is written and read back like any other."""
    import xarray as xr

    from chainchaos.records.io import write_netcdf
    from chainchaos.studies.study.laws import laws

    t = np.concatenate([[0.0], _times()[:41]])
    dims = ("model", "energy", "realization", "lane")
    ones = np.ones((1, 1, 3, 1))
    merged = xr.Dataset({"participation": (dims + ("time",), ones[..., None] * np.ones(t.size)),
                         "valid": (dims, ones.astype(np.int8)), "energy_error_max": (dims, 1e-7 * ones)},
                        coords={"model": ["fput"], "energy": [0.5], "time": t})
    spec = {"criteria": {"slope_window_decades": 1.0},
            "laws": {"fits": [], "min_decades": 1.0, "band": 0.1, "t_min": 10.0, "bootstrap": 10, "seed": 0,
                     "walls": {"edge_energy": None, "participation_fraction": None}}}
    ds = laws(merged, spec, _Grid(t), N=40)
    assert ds.sizes["law"] == 0 and ds["energy_error_max"].item() == 1e-7
    back = xr.load_dataset(write_netcdf(ds, tmp_path / "laws.nc"))
    assert back.sizes["law"] == 0 and set(back.data_vars) == set(ds.data_vars)


def test_the_local_derivative_of_a_crossover_and_its_band():
    """m2 ~ t^(1/2) up to t = 1e3, then ~ t^(1/3): away from the kink the local derivative is the
    exponent; realizations differing by a constant factor give a band of zero width, noisy ones
    a band around the mean's derivative; the largest value is 1/2, before the kink."""
    from chainchaos.studies.study.laws import local_derivative

    t = 10.0 ** np.arange(0, 6.01, 0.1)
    law = np.where(t < 1e3, t**0.5, 1e3**0.5 * (t / 1e3) ** (1 / 3))
    rng = np.random.default_rng(0)
    shifted = law * 10.0 ** rng.uniform(-0.3, 0.3, (16, 1))
    found = local_derivative(t, shifted, window_decades=1.0, t_min=1.0, bootstrap=200, seed=0)
    early, late = (t > 3) & (t < 300), t > 3e3
    np.testing.assert_allclose(found["slope"][early], 0.5, atol=1e-12)
    np.testing.assert_allclose(found["slope"][late & np.isfinite(found["slope"])], 1 / 3, atol=1e-12)
    np.testing.assert_allclose(found["upper"] - found["lower"], 0.0, atol=1e-12, equal_nan=True)
    assert found["max"] == pytest.approx(0.5, abs=1e-12) and found["t_max"] < 1e3
    noisy = shifted * 10.0 ** rng.normal(0, 0.05, shifted.shape)
    band = local_derivative(t, noisy, window_decades=1.0, t_min=1.0, bootstrap=200, seed=0)
    inside = np.isfinite(band["slope"])
    assert np.all(band["lower"][inside] <= band["upper"][inside]) and np.nanmax(band["upper"] - band["lower"]) > 0.01
    cut = local_derivative(t, shifted, window_decades=1.0, t_min=1.0, bootstrap=10, seed=0, t_walls=1e4)
    assert np.all(np.isnan(cut["slope"][t >= 1e4]))
