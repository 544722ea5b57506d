"""Tests of a study's chaos figure (chainchaos.output.plotting.study), drawn from a small synthetic
statistics file that follows the data contract (docs/conventions.md#study-files)."""

import numpy as np
import pytest
import xarray as xr

from chainchaos.output.plotting.study import chaos_figure, fractions_figure


def _statistics() -> xr.Dataset:
    t = np.logspace(0, 4, 41)
    mean = -0.25 * np.log10(t) - 1.0
    dims = ("model", "energy", "time")
    return xr.Dataset(
        {"mean_log10_mlce": (dims, mean[None, None]),
         "quantile_log10_mlce": (("model", "energy", "quantile", "time"),
                                 np.stack([mean - 0.1, mean + 0.1])[None, None]),
         "slope_log10_mlce": (dims, np.full((1, 1, t.size), -0.25))},
        coords={"model": ["kg"], "energy": [0.4], "quantile": [0.25, 0.75], "time": t})


def _reference_lines(stats) -> list[float]:
    """The dotted horizontal lines under <log10 Lambda>: the slope drawn as the reference."""
    ax = chaos_figure(stats).axes[1]
    return [line.get_ydata()[0] for line in ax.lines if line.get_linestyle() == ":"]


@pytest.mark.parametrize("published", [-0.3, -0.25])
def test_the_chaos_figure_draws_the_published_slope_the_study_names(published):
    stats = _statistics()
    stats["published_slope_mlce"] = ((), published)
    assert _reference_lines(stats) == [published]
    labels = [text.get_text() for text in chaos_figure(stats).axes[1].texts]
    assert f"{published:.3g}" in labels


def test_without_a_law_of_lambda_the_chaos_figure_draws_no_published_slope():
    assert _reference_lines(_statistics()) == []


def test_the_chaos_figure_draws_the_study_s_chaos_threshold():
    stats = _statistics()
    assert [line for line in chaos_figure(stats).axes[1].lines if line.get_linestyle() == "-."] == []
    stats.attrs["chaos_slope"] = -0.5
    ax = chaos_figure(stats).axes[1]
    assert [line.get_ydata()[0] for line in ax.lines if line.get_linestyle() == "-."] == [-0.5]
    assert "chaotic above -0.5" in [text.get_text() for text in ax.texts]


def test_the_fractions_figure_names_each_verdict_s_threshold():
    dims = ("model", "energy")
    one = np.full((1, 2), 0.5)
    stats = xr.Dataset({f"fraction_{flag}{end}": (dims, one) for flag in ("chaotic", "delocalized")
                        for end in ("", "_lower", "_upper")}, coords={"model": ["kg"], "energy": [0.4, 0.8]},
                       attrs={"chaos_slope": -0.5, "p_delocalized": 10.0})
    legend = [text.get_text() for text in fractions_figure(stats).axes[0].get_legend().get_texts()]
    assert legend == [r"chaotic ($\Lambda$) slope $> -0.5$", r"delocalized $P > 10$"]
