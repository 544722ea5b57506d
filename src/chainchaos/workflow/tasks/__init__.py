"""One function per workflow rule: what the rule's script runs, with its inputs, outputs and params.

Every script in workflow/scripts is named like its rule and names the function it runs::

    from chainchaos.workflow.tasks import run
    from chainchaos.workflow.tasks.chain import select_chain

    run(snakemake, select_chain)

:func:`run` sends stderr to the rule's log and calls the task, a function
``task(inputs, outputs, params, wildcards)`` of dicts. The task of a rule in
``workflow/rules/X.smk`` lives in ``chainchaos.workflow.tasks.X``. A task reads its inputs, calls
the package and writes its outputs atomically (``write_netcdf``, ``write_text``,
``atomic_output``); the physics is elsewhere. The ``chainchaos`` command is the command line.
"""

import contextlib
import sys
import traceback
from collections.abc import Callable

from chainchaos.errors import BuildError, KeptFileError

#: Errors whose message tells the reader what to do (install TeX, restore a kept file): shown
#: without a traceback.
READER_ERRORS = (BuildError, KeptFileError)


def run(smk, task: Callable[[dict, dict, dict, dict], None]) -> None:
    """Run ``task`` on the job of a rule's script, with stderr in the rule's log.

    Parameters
    ----------
    smk : snakemake.script.Snakemake
        The ``snakemake`` object of the script: its ``input``, ``output``, ``params`` and
        ``wildcards`` are passed to ``task`` as dicts, and stderr goes to its first ``log`` file.
    task : callable
        The rule's task, ``task(inputs, outputs, params, wildcards)``.

    Raises
    ------
    SystemExit
        With the message alone (no traceback) for a :data:`READER_ERRORS` error; any other
        exception propagates after its traceback is written to the log, which Snakemake shows
        for a failed job.
    """
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
