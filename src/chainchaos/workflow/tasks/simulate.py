"""Tasks of workflow/rules/simulate.smk: the compiled kernels, the scene batches, one file per scene."""

import sys
import time

import xarray as xr

from chainchaos.output.io import atomic_output, read_chain, write_netcdf, write_text
from chainchaos.run.progress import ProgressReporter
from chainchaos.run.scenes import simulate_scenes as integrate_scenes
from chainchaos.run.warmup import warm_up


def compile_kernels(inputs, outputs, params, wildcards) -> None:
    """Compile one model's Numba kernels into the project's on-disk cache (tiny runs of it)."""
    start = time.perf_counter()
    cache = warm_up([wildcards["model"]])
    message = f"kernels compiled or loaded from {cache} in {time.perf_counter() - start:.1f} s"
    print(message, file=sys.stderr)
    write_text(message + "\n", outputs["flag"])


def simulate_scenes(inputs, outputs, params, wildcards) -> None:
    """The scenes of one batch integrated together; each scene's Dataset a group of one file."""
    scenes = params["scenes"]  # SceneParameters, built and checked when the workflow was read
    chain = read_chain(inputs["chain"])
    datasets = integrate_scenes(chain, scenes, ProgressReporter(wildcards["batch"], scenes[0].t_final, every=10.0))
    with atomic_output(outputs["batch"]) as tmp:
        for i, (scene, ds) in enumerate(zip(scenes, datasets)):
            ds.to_netcdf(tmp, mode="w" if i == 0 else "a", group=scene.name, engine="netcdf4")


def simulate_scene(inputs, outputs, params, wildcards) -> None:
    """One scene's file, taken from the batch it was integrated in."""
    with xr.open_dataset(inputs["batch"], group=wildcards["scene"], engine="netcdf4") as ds:
        write_netcdf(ds.load(), outputs["scene"])


TASKS = (compile_kernels, simulate_scenes, simulate_scene)
