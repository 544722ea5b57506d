# The scenes, one job each (plan.scene_run), each computing only the observables its panels use.

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


rule simulate_scene:
    """One scene of the paper on the chosen chain, on the single-trajectory engine (the batch
    engine where it needs several deviation vectors)."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=lambda wildcards: kernel_flags([SCENES[wildcards.scene].model]),
    output:
        scene=scene_file("{scene}"),
    priority: 5  # the longest jobs: before the many short scan and plot jobs, so the figures do not wait
    params:
        scene=lambda wildcards: plan.scene_run(config, wildcards.scene),
    log:
        log_file("simulate_scene", "{scene}"),
    benchmark:
        benchmark_file("simulate_scene", "{scene}")
    resources:
        mem_mb=1000,
        runtime=60,  # paper scale: 2e8 steps of one trajectory
    script:
        "../scripts/simulate_scene.py"
