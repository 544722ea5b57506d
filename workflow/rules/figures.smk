# One job per figure of the paper (rule plot_figure_<N>): it draws each of the figure's panels, one
# target per panel (results/figures/fig<N><x>.pdf|png: asking for one runs its figure's job), and
# the composite (results/figures/fig<N>.pdf|png), paying the plotting set-up once per figure.


for number in FIGURES:

    rule:
        name:
            f"plot_figure_{number}"
        input:
            **plan.figure_inputs(number, RESULTS),
        output:
            **figure_outputs(number),
        params:
            number=number,
            dpi=config["figures"]["dpi"],
        priority: 1  # the longest drawing jobs first: the short ones fill the end of a run
        log:
            log_file("plot_figure", f"fig{number}"),
        benchmark:
            benchmark_file("plot_figure", f"fig{number}")
        script:
            "../scripts/plot_figure.py"
