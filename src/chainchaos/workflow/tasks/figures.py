"""Tasks of workflow/rules/figures.smk: one job per figure of the paper draws each of its panels and
its composite (PDF and PNG) from the NetCDF files the panel table names (scenes, 'chain',
'ensemble'), so a job pays matplotlib's, mathtext's and the fonts' set-up once per figure."""

from pathlib import Path

from chainchaos.paper import panels


def figure_outputs(number: int) -> dict[str, str]:
    """The output keys of figure ``number``'s job, by what they hold: ``pdf``/``png`` of the
    composite and ``pdf_<panel>``/``png_<panel>`` of each panel (e.g. ``png_4d``)."""
    keys = {"": f"fig{number}", **{f"_{p}": f"fig{p}" for p in panels.panels_of_figure(number)}}
    return {f"{ext}{key}": f"{stem}.{ext}" for key, stem in keys.items() for ext in ("pdf", "png")}


def plot_figure(inputs, outputs, params, wildcards) -> None:
    """Figure ``params["number"]`` of the paper: each of its panels alone (panels.PANELS) and the
    composite laid out like the original (panels.LAYOUTS), every Dataset read once."""
    import xarray as xr

    # matplotlib: only in the plotting jobs
    from chainchaos.output.plotting.composite import plot_figure as composite
    from chainchaos.output.plotting.panels import plot_panel
    from chainchaos.output.plotting.style import save_figure

    number = int(params["number"])
    data = {name: xr.load_dataset(path) for name, path in inputs.items()}

    def save(fig, key: str) -> None:
        save_figure(fig, str(Path(outputs[f"pdf{key}"]).with_suffix("")), dpi=params["dpi"])

    for panel_id in panels.panels_of_figure(number):
        save(plot_panel(panel_id, data), f"_{panel_id}")
    save(composite(number, data), "")
