"""Compile the batch engine once into Numba's on-disk cache before the scan jobs fan out."""

import contextlib
import sys
import time
from pathlib import Path

from chainchaos.batch import warm_up
from chainchaos.simulate import warm_up as warm_up_single


def main(flag):
    start = time.perf_counter()
    warm_up()
    cache = warm_up_single()
    text = f"batch and single-trajectory kernels compiled in {time.perf_counter() - start:.1f} s; cache {cache}\n"
    print(text, file=sys.stderr, end="")
    Path(flag).parent.mkdir(parents=True, exist_ok=True)
    Path(flag).write_text(text)


if "snakemake" in globals():
    with open(snakemake.log[0], "w") as log, contextlib.redirect_stderr(log):
        main(snakemake.output.flag)
else:
    main(sys.argv[1] if len(sys.argv) > 1 else "scan_kernels_compiled.txt")
