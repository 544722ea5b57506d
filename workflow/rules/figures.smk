# The paper's figures: one job per panel (results/figures/fig<N><x>.pdf|png, rule plot_panel) and
# one per composite laid out like the original (results/figures/fig<N>.pdf|png, rule plot_figure),
# each drawn from the NetCDF files the panel table names.


wildcard_constraints:
    panel="|".join(sorted(panels.PANELS)),
    number=r"\d+",


rule plot_panel:
    """One panel of the paper's figures."""
    input:
        unpack(lambda wildcards: plan.panel_inputs(wildcards.panel, RESULTS)),
    output:
        pdf=result("figures", "fig{panel}.pdf"),
        png=report(
            result("figures", "fig{panel}.png"),
            caption="../report/panel.rst",
            category=REPORT_CATEGORIES["figures"],
            subcategory=lambda wildcards: report_captions.figure_subcategory(
                int(wildcards.panel[:-1])
            ),
            labels=lambda wildcards: report_captions.panel_labels(wildcards.panel),
        ),
    params:
        dpi=config["figures"]["dpi"],
        caption=lambda wildcards: report_captions.panel_caption(wildcards.panel),
    log:
        log_file("plot_panel", "fig{panel}"),
    benchmark:
        benchmark_file("plot_panel", "fig{panel}")
    script:
        "../scripts/plot_panel.py"


rule plot_figure:
    """One figure of the paper: its panels laid out as in the original."""
    input:
        unpack(lambda wildcards: plan.figure_inputs(int(wildcards.number), RESULTS)),
    output:
        pdf=result("figures", "fig{number}.pdf"),
        png=report(
            result("figures", "fig{number}.png"),
            caption="../report/figure.rst",
            category=REPORT_CATEGORIES["figures"],
            subcategory=lambda wildcards: report_captions.figure_subcategory(
                int(wildcards.number)
            ),
            labels=lambda wildcards: report_captions.figure_labels(int(wildcards.number)),
        ),
    params:
        dpi=config["figures"]["dpi"],
        caption=lambda wildcards: report_captions.figure_caption(int(wildcards.number)),
    priority: 1  # the longest drawing jobs first: the short ones fill the end of a run
    log:
        log_file("plot_figure", "fig{number}"),
    benchmark:
        benchmark_file("plot_figure", "fig{number}")
    script:
        "../scripts/plot_figure.py"
