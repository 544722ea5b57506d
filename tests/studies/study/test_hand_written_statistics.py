"""The statistics written by hand for reasons worth keeping (the same bits on every CPU: sums in
index order, fdlibm's logarithms), checked against the maintained libraries on the same data:
the Wilson interval against statsmodels, the bootstrap interval of a fitted exponent against
scipy.stats.bootstrap (percentile method), within the resampling error."""

import numpy as np
import pytest
from scipy import stats
from statsmodels.stats.proportion import proportion_confint

from chainchaos.kernels import exactmath
from chainchaos.studies.study.laws import fit_law
from chainchaos.studies.study.statistics import ordered_mean, wilson_interval


@pytest.mark.parametrize("n", [1, 5, 16, 32, 100])
def test_the_wilson_interval_is_statsmodels(n):
    k = np.arange(n + 1)
    lower, upper = wilson_interval(k, np.full(k.shape, n))
    theirs = proportion_confint(k, n, alpha=0.05, method="wilson")
    np.testing.assert_allclose(lower, theirs[0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(upper, theirs[1], rtol=0, atol=1e-12)


def test_the_bootstrap_interval_of_an_exponent_is_scipy_s_within_the_resampling_error():
    """32 realizations of log10 m2 = 0.3 log10 t + a realization's offset and noise: the interval
    of fit_law (its own resamples, in index order) and scipy's percentile interval of the same
    statistic (the exponent of the mean over the same window) agree to a few resampling errors."""
    rng = np.random.default_rng(7)
    t = np.logspace(0, 6, 121)
    R = 32
    logs = 0.3 * np.log10(t)[None, :] + rng.normal(0, 0.3, (R, 1)) + rng.normal(0, 0.05, (R, t.size)) \
        + rng.normal(0, 0.02, (R, 1)) * np.log10(t)[None, :]
    fit = fit_law(t, 10.0 ** logs, window_decades=1.0, min_decades=2.0, band=0.05, t_min=10.0, bootstrap=4000,
                  seed=0)
    window = (t >= fit["t_start"]) & (t <= fit["t_end"])
    log_t = exactmath.log10(t[window])

    def exponent(pick):  # the realizations are the units resampled: scipy resamples their indices
        return np.polyfit(log_t, ordered_mean(logs[pick.astype(int)][:, window], axis=0)[0], 1)[0]

    theirs = stats.bootstrap((np.arange(R),), exponent, vectorized=False, method="percentile", n_resamples=4000,
                             random_state=np.random.default_rng(1)).confidence_interval
    width = fit["upper"] - fit["lower"]
    assert fit["lower"] < 0.3 < fit["upper"]
    # the 2.5 and 97.5 % quantiles of 4000 resamples: each known to a few per cent of the width
    assert abs(fit["lower"] - theirs.low) < 0.1 * width and abs(fit["upper"] - theirs.high) < 0.1 * width, \
        (fit["lower"], fit["upper"], theirs)
