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
