# One simulation per scene, each computing only the observables its panels use.


from chainchaos._numba_cache import kernel_sources


wildcard_constraints:
    scene="|".join(re.escape(name) for name in SCENES),


rule compile_kernels:
    """Compile the Numba kernels once into the on-disk cache before the simulations fan out.
    An edit to a kernel's source reruns it, and so the scenes."""
    input:
        sources=[str(path) for path in kernel_sources()],
    output:
        flag=result("kernels_compiled.txt"),
    log:
        log_file("compile_kernels"),
    benchmark:
        benchmark_file("compile_kernels")
    script:
        "../scripts/compile_kernels.py"


rule simulate_scene:
    input:
        chain=result("chain", "chain.nc"),
        kernels=result("kernels_compiled.txt"),
    output:
        scene=result("scenes", "{scene}.nc"),
    priority: 5  # 1-1.5 min each: before the many short scan and plot jobs, so the figures do not wait
    params:
        scene=lambda wildcards: scene_parameters(wildcards.scene),
    log:
        log_file("simulate_scene", "{scene}"),
    benchmark:
        benchmark_file("simulate_scene", "{scene}")
    resources:
        mem_mb=1000,
        runtime=60,  # paper scale: 2e8 steps, ~1-3 CPU-minutes
    script:
        "../scripts/simulate_scene.py"
