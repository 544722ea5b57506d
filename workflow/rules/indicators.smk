# Chaos indicators beyond the paper's Lambda (chainchaos.studies.indicators): the Lyapunov spectra
# of the scenes named in config `indicators.spectra.scenes`, on the chosen chain, each over an
# ensemble of perturbed orbits, and their figure.


rule lyapunov_spectrum:
    """The Lyapunov spectrum of one scene over its perturbed orbits (all 2N exponents)."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        result=result("indicators", "spectrum_{scene}.nc"),
    params:
        spectra=config["indicators"]["spectra"],
        site=config["simulation"]["excited_site"],
    log:
        log_file("lyapunov_spectrum", "{scene}"),
    benchmark:
        benchmark_file("lyapunov_spectrum", "{scene}")
    resources:
        mem_mb=1000,
        runtime=60,
    script:
        "../scripts/lyapunov_spectrum.py"


rule plot_lyapunov_spectra:
    input:
        spectra=list(SPECTRA_FILES.values()),
    output:
        pdf=result("figures", "lyapunov_spectra.pdf"),
        png=report(
            result("figures", "lyapunov_spectra.png"),
            caption="../report/lyapunov_spectra.rst",
            category=REPORT_CATEGORIES["indicators"],
            labels={
                "result": "Lyapunov spectra",
                "shows": "exponents against i/N, KS entropy against t",
            },
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_lyapunov_spectra"),
    benchmark:
        benchmark_file("plot_lyapunov_spectra")
    resources:
        mem_mb=2000,
        runtime=10,
    script:
        "../scripts/plot_lyapunov_spectra.py"
