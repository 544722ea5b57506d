# The scenes, integrated in batches of those that share their settings (one SIMD block each), each
# computing only the observables its panels use, then one file per scene.


import os

from chainchaos.engine.cache import kernel_sources
from chainchaos.system.models import MODELS


wildcard_constraints:
    scene="|".join(re.escape(name) for name in SCENES),
    batch="|".join(re.escape(name) for name in SCENE_BATCHES),
    model="|".join(re.escape(name) for name in MODELS),


rule compile_kernels:
    """Compile one model's Numba kernels once into the on-disk cache before the simulations,
    scans and the search fan out (one job per model: they compile side by side). An edit to a
    kernel's source reruns it, and every integration after it."""
    input:
        sources=[os.path.relpath(path) for path in kernel_sources()],
    output:
        flag=result("kernels", "{model}.txt"),
    log:
        log_file("compile_kernels", "{model}"),
    benchmark:
        benchmark_file("compile_kernels", "{model}")
    priority: 20  # every integration waits for it: before the plots that need no kernels
    resources:
        mem_mb=2000,
        runtime=15,
    script:
        "../scripts/compile_kernels.py"


rule simulate_scenes:
    """The scenes of one batch (those sharing their integration settings, one SIMD block of the
    batch engine) integrated together; every lane's numbers are those of its scene alone."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        batch=temp(result("scenes", "batches", "{batch}.nc")),
    priority: 5  # the longest jobs: before the many short scan and plot jobs, so the figures do not wait
    params:
        scenes=lambda wildcards: [SCENE_PARAMETERS[name] for name in SCENE_BATCHES[wildcards.batch]],
    log:
        log_file("simulate_scenes", "{batch}"),
    benchmark:
        benchmark_file("simulate_scenes", "{batch}")
    resources:
        mem_mb=1000,
        runtime=60,  # paper scale: 2e8 steps of one SIMD block
    script:
        "../scripts/simulate_scenes.py"


rule simulate_scene:
    """One scene's file, from its batch."""
    input:
        batch=lambda wildcards: result("scenes", "batches", f"{SCENE_BATCH[wildcards.scene]}.nc"),
    output:
        scene=result("scenes", "{scene}.nc"),
    priority: 5
    log:
        log_file("simulate_scene", "{scene}"),
    benchmark:
        benchmark_file("simulate_scene", "{scene}")
    script:
        "../scripts/simulate_scene.py"
