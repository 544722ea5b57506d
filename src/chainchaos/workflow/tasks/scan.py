"""Tasks of workflow/rules/scan.smk: the energy scan and the disorder statistics (whose groups of
orbits are those of their studies, workflow/rules/study.smk) merged onto their grids, their
figures and the threshold table."""

import sys
from pathlib import Path

import xarray as xr

from chainchaos.records import kept
from chainchaos.records.io import read_chain, write_netcdf, write_text
from chainchaos.paper import thresholds
from chainchaos.studies.scan import merge


def _write_merged(kind: str, ds: xr.Dataset, groups: list, out) -> None:
    """The merged Dataset, with the groups' mean wall time per trajectory."""
    seconds = [g.attrs["seconds_per_orbit"] for g in groups if "seconds_per_orbit" in g.attrs]
    if seconds:
        ds.attrs["mean_seconds_per_trajectory"] = float(sum(seconds) / len(seconds))
    print(f"{kind}: merged {len(groups)} groups, {int((ds['valid'] == 1).sum())} valid runs", file=sys.stderr)
    write_netcdf(ds, out)


def merge_energy_scan(inputs, outputs, params, wildcards) -> None:
    """The energy scan's group files on the (model, energy) grid."""
    groups = merge.scan_groups([xr.load_dataset(f) for f in inputs["groups"]])
    ds = merge.merge_energy_scan(groups, params["scan"], read_chain(inputs["chain"]))
    _write_merged("energy_scan", ds, groups, outputs["merged"])


def merge_disorder(inputs, outputs, params, wildcards) -> None:
    """The disorder statistics' group files on the (model, realization, energy) grid, or the
    archived full disorder statistics (``scan.disorder.archive``) as they are."""
    if "archive" in inputs.keys():
        kept.check_data(inputs["archive"], "snakemake --cores 2 keep --config keep=disorder_full")
        ds = xr.load_dataset(inputs["archive"])
        # where the numbers come from (ACDD's `source` names the software on every file)
        ds.attrs["kept_file"] = f"{inputs['archive']} (the archived full disorder statistics, snakemake keep --config keep=disorder_full)"
        print(f"disorder: {inputs['archive']}, {ds.sizes['realization']} realizations x {ds.sizes['energy']} "
              f"energies", file=sys.stderr)
        write_netcdf(ds, outputs["merged"])
        return
    groups = merge.scan_groups([xr.load_dataset(f) for f in inputs["groups"]])
    _write_merged("disorder", merge.merge_disorder(groups, params["scan"]), groups, outputs["merged"])


def plot_energy_scan(inputs, outputs, params, wildcards) -> None:
    """The energy-scan figure (PDF and PNG)."""
    from chainchaos.output.plotting.style import (
        save_figure,  # matplotlib: only in the plotting jobs
    )
    from chainchaos.output.plotting import scan as scan_plots

    fig = scan_plots.energy_scan_figure(xr.load_dataset(inputs["data"]))
    save_figure(fig, Path(outputs["pdf"]).with_suffix(""), dpi=params["dpi"])


def plot_disorder_statistics(inputs, outputs, params, wildcards) -> None:
    """The disorder-statistics figure (PDF and PNG)."""
    from chainchaos.output.plotting.style import (
        save_figure,  # matplotlib: only in the plotting jobs
    )
    from chainchaos.output.plotting import scan as scan_plots

    fig = scan_plots.disorder_figure(xr.load_dataset(inputs["data"]))
    save_figure(fig, Path(outputs["pdf"]).with_suffix(""), dpi=params["dpi"])


def scan_thresholds(inputs, outputs, params, wildcards) -> None:
    """The energies where the chain delocalizes and where it is chaotic (CSV and LaTeX table)."""
    ds = xr.load_dataset(inputs["data"])
    rows = thresholds.thresholds_table(ds)
    write_text(thresholds.thresholds_csv(rows, ds), outputs["csv"])
    write_text(thresholds.thresholds_tex(rows, ds), outputs["tex"])
