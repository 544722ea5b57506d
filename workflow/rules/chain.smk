# Disorder statistics (Fig. 1a) and the chosen realization.


rule compute_ensemble:
    output:
        stats=result("ensemble", "participation_stats.nc"),
    params:
        ensemble=config["ensemble"],
        N=config["chain"]["N"],
    log:
        log_file("compute_ensemble"),
    benchmark:
        benchmark_file("compute_ensemble")
    script:
        "../scripts/compute_ensemble.py"


rule select_chain:
    """The chain file of the realization the search chose (workflow/rules/search.smk): the kept
    full search's when config search.archive names it, else this run's."""
    input:
        **SEARCH_INPUTS,
    output:
        chain=result("chain", "chain.nc"),
    params:
        chain=config["chain"],
    log:
        log_file("select_chain"),
    benchmark:
        benchmark_file("select_chain")
    script:
        "../scripts/select_chain.py"
