# One target per panel of the paper, and the composite figures.


wildcard_constraints:
    panel="|".join(panels.PANELS),
    number="|".join(str(n) for n in FIGURES),


rule plot_panel:
    input:
        unpack(lambda wildcards: panel_inputs(wildcards.panel)),
    output:
        pdf=result("figures", "fig{panel}.pdf"),
        png=report(
            result("figures", "fig{panel}.png"),
            caption="../report/panel.rst",
            category=REPORT_CATEGORIES["figures"],
            subcategory=lambda wildcards: figure_subcategory(int(wildcards.panel[:-1])),
            labels=lambda wildcards: panel_labels(wildcards.panel),
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_panel", "fig{panel}"),
    benchmark:
        benchmark_file("plot_panel", "fig{panel}")
    script:
        "../scripts/plot_panel.py"


rule plot_figure:
    input:
        unpack(lambda wildcards: figure_inputs(int(wildcards.number))),
    output:
        pdf=result("figures", "fig{number}.pdf"),
        png=report(
            result("figures", "fig{number}.png"),
            caption="../report/figure.rst",
            category=REPORT_CATEGORIES["figures"],
            subcategory=lambda wildcards: figure_subcategory(int(wildcards.number)),
            labels=lambda wildcards: figure_labels(int(wildcards.number)),
        ),
    params:
        dpi=config["figures"]["dpi"],
    log:
        log_file("plot_figure", "fig{number}"),
    benchmark:
        benchmark_file("plot_figure", "fig{number}")
    script:
        "../scripts/plot_figure.py"
