"""Tasks of workflow/rules/figures.smk: each panel of the paper and the composite figures (PDF and
PNG), drawn from the NetCDF files the panel table names (scenes, 'chain', 'ensemble')."""

from pathlib import Path

import xarray as xr


def _draw(draw, key, inputs: dict, outputs: dict, params: dict) -> None:
    from chainchaos.output.plotting import save_figure  # matplotlib: only in the plotting jobs

    data = {name: xr.load_dataset(path) for name, path in inputs.items()}
    save_figure(draw(key, data), str(Path(outputs["pdf"]).with_suffix("")), dpi=params["dpi"])


def plot_panel(inputs, outputs, params, wildcards) -> None:
    """One panel of the paper (panels.PANELS)."""
    from chainchaos.output import plotting

    _draw(plotting.plot_panel, wildcards["panel"], inputs, outputs, params)


def plot_figure(inputs, outputs, params, wildcards) -> None:
    """A composite figure of the paper, laid out like the original (panels.LAYOUTS)."""
    from chainchaos.output import plotting

    _draw(plotting.plot_figure, int(wildcards["number"]), inputs, outputs, params)


TASKS = (plot_panel, plot_figure)
