# Numerical accuracy and stability of the integrators (issue 5), on the chosen chain:
# work precision of every scheme and of solve_ivp, observed orders, largest stable steps, the
# near-sonic-vacuum limit, long-time energy drift, FPUT with the Taylor sign of K4, and the
# energy error of the production step per scene. Settings: the `numerics` block of the config.

if "numerics" not in config:
    raise ValueError(
        "config lacks the `numerics` block that workflow/rules/numerics.smk reads "
        "(see config/config.yaml)"
    )

import re

NUMERICS = config["numerics"]
# The scheme of the production runs: advice, drift and the Taylor-sign probe measure that one.
NUMERICS_INTEGRATOR = NUMERICS.get("integrator") or config["simulation"]["integrator"]
# The work-precision cases by model, in the config's order: one job per model measures its cases
# (a case's runs take seconds at the quick scale, less than a job of its own costs).
WP_MODELS = {}
for case in NUMERICS["work_precision"]["cases"]:
    WP_MODELS.setdefault(case["model"], []).append((case["model"], float(case["energy"])))

NUMERICS_TARGETS = [
    result("figures", "work_precision.pdf"),
    result("figures", "work_precision.png"),
    result("figures", "stability.pdf"),
    result("figures", "stability.png"),
    result("tables", "work_precision.csv"),
    result("tables", "work_precision.tex"),
    result("tables", "work_precision_runs.csv"),
    result("tables", "stability.csv"),
    result("tables", "stability.tex"),
    result("tables", "step_advice.csv"),
    result("tables", "step_advice.tex"),
    result("numerics", "work_precision.nc"),
]


wildcard_constraints:
    wp_model="|".join(re.escape(m) for m in WP_MODELS),


rule numerics_work_precision_model:
    """Error against run time of every scheme and solve_ivp method for one model's cases."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=lambda wildcards: kernel_flags([wildcards.wp_model]),
    output:
        data=result("numerics", "work_precision", "{wp_model}.nc"),
    params:
        cases=lambda wildcards: WP_MODELS[wildcards.wp_model],
        settings={k: v for k, v in NUMERICS["work_precision"].items() if k != "cases"},
    priority: 5  # the head of a chain the manuscript waits for (merge, figure): first once the kernels are ready
    log:
        log_file("numerics_work_precision_model", "{wp_model}"),
    benchmark:
        benchmark_file("numerics_work_precision_model", "{wp_model}")
    script:
        "../scripts/numerics_work_precision_model.py"


rule numerics_work_precision:
    """All cases in one file (by model, each model's in the config's order), and the table of
    observed orders (CSV, LaTeX)."""
    input:
        models=[result("numerics", "work_precision", f"{m}.nc") for m in WP_MODELS],
    output:
        data=result("numerics", "work_precision.nc"),
        orders_csv=report(
            result("tables", "work_precision.csv"),
            caption="../report/work_precision_table.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "orders (CSV)", "shows": "observed orders of the schemes"},
        ),
        orders_tex=result("tables", "work_precision.tex"),
        runs_csv=report(
            result("tables", "work_precision_runs.csv"),
            caption="../report/work_precision_runs.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "work-precision runs (CSV)", "shows": "every run of the study"},
        ),
    log:
        log_file("numerics_work_precision"),
    benchmark:
        benchmark_file("numerics_work_precision")
    script:
        "../scripts/numerics_work_precision.py"


rule numerics_plot_work_precision:
    input:
        data=result("numerics", "work_precision.nc"),
    output:
        pdf=result("figures", "work_precision.pdf"),
        png=report(
            result("figures", "work_precision.png"),
            caption="../report/work_precision.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "work precision", "shows": "error against run time"},
        ),
    priority: 1  # the longest drawing jobs first: the short ones fill the end of a run
    log:
        log_file("numerics_plot_work_precision"),
    benchmark:
        benchmark_file("numerics_plot_work_precision")
    script:
        "../scripts/numerics_plot_work_precision.py"


rule numerics_stability:
    """Largest stable step of every scheme over alpha and H, and near the sonic vacuum."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        data=result("numerics", "stability.nc"),
    # the stability figure's inputs, which the manuscript waits for: among the first jobs once the
    # kernels are ready (run late, they and the figure were the quick scale's tail)
    priority: 5
    params:
        settings=NUMERICS["stability"],
    log:
        log_file("numerics_stability"),
    benchmark:
        benchmark_file("numerics_stability")
    script:
        "../scripts/numerics_stability.py"


rule numerics_energy_drift:
    """The long run: energy error of the production scheme and step up to t_final (progress in the log)."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        data=result("numerics", "energy_drift.nc"),
    # The longest single job of `all` at paper scale (one trajectory of 2e9 steps): started first,
    # it runs beside the rest instead of alone at the end (its time per machine: README).
    priority: 10
    params:
        settings=NUMERICS["drift"],
        integrator=NUMERICS_INTEGRATOR,
    log:
        log_file("numerics_energy_drift"),
    benchmark:
        benchmark_file("numerics_energy_drift")
    resources:
        mem_mb=1000,
        runtime=90,  # 2e9 steps of one trajectory, with room for a slow or busy node
    script:
        "../scripts/numerics_energy_drift.py"


rule numerics_taylor_sign:
    """FPUT with K4 < 0: bounded, escape stopped by the guard, or unreachable energy."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        data=result("numerics", "taylor_sign.nc"),
    priority: 5  # an input of the stability figure (numerics_stability)
    params:
        settings=NUMERICS["taylor"],
        integrator=NUMERICS_INTEGRATOR,
    log:
        log_file("numerics_taylor_sign"),
    benchmark:
        benchmark_file("numerics_taylor_sign")
    script:
        "../scripts/numerics_taylor_sign.py"


rule numerics_step_advice:
    """Energy error per scene at the production step and at larger ones."""
    input:
        chain=result("chain", "chain.nc"),
        kernels=kernel_flags(),
    output:
        data=result("numerics", "step_advice.nc"),
        csv=report(
            result("tables", "step_advice.csv"),
            caption="../report/step_advice.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "step advice (CSV)", "shows": "energy error per scene against step"},
        ),
        tex=result("tables", "step_advice.tex"),
    priority: 5  # an input of the stability figure (numerics_stability)
    params:
        settings=NUMERICS["advice"],
        scenes=[[s.model, float(s.energy)] for s in SCENES.values()],
        integrator=NUMERICS_INTEGRATOR,
        k4_sign=config["simulation"].get("k4_sign", 1),
    log:
        log_file("numerics_step_advice"),
    benchmark:
        benchmark_file("numerics_step_advice")
    script:
        "../scripts/numerics_step_advice.py"


rule numerics_plot_stability:
    input:
        stability=result("numerics", "stability.nc"),
        drift=result("numerics", "energy_drift.nc"),
        taylor=result("numerics", "taylor_sign.nc"),
        advice=result("numerics", "step_advice.nc"),
    output:
        pdf=result("figures", "stability.pdf"),
        png=report(
            result("figures", "stability.png"),
            caption="../report/stability.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "stability", "shows": "largest stable steps, drift, step advice"},
        ),
        csv=report(
            result("tables", "stability.csv"),
            caption="../report/stability_table.rst",
            category=REPORT_CATEGORIES["numerics"],
            labels={"result": "stable steps (CSV)", "shows": "largest stable step per case"},
        ),
        tex=result("tables", "stability.tex"),
    params:
        integrator=NUMERICS_INTEGRATOR,
    priority: 1  # the longest drawing jobs first: the short ones fill the end of a run
    log:
        log_file("numerics_plot_stability"),
    benchmark:
        benchmark_file("numerics_plot_stability")
    script:
        "../scripts/numerics_plot_stability.py"
