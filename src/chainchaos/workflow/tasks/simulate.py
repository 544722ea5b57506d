"""Tasks of workflow/rules/simulate.smk: the compiled kernels, and the scenes, one file each."""

import sys
import time

from chainchaos.records.io import read_chain, write_netcdf, write_text
from chainchaos.run.progress import ProgressReporter
from chainchaos.run.scenes import SceneParameters, simulate
from chainchaos.run.warmup import warm_up


def compile_kernels(inputs, outputs, params, wildcards) -> None:
    """Compile one model's Numba kernels into the project's on-disk cache (tiny runs of it)."""
    start = time.perf_counter()
    cache = warm_up([wildcards["model"]])
    message = f"kernels compiled or loaded from {cache} in {time.perf_counter() - start:.1f} s"
    print(message, file=sys.stderr)
    write_text(message + "\n", outputs["flag"])


def simulate_scene(inputs, outputs, params, wildcards) -> None:
    """One scene of the paper (rule simulate_scene), written to its file."""
    scene = SceneParameters(**params["scene"])  # its fields, checked when the workflow was read
    chain = read_chain(inputs["chain"])
    write_netcdf(simulate(chain, scene, ProgressReporter(scene.name, scene.t_final, every=10.0)), outputs["scene"])
