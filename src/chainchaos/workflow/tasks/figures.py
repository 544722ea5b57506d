"""Tasks of workflow/rules/figures.smk: a panel of the paper, or a composite figure laid out like the
original, drawn (PDF and PNG) from the NetCDF files the panel table names (scenes, 'chain',
'ensemble')."""

from pathlib import Path


def _draw(inputs, outputs, params, figure) -> None:
    import xarray as xr

    from chainchaos.output.plotting.style import save_figure  # matplotlib: only in the plotting jobs

    data = {name: xr.load_dataset(path) for name, path in inputs.items()}
    save_figure(figure(data), str(Path(outputs["pdf"]).with_suffix("")), dpi=params["dpi"])


def plot_panel(inputs, outputs, params, wildcards) -> None:
    """Panel ``wildcards["panel"]`` of the paper (panels.PANELS), alone."""
    from chainchaos.output.plotting.panels import plot_panel as panel

    _draw(inputs, outputs, params, lambda data: panel(wildcards["panel"], data))


def plot_figure(inputs, outputs, params, wildcards) -> None:
    """Figure ``wildcards["number"]`` of the paper, its panels laid out like the original
    (panels.LAYOUTS)."""
    from chainchaos.output.plotting.composite import plot_figure as composite

    _draw(inputs, outputs, params, lambda data: composite(int(wildcards["number"]), data))
