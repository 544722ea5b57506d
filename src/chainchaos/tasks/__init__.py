"""One function per workflow rule: what the rule's script runs, with its inputs, outputs and params.

Every script in workflow/scripts is two lines (``from chainchaos.tasks import run_rule;
run_rule(snakemake)``), named like its rule: :func:`run_rule` sends stderr to the rule's log and
calls ``TASKS[rule]``, a function ``rule(inputs, outputs, params, wildcards)`` of dicts. The task of
a rule in ``workflow/rules/X.smk`` lives in ``chainchaos.tasks.X``. A task reads its inputs, calls
the package and writes its outputs atomically (``write_netcdf``, ``write_text``,
``atomic_output``); the physics is elsewhere. The ``chainchaos`` command is the command line.
"""

import contextlib
import sys
import traceback

from chainchaos.manuscript import BuildError
from chainchaos.tasks import chain, figures, manuscript, numerics, scan, search, simulate

#: The task modules, one per rule file of the workflow (workflow/rules/<name>.smk).
FAMILIES = (search, chain, simulate, scan, numerics, figures, manuscript)

TASKS = {task.__name__: task for family in FAMILIES for task in family.TASKS}

#: Errors whose message tells the reader what to do (install TeX, ...): shown without a traceback.
READER_ERRORS = (BuildError,)


def run_rule(smk) -> None:
    """Run ``TASKS[smk.rule]`` with stderr in the rule's log (the first ``log:`` file).

    A failure's traceback goes to the log, which Snakemake shows for a failed job; a
    :data:`READER_ERRORS` error ends the job with its message alone (exit status 1).
    """
    task = TASKS[smk.rule]
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
