"""One function per workflow rule: what the rule's script runs, with its inputs, outputs and params.

Every script in workflow/scripts is two lines (``from chainchaos.workflow.tasks import run_rule;
run_rule(snakemake)``), named like its rule: :func:`run_rule` sends stderr to the rule's log and
calls the rule's task, a function ``rule(inputs, outputs, params, wildcards)`` of dicts. The task of
a rule in ``workflow/rules/X.smk`` lives in ``chainchaos.workflow.tasks.X`` (``TASKS``: all of them). A task
reads its inputs, calls the package and writes its outputs atomically (``write_netcdf``,
``write_text``, ``atomic_output``); the physics is elsewhere. The ``chainchaos`` command is the command line.
"""

import contextlib
import functools
import importlib
import re
import sys
import traceback
from pathlib import Path

from chainchaos.errors import BuildError

#: The task modules, one per rule file of the workflow (workflow/rules/<name>.smk).
FAMILIES = ("search", "chain", "simulate", "scan", "numerics", "indicators", "figures", "manuscript", "study")

#: Every module a job may call into: what the job server imports (``chainchaos.workflow.jobserver``).
MODULES = (__name__, *(f"{__name__}.{family}" for family in FAMILIES))


def family_tasks(family: str) -> dict:
    """The tasks of one task module, by rule name."""
    return {task.__name__: task for task in importlib.import_module(f"chainchaos.workflow.tasks.{family}").TASKS}


@functools.cache
def _all_tasks() -> dict:
    return {rule: task for family in FAMILIES for rule, task in family_tasks(family).items()}


def __getattr__(name):
    """``TASKS``, every task by rule name, imported on first use: a job imports only its own task
    module (a plotting job then loads no integrator, a simulation no plotting library)."""
    if name == "TASKS":
        return _all_tasks()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _task_name(rule: str, text: str) -> str | None:
    """The task of ``rule`` if the rule file ``text`` defines it: ``rule <rule>:``, or one rule
    of a loop, ``name: f"<task>_{...}"`` (plot_figure_4 of ``for number in FIGURES``)."""
    if re.search(rf"^rule {re.escape(rule)}:", text, re.M):
        return rule
    for task in re.findall(r'^\s+name:\n\s+f"(\w+)_\{\w+\}"$', text, re.M):
        if re.fullmatch(rf"{re.escape(task)}_\w+", rule):
            return task
    return None


def _family_and_task_name(smk) -> tuple[str | None, str]:
    """The task module (None: unknown) and the task name of the rule of a workflow script,
    without importing the module: from the rule file that defines the rule
    (``workflow/rules/<family>.smk``, beside the scripts' directory), or the rule's own name."""
    rule_files = Path(smk.scriptdir).parent / "rules" if getattr(smk, "scriptdir", None) else None
    if rule_files is not None and rule_files.is_dir():
        for path in sorted(rule_files.glob("*.smk")):
            if path.stem in FAMILIES and (name := _task_name(smk.rule, path.read_text())):
                return path.stem, name
    return None, smk.rule


def _task(family: str | None, name: str):
    """The task ``name`` of the task module ``family`` (:func:`_family_and_task_name`), or, without
    a workflow around it (family None), looked up among all tasks."""
    return family_tasks(family)[name] if family else _all_tasks()[name]


#: The tasks whose jobs the run's job server takes: those that read, reduce and draw. A job that
#: integrates orbits keeps its own process, as every job of a cluster run does: the
#: single-trajectory engine's speed depends on where its work buffer lands in memory (by up to a
#: half, docs/explanation/performance.md), which is the same in each fresh process of a run but
#: differs from one forked worker to the next; and the benchmark of a search's or a
#: study's job, whose CPU seconds are kept as the cost of an archive, measures only its own process.
SERVED_TASKS = frozenset({
    "beyond_the_paper", "build_manuscript", "compute_ensemble", "evaluate_claims", "keep_study_group",
    "merge_disorder", "merge_energy_scan", "numerics_plot_stability", "numerics_plot_work_precision",
    "numerics_work_precision", "plot_disorder_statistics", "plot_energy_scan", "plot_figure", "plot_lyapunov_spectra",
    "plot_search", "plot_study", "run_summary", "scan_thresholds", "select_chain", "study_scene", "study_statistics",
})

#: Errors whose message tells the reader what to do (install TeX, ...): shown without a traceback.
READER_ERRORS = (BuildError,)


def run_rule(smk) -> None:
    """Run ``TASKS[smk.rule]`` with stderr in the rule's log (the first ``log:`` file): in a
    worker of the run's job server (``chainchaos.workflow.jobserver``) if it has one and the task
    is one of :data:`SERVED_TASKS`, else here.

    A failure's traceback goes to the log, which Snakemake shows for a failed job; a
    :data:`READER_ERRORS` error ends the job with its message alone (exit status 1).
    """
    from chainchaos.workflow import jobserver

    family, name = _family_and_task_name(smk)
    status = jobserver.submit(__name__, "run_rule_here", smk, family, name) if name in SERVED_TASKS else None
    if status is None:
        run_rule_here(smk, family, name)
    elif status:
        raise SystemExit(status)


def run_rule_here(smk, family: str | None, name: str) -> None:
    """:func:`run_rule` in this process, with the task ``name`` of the module ``family`` that it
    found (:func:`_family_and_task_name`)."""
    task = _task(family, name)
    with open(smk.log[0], "w") as log, contextlib.redirect_stderr(log):
        try:
            task(dict(smk.input.items()), dict(smk.output.items()), dict(smk.params.items()),
                 dict(smk.wildcards.items()))
        except READER_ERRORS as error:
            message = f"{smk.rule}: {error}"
            print(message, file=sys.stderr)
            raise SystemExit(message) from None  # Python prints the message to the job's stderr
        except BaseException:
            traceback.print_exc()
            raise
