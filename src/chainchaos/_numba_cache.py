"""Point Numba's on-disk cache at a directory inside the project, keyed by the kernels' source.

Numba reads ``NUMBA_CACHE_DIR`` when it is first imported, so this runs before any module of the
package imports numba. A checkout (editable install) caches in ``<project>/.numba_cache/<key>``,
so every job of the pipeline reuses the kernels compiled once; an installed wheel falls back to
the user's cache directory. Numba invalidates a cached function only when its own file changes,
yet ``integrators.advance`` compiles in the force laws of ``models.py``: the key, a hash of every
module of the package that uses Numba, makes any edit to a kernel start a fresh cache instead of
loading a stale one. An explicit ``NUMBA_CACHE_DIR`` always wins.
"""

import hashlib
import os
import re
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent


def project_root() -> Path | None:
    """The checkout that holds this package (``src/chainchaos``), or None for an installed wheel."""
    root = PACKAGE.parents[1]
    return root if (root / "pyproject.toml").is_file() else None


def kernel_sources() -> list[Path]:
    """The package's modules that compile Numba kernels."""
    uses_numba = re.compile(r"^\s*(from|import) numba\b", re.M)
    return sorted(p for p in PACKAGE.rglob("*.py") if uses_numba.search(p.read_text(encoding="utf-8")))


def kernel_key() -> str:
    digest = hashlib.sha256()
    for path in kernel_sources():
        digest.update(path.relative_to(PACKAGE).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]


def configure_numba_cache() -> None:
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    root = project_root()
    base = root / ".numba_cache" if root else Path.home() / ".cache" / "chainchaos" / "numba"
    os.environ["NUMBA_CACHE_DIR"] = str(base / kernel_key())
