# The scenes, integrated in jobs of those that share their settings (plan.scene_jobs: a count of
# the config, the same on every CPU), each computing only the observables its panels use and
# written one file per scene.

import re

from chainchaos.system.models import MODELS


wildcard_constraints:
    scene="|".join(re.escape(name) for name in SCENES),
    model="|".join(re.escape(name) for name in MODELS),


rule compile_kernels:
    """Compile one model's Numba kernels once into the on-disk cache before the simulations,
    scans and the search fan out (one job per model, the paper's one after the other: the second
    loads what they share). An edit to a kernel's source reruns it, and every integration after
    it."""
    input:
        sources=kernel_inputs(),
        earlier=earlier_kernel_flags,
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


# One job per batch of scenes (rule simulate_scenes_<batch>), one target per scene.
for batch, batch_scenes in SCENE_JOBS.items():

    rule:
        name:
            f"simulate_scenes_{batch}"
        input:
            chain=result("chain", "chain.nc"),
            kernels=kernel_flags([batch_scenes[0].model]),
        output:
            **{scene.name: scene_file(scene.name) for scene in batch_scenes},
        priority: 5  # the longest jobs: before the many short scan and plot jobs, so the figures do not wait
        params:
            scenes=batch_scenes,
            batch=batch,
        log:
            log_file("simulate_scenes", batch),
        benchmark:
            benchmark_file("simulate_scenes", batch)
        resources:
            mem_mb=1000,
            runtime=60,  # paper scale: 2e8 steps of one SIMD block
        script:
            "../scripts/simulate_scenes.py"
