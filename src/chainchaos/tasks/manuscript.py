"""Tasks of workflow/rules/manuscript.smk: the paper's claims measured on the results, and the
manuscript built from them (chainchaos.manuscript)."""

from chainchaos import manuscript


def evaluate_claims(inputs, outputs, params, wildcards) -> None:
    """Measure the paper's claims on the results: claims.csv, claims_table.tex, claims_notes.tex,
    scenes_table.tex, search_table.tex and macros.tex (every number the manuscript prints, as \\cc{key})."""
    from chainchaos.claims.task import evaluate

    evaluate(inputs, outputs, params)


def build_manuscript(inputs, outputs, params, wildcards) -> None:
    """latexmk in the build directory on a copy of manuscript/ms.tex and of its inputs; a
    :class:`~chainchaos.errors.BuildError` (TeX missing, a LaTeX error) names what to do."""
    figures = {k: v for k, v in inputs.items() if k.startswith("fig")}
    numerics = {k[len("numerics_"):]: v for k, v in inputs.items() if k.startswith("numerics_")}
    manuscript.build(inputs["tex"], {k: inputs[k] for k in manuscript.GENERATED}, figures, numerics, outputs["pdf"],
                     params["build_dir"])


TASKS = (evaluate_claims, build_manuscript)
