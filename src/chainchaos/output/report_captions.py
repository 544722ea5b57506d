"""The HTML report's captions and labels of the paper's figures, from the panel table (``paper``).

``snakemake --report`` renders the caption file of each file marked for the report
(reStructuredText with Jinja): the rules plot_panel and plot_figure pass a panel's or a figure's
caption from here as their param ``caption``, which workflow/report/panel.rst and figure.rst insert.

A caption says what the panel shows (``panels.KIND_TEXT``), what the paper reports about it
(``panels.FIGURES``) and the paper's statements the claims table judges on it
(``statements.statements_of_panel``). Labels (figure, panel, model, energy, what it shows) let a reader
pick a panel by model and energy in the report's tables.
"""

import re

from chainchaos.paper import panels, statements
from chainchaos.system.models import MODELS, model_label

#: The categories of the HTML report (snakemake --report), by kind of result; workflow/report/
#: workflow.rst links to them by name.
CATEGORIES = {
    "run": "This run",
    "figures": "Paper figures",
    "claims": "Claims",
    "scan": "Energy scan and disorder statistics",
    "search": "Realization search",
    "numerics": "Numerical accuracy",
    "indicators": "Chaos indicators",
    "studies": "Studies",
}

_MATH = re.compile(r"\$([^$]+)\$")


def rst(text: str) -> str:
    """Text with LaTeX math in $...$ as reStructuredText: the math as :math: roles (an escaped
    space before a role glued to a word, as RST inline markup needs one)."""
    out = _MATH.sub(lambda m: rf":math:`{m.group(1)}`", text)
    return re.sub(r"(?<=[\w)])(:math:`)", r"\\ \1", out)


def figure_subcategory(number: int) -> str:
    """The report's subcategory of figure ``number``: its number and subject."""
    return f"Fig. {number}: {panels.FIGURES[number].title}"


def _models_and_energies(panel_ids) -> tuple[str, str]:
    scenes = [s for p in panel_ids for s in panels.PANELS[p].scenes]
    if not scenes:
        return "linear modes", "-"
    models = [model_label(m) for m in MODELS if any(s.model == m for s in scenes)]
    energies = sorted({s.energy for s in scenes})
    return ", ".join(models), ", ".join(f"{e:g}" for e in energies)


def panel_labels(panel_id: str) -> dict[str, str]:
    model, energy = _models_and_energies([panel_id])
    return {"figure": f"Fig. {panel_id[:-1]}", "panel": f"({panel_id[-1]})", "model": model,
            "energy H": energy, "shows": panels.KIND_TEXT[panels.PANELS[panel_id].kind][0]}


def figure_labels(number: int) -> dict[str, str]:
    model, energy = _models_and_energies(panels.panels_of_figure(number))
    return {"figure": f"Fig. {number}", "panel": "all (composite)", "model": model, "energy H": energy,
            "shows": panels.FIGURES[number].title}


def _scenes_text(panel_ids) -> str:
    scenes = sorted({s for p in panel_ids for s in panels.PANELS[p].scenes},
                    key=lambda s: (list(MODELS).index(s.model), s.energy))
    by_model = {}
    for s in scenes:
        by_model.setdefault(model_label(s.model), []).append(f"{s.energy:g}")
    return "; ".join(f"{model} chain, :math:`H = {', '.join(es)}`" for model, es in by_model.items())


def _reports_of_panel(panel_id: str) -> list[str]:
    figure = panels.FIGURES[int(panel_id[:-1])]
    return [text for letters, text in figure.reports.items() if panel_id[-1] in letters]


def _statement_lines(shown) -> list[str]:
    if not shown:
        return []
    return ["", "**Statements the claims table judges on this run** (category *Claims*):", ""] + [
        f"- {rst(s.text)}" for s in shown]


def panel_caption(panel_id: str) -> str:
    """The caption of one panel (reStructuredText)."""
    panel = panels.PANELS[panel_id]
    number = int(panel_id[:-1])
    head = f"**Fig. {number}({panel_id[-1]})** of the paper"
    scenes = _scenes_text([panel_id])
    lines = [f"{head}: {scenes}." if scenes else f"{head}.", "",
             f"**Shows** {rst(panels.KIND_TEXT[panel.kind][1])}.", "",
             f"**The paper reports** {' '.join(rst(t) for t in _reports_of_panel(panel_id))}"]
    lines += _statement_lines(statements.statements_of_panel(panel_id))
    return "\n".join(lines) + "\n"


def figure_caption(number: int) -> str:
    """The caption of composite figure ``number`` (reStructuredText)."""
    ids = panels.panels_of_figure(number)
    figure = panels.FIGURES[number]
    scenes = _scenes_text(ids)
    lines = [f"**Fig. {number}** of the paper ({figure.title})." + (f" Scenes: {scenes}." if scenes else ""),
             "", "**Panels**", ""]
    by_kind: dict[str, list[str]] = {}
    for p in ids:
        by_kind.setdefault(panels.PANELS[p].kind, []).append(p[-1])
    lines += [f"- *({', '.join(letters)})* {rst(panels.KIND_TEXT[kind][1])}" for kind, letters in by_kind.items()]
    lines += ["", "**The paper reports**", ""]
    lines += [f"- *({', '.join(letters)})* {rst(text)}" for letters, text in figure.reports.items()]
    shown = [s for s in statements.STATEMENTS if any(p in ids for p in statements.statement_panels(s))]
    lines += _statement_lines(shown)
    return "\n".join(lines) + "\n"
