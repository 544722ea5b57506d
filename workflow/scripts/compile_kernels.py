"""Compile the Numba kernels into the project's on-disk cache (one tiny run of each model)."""

import contextlib
import sys
import time
from pathlib import Path

from chainchaos.simulate import warm_up


def main(flag):
    start = time.perf_counter()
    cache = warm_up()
    message = f"kernels compiled or loaded from {cache} in {time.perf_counter() - start:.1f} s"
    print(message, file=sys.stderr)
    Path(flag).write_text(message + "\n")


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.output.flag)
else:
    main(sys.argv[1] if len(sys.argv) > 1 else "kernels_compiled.txt")
