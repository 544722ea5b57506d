"""Point Numba's on-disk cache at a directory inside the project, keyed by the kernels' source.

Numba reads ``NUMBA_CACHE_DIR`` when it is first imported, so this runs before any module of the
package imports numba. A checkout (editable install) caches in ``<project>/.numba_cache/<key>``,
so every job of the pipeline reuses the kernels compiled once; an installed wheel falls back to
the platform's user cache directory (``platformdirs``: ``~/.cache/chainchaos/numba`` on Linux). Numba invalidates a cached function only when its own file changes,
yet the engines (``integrators``, ``batch``, ``numerics``) compile in the bond laws of ``models``,
the helpers of ``integrators`` and the vector operations of ``simd``: the key, a hash of those shared kernel modules, makes an edit
there start a fresh cache instead of loading a stale one. An explicit ``NUMBA_CACHE_DIR`` always
wins.

It also turns off Numba's use of Intel's SVML vector math library (used when the package
``intel-cmplr-lib-rt`` happens to be installed), whose results depend on the CPU: the kernels then
call the C library's scalar routines on every machine (chainchaos.kernels.exactmath). An explicit
``NUMBA_DISABLE_INTEL_SVML`` wins.
"""

import hashlib
import os
from pathlib import Path

from chainchaos.project import PACKAGE, package_checkout

#: The environment variable that overrides the SIMD width fitted to the CPU (chainchaos.kernels.simd).
LANES_VARIABLE = "CHAINCHAOS_SIMD_LANES"

#: Modules whose Numba functions are compiled into functions of other modules (patterns).
SHARED_KERNEL_MODULES = ("system/models/*.py", "engine/integrators.py", "kernels/simd.py", "kernels/exactmath.py")


def kernel_sources() -> list[Path]:
    """The shared kernel modules: an edit to one of them (or a new model) invalidates kernels in
    other files."""
    return [path for pattern in SHARED_KERNEL_MODULES for path in sorted(PACKAGE.glob(pattern))]


def kernel_key() -> str:
    """A hash of the shared kernel modules and of a chosen vector width (``CHAINCHAOS_SIMD_LANES``),
    which changes compiled code without changing a source file; the width fitted to the CPU needs no key, as Numba keys its cache
    entries by the target CPU."""
    digest = hashlib.sha256()
    for path in kernel_sources():
        digest.update(path.relative_to(PACKAGE).as_posix().encode() + b"\0" + path.read_bytes())
    digest.update(b"lanes\0" + os.environ.get(LANES_VARIABLE, "").strip().encode())
    return digest.hexdigest()[:16]


def configure_numba_cache() -> None:
    os.environ.setdefault("NUMBA_DISABLE_INTEL_SVML", "1")
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    root = package_checkout()
    if root:
        base = root / ".numba_cache"
    else:  # an installed package: the platform's user cache directory (~/.cache/chainchaos on Linux)
        from platformdirs import user_cache_dir

        base = Path(user_cache_dir("chainchaos")) / "numba"
    os.environ["NUMBA_CACHE_DIR"] = str(base / kernel_key())
