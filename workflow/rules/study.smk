# Studies of one's own: a file studies/<name>.yaml (keys: studies/README.md), run by
#
#   snakemake --cores 2 study --config study=<name>
#
# in resumable jobs of `jobs.orbits_per_job` orbits (study_group), merged into one NetCDF file
# per model and energy holding every realization (study_scene) and the ensemble statistics
# and its power laws (study_statistics), drawn as the study's figures (plot_study, one job each) and shown
# in the HTML report (category "Studies"). Nothing of the paper (search, claims, manuscript) runs.


wildcard_constraints:
    group=r"\d+",
    figure=r"[a-z_]+",
    study=r"[A-Za-z0-9][A-Za-z0-9_.-]*",


# Seconds of work each: on a cluster they run on the submitting host (as does plot_study).
localrules:
    study,
    study_scene,
    study_statistics,


rule study_group:
    """One job's orbits of a study, integrated on the batch engine."""
    input:
        unpack(study_chain),
        kernels=lambda wildcards: kernel_flags(study_of(wildcards.study).models),
    output:
        group=result("studies", "{study}", "groups", "{group}.nc"),
    params:
        spec=lambda wildcards: plan.group_spec(study_of(wildcards.study)),
    log:
        log_file("study_group", "{study}-{group}"),
    benchmark:
        benchmark_file("study_group", "{study}-{group}")
    resources:
        mem_mb=2000,
        runtime=lambda wildcards: plan.study_minutes(study_of(wildcards.study), US_PER_STEP),
    script:
        "../scripts/study_group.py"


rule study_scene:
    """One model and energy of a study: every realization and lane, and their statistics."""
    input:
        groups=lambda wildcards: study_group_files(wildcards.study),
    output:
        scene=result("studies", "{study}", "{model}_H{energy}.nc"),
    params:
        spec=lambda wildcards: plan.study_spec(study_of(wildcards.study)),
        check=study_group_check,
    log:
        log_file("study_scene", "{study}-{model}_H{energy}"),
    benchmark:
        benchmark_file("study_scene", "{study}-{model}_H{energy}")
    script:
        "../scripts/study_scene.py"


rule study_statistics:
    """The ensemble statistics of a study on its (model, energy) grid, and the power laws it names
    (key laws) fitted to its ensemble means: both read every group, so one job reads them once."""
    input:
        groups=lambda wildcards: study_group_files(wildcards.study),
    output:
        statistics=result("studies", "{study}", "statistics.nc"),
        laws=result("studies", "{study}", "laws.nc"),
    params:
        spec=lambda wildcards: plan.study_spec(study_of(wildcards.study)),
        check=study_group_check,
    log:
        log_file("study_statistics", "{study}"),
    benchmark:
        benchmark_file("study_statistics", "{study}")
    script:
        "../scripts/study_statistics.py"


rule plot_study:
    """One figure of a study (key ``figures``; ``comparison`` with ``compare_with``)."""
    localrule: True
    input:
        unpack(study_figure_inputs),
    output:
        pdf=result("studies", "{study}", "figures", "{figure}.pdf"),
        png=report(
            result("studies", "{study}", "figures", "{figure}.png"),
            caption="../report/study.rst",
            category=REPORT_CATEGORIES["studies"],
            subcategory="{study}",
            labels={"study": "{study}", "figure": "{figure}"},
        ),
    params:
        models=lambda wildcards: plan.own_models(study_of(wildcards.study)),
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_study", "{study}-{figure}"),
    benchmark:
        benchmark_file("plot_study", "{study}-{figure}")
    script:
        "../scripts/plot_study.py"


rule study:
    """Everything of the study named by config `study` (--config study=<name>)."""
    input:
        lambda wildcards: plan.study_targets(
            study_of(named_study()), RESULTS, study_figure_names(named_study())
        ),
