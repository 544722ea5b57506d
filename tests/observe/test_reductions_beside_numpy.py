"""The time reductions written by hand (observe.reductions) until the NumPy floor is 2.0, beside
what NumPy 2.0 offers: the same bits on random samples (skipped under NumPy 1.x)."""

import numpy as np
import pytest

from chainchaos.kernels import exactmath
from chainchaos.observe.reductions import log_time_median, time_average

pytestmark = pytest.mark.skipif(int(np.__version__.split(".")[0]) < 2, reason="NumPy 2.0's trapezoid and weights")


def _samples(rng):
    t = np.sort(np.concatenate([[1.0], rng.uniform(1.0, 1e4, 50)]))
    return t, rng.normal(size=t.size)


def test_the_time_average_is_numpy_s_trapezoid_to_the_bit():
    rng = np.random.default_rng(0)
    for _ in range(500):
        t, y = _samples(rng)
        assert time_average(t, y, t[0]) == np.trapezoid(y, t) / (t[-1] - t[0])


def test_the_log_time_median_is_numpy_s_weighted_lower_median():
    rng = np.random.default_rng(1)
    for _ in range(500):
        t, y = _samples(rng)
        x = exactmath.log10(t)
        weights = np.diff(np.concatenate(([0.0], 0.5 * (x[1:] + x[:-1]), [x[-1]])))
        assert log_time_median(t, y, 1.0) == np.quantile(y, 0.5, weights=weights, method="inverted_cdf")
