"""Point Numba's on-disk cache at a directory inside the project.

Numba reads ``NUMBA_CACHE_DIR`` when it is first imported, so this runs before any module of the
package imports numba. A checkout (editable install) caches in ``<project>/.numba_cache``, so every
job of the pipeline reuses the kernels compiled once; an installed wheel falls back to the user's
cache directory. An explicit ``NUMBA_CACHE_DIR`` always wins.
"""

import os
from pathlib import Path


def project_root() -> Path | None:
    """The checkout that holds this package (``src/chainchaos``), or None for an installed wheel."""
    root = Path(__file__).resolve().parents[2]
    return root if (root / "pyproject.toml").is_file() else None


def configure_numba_cache() -> None:
    if os.environ.get("NUMBA_CACHE_DIR"):
        return
    root = project_root()
    cache = root / ".numba_cache" if root else Path.home() / ".cache" / "chainchaos" / "numba"
    os.environ["NUMBA_CACHE_DIR"] = str(cache)
