"""Tasks of workflow/rules/indicators.smk: the Lyapunov spectra of chosen scenes and their figure."""

import sys
from pathlib import Path

import xarray as xr

from chainchaos.paper import statements
from chainchaos.records.io import read_chain, write_netcdf
from chainchaos.run.orbits import OrbitSettings
from chainchaos.run.progress import OrbitProgress
from chainchaos.studies.indicators.spectra import scene_spectra


def lyapunov_spectrum(inputs, outputs, params, wildcards) -> None:
    """One scene's Lyapunov spectrum over its perturbed orbits."""
    block = params["spectra"]
    scene = statements.statement_scenes()[wildcards["scene"]]
    settings = OrbitSettings.from_config({**block["settings"], "exponents": 0})
    ds = scene_spectra(read_chain(inputs["chain"]), scene.model, scene.energy, int(params["site"]), settings,
                       int(block["lanes"]), OrbitProgress(f"spectrum {wildcards['scene']}"))
    ds.attrs["scene"] = wildcards["scene"]
    print(f"{wildcards['scene']}: lambda_1 = {float(ds['spectrum_final'][0]):.4g}, h_KS = "
          f"{float(ds['ks_entropy'].isel(time=-1).median()):.4g}", file=sys.stderr)
    write_netcdf(ds, outputs["result"])


def plot_lyapunov_spectra(inputs, outputs, params, wildcards) -> None:
    """The figure of the spectra (PDF and PNG)."""
    from chainchaos.output.plotting.style import (
        save_figure,  # matplotlib: only in the plotting jobs
    )
    from chainchaos.output.plotting.indicators import spectra_figure

    fig = spectra_figure([xr.load_dataset(f) for f in inputs["spectra"]])
    save_figure(fig, Path(outputs["pdf"]).with_suffix(""), dpi=params["dpi"])
