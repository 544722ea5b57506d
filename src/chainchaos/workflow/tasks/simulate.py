"""Tasks of workflow/rules/simulate.smk: the compiled kernels, and the scenes in batches, one file per scene."""

import sys
import time

from chainchaos.records.io import read_chain, write_netcdf, write_text
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
    """The scenes of one batch (rule simulate_scenes_<batch>) integrated together, each written
    to its own file (output keyed by the scene's name)."""
    scenes = params["scenes"]  # SceneParameters, built and checked when the workflow was read
    chain = read_chain(inputs["chain"])
    datasets = integrate_scenes(chain, scenes, ProgressReporter(params["batch"], scenes[0].t_final, every=10.0))
    for scene, ds in zip(scenes, datasets):
        write_netcdf(ds, outputs[scene.name])
