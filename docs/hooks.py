"""MkDocs hooks of the documentation site (mkdocs.yml: ``hooks``).

- Pages generated at build time, so that they cannot go stale: a page holding the line
  ``<!-- generated: NAME -->`` gets the text of ``GENERATORS[NAME]`` in its place: the config keys
  and the study keys (``chainchaos.workflow.config_docs.render``, the text of config/README.md and
  studies/README.md), the command line (the ``chainchaos`` argparse parser) and the measured
  performance (every record in benchmarks/results/, written by benchmarks/record.py).
- The Sphinx roles of the package's numpydoc docstrings (``:func:`random_chain```,
  ``:class:`~chainchaos.run.settings.RunSettings```), which mkdocstrings leaves as text, are shown
  as the code they mark (``~``: the last name only, as Sphinx shows it).
- An executed example that raises fails the build, strict or not: markdown-exec logs the
  traceback as a warning (which ``strict: true`` already turns into a failure); this hook collects
  those warnings and raises after the build, naming the pages.
"""

from __future__ import annotations

import json
import logging
import os
import re
from pathlib import Path

from mkdocs.exceptions import PluginError

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"
MARKER = re.compile(r"^<!-- generated: ([a-z_]+) -->$", re.MULTILINE)
EXEC_FAILURE = "exited with errors"
#: A Sphinx role of a docstring as mkdocstrings renders it: the role's name, then its target as code.
ROLE = re.compile(r":(?:py:)?(?:func|class|meth|attr|data|const|exc|mod|obj):<code>(~?)([^<]*)</code>")


# ---------------------------------------------------------------- generated pages


def _drop_title(text: str) -> str:
    """The generated README's text without its first-level title (the page has its own)."""
    lines = text.splitlines()
    return "\n".join(lines[1:] if lines and lines[0].startswith("# ") else lines).strip() + "\n"


def config_keys() -> str:
    from chainchaos.workflow import config_docs as cd

    return _drop_title(cd.render(cd.config_schema(own_models=False), cd.HEADER))


def study_keys() -> str:
    from chainchaos.workflow import config_docs as cd

    return _drop_title(cd.render(cd.load_schema(cd.STUDY_SCHEMA, own_models=False), cd.STUDY_HEADER))


def _cell(text) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def _option_rows(parser) -> list[str]:
    import argparse

    rows = ["| option | default | description |", "| --- | --- | --- |"]
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        if action.option_strings:
            metavar = "" if action.nargs == 0 else " " + (action.metavar or action.dest.upper())
            name = ", ".join(f"`{o}{metavar}`" for o in action.option_strings)
        else:
            name = f"`{action.metavar or action.dest}`"
        default = action.default
        shown = "" if default in (None, False, argparse.SUPPRESS) or action.nargs == 0 else f"`{default}`"
        if action.required:
            shown = "required"
        text = action.help or ""
        if action.choices and not text.startswith("one of"):
            text += ("; " if text else "") + "one of " + ", ".join(f"`{c}`" for c in action.choices)
        rows.append(f"| {name} | {_cell(shown)} | {_cell(text)} |")
    return rows


def cli() -> str:
    """Every command of ``chainchaos``: its usage and a table of its options, from the parser."""
    import argparse

    from chainchaos.workflow.cli import build_parser

    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = "100"  # argparse wraps usage lines to the terminal's width
    try:
        parser = build_parser()
        out = ["```text", parser.format_usage().strip(), "```", "", *_option_rows(parser), ""]
        sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        helps = {choice.dest: choice.help for choice in sub._choices_actions}
        for name, command in sub.choices.items():
            out += [f"## `chainchaos {name}`", "", _cell(helps.get(name, "")) + ".", ""]
            if command.description:
                out += [command.description.strip(), ""]
            out += ["```text", command.format_usage().strip(), "```", "", *_option_rows(command), ""]
            if command.epilog:
                out += [command.epilog.strip(), ""]
        return "\n".join(out)
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


def records(folder: Path = RESULTS) -> list[dict]:
    """The benchmark records of ``folder``, newest first."""
    found = [json.loads(path.read_text()) | {"file": path.name} for path in sorted(folder.glob("*.json"))]
    return sorted(found, key=lambda r: r["date"], reverse=True)


def _number(value) -> str:
    if isinstance(value, bool) or not isinstance(value, float):
        return str(value)
    return f"{value:.4g}"


def render_record(record: dict, level: str = "###") -> str:
    cpu = record["cpu"]
    load = record.get("load_average_1min", {})
    state = " (the package's sources differed from it)" if record.get("sources_differ_from_commit") else ""
    lines = [
        f"{level} {record.get('title', record['benchmark'])}",
        "",
        f"- **benchmark**: `{record['command']}` (record `benchmarks/results/{record['file']}`)",
        f"- **date**: {record['date']}; **commit**: `{record['commit'][:12]}`{state}",
        (f"- **CPU**: {cpu.get('model_name') or 'unknown'}, {cpu.get('cpus', '?')} CPUs; vector extensions "
         f"{cpu.get('vector_extensions') or 'unknown'}; Numba target {cpu.get('numba_target', '?')}, "
         f"SIMD width {cpu.get('simd_width_doubles', '?')} doubles"
         + (f", square root {cpu['square_root']}" if "square_root" in cpu else "")),
        (f"- **load**: 1-minute load average {load.get('before', '?')} before, {load.get('after', '?')} after"
         + (f"; CPUs busy with other work at the start: {record['busy_share_before']:.0%}"
            if record.get("busy_share_before") is not None else "")
         + ("; **measured on a loaded machine**" if record.get("loaded_machine") else "")),
    ]
    if record.get("note"):
        lines.append(f"- **note**: {record['note']}")
    if record.get("parameters"):
        lines.append("- **parameters**: " + ", ".join(f"{k} = {_number(v)}" for k, v in record["parameters"].items()))
    columns = record.get("columns") or [{"key": k, "label": k} for k in record["rows"][0]]
    lines += ["", "| " + " | ".join(_cell(c["label"]) for c in columns) + " |",
              "|" + "|".join(" --- " for _ in columns) + "|"]
    lines += ["| " + " | ".join(_number(row.get(c["key"], "")) for c in columns) + " |" for row in record["rows"]]
    return "\n".join(lines) + "\n"


def performance(folder: Path = RESULTS) -> str:
    """The newest record of each measurement (a benchmark, its title and its label: the quick and
    the paper scale are two), then the earlier records, each as a table."""
    found = records(folder)
    if not found:
        return "No benchmark record yet: run `python benchmarks/record.py --help`.\n"
    current, earlier, seen = [], [], set()
    for record in found:
        key = (record["benchmark"], record.get("title"), record.get("label"))  # quick and paper scale
        (earlier if key in seen else current).append(record)
        seen.add(key)
    out = ["## Current measurements", ""] + [render_record(r) for r in current]
    if earlier:
        out += ["## Earlier records", ""] + [render_record(r) for r in earlier]
    return "\n".join(out)


GENERATORS = {"config_keys": config_keys, "study_keys": study_keys, "cli": cli, "performance": performance}


def on_page_markdown(markdown: str, page, config, files) -> str:
    _page_start[0] = len(_failures.messages)  # the page's examples run after this, before on_page_content
    def replace(match: re.Match) -> str:
        name = match.group(1)
        if name not in GENERATORS:
            raise PluginError(f"{page.file.src_uri}: no generator {name!r}; known: {sorted(GENERATORS)}")
        return GENERATORS[name]()

    return MARKER.sub(replace, markdown)


# ---------------------------------------------------------------- failing examples


class _ExecFailures(logging.Handler):
    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        message = record.getMessage()
        if EXEC_FAILURE in message:
            self.messages.append(message)


_failures = _ExecFailures()
_page_start = [0]


def on_startup(command, dirty) -> None:
    logging.getLogger("mkdocs.plugins.markdown_exec").addHandler(_failures)


def on_pre_build(config) -> None:
    logger = logging.getLogger("mkdocs.plugins.markdown_exec")
    if _failures not in logger.handlers:
        logger.addHandler(_failures)
    _failures.messages.clear()


def plain_roles(html: str) -> str:
    """The page's Sphinx roles (:data:`ROLE`) as the code they mark."""
    return ROLE.sub(lambda m: f"<code>{m.group(2).rsplit('.', 1)[-1] if m.group(1) else m.group(2)}</code>", html)


def on_page_content(html: str, page, config, files):
    for i in range(_page_start[0], len(_failures.messages)):
        _failures.messages[i] = f"{page.file.src_uri}: {_failures.messages[i]}"
    return plain_roles(html)


def on_post_build(config) -> None:
    if _failures.messages:
        raise PluginError(f"{len(_failures.messages)} executed example(s) raised:\n\n" + "\n\n".join(_failures.messages))
