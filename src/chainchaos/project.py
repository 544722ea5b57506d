"""Where the project's files are: the one place the package looks for files outside itself.

Two directories, asked for by what they are for:

- :func:`package_checkout`: the git checkout that holds this package's source (an editable
  install), or None for an installed wheel. The code that ran: provenance's commit, the on-disk
  cache of its compiled kernels.
- :func:`project_root`: the project a command works in (its ``config/``, ``studies/``,
  ``data/``, ``workflow/``): ``CHAINCHAOS_PROJECT`` if set, else the working directory or the
  nearest of its parents that holds a ``Snakefile`` and a ``pyproject.toml``, else the package's
  checkout; None when there is none (a wheel used outside a checkout).

Files the package itself needs are package data, read beside the modules that use them (the
study schema: ``studies/study/schema.yaml``), never from a checkout.
"""

import os
from pathlib import Path

#: The environment variable that names the project directory.
PROJECT_VARIABLE = "CHAINCHAOS_PROJECT"
#: The package's own directory (``src/chainchaos`` in a checkout).
PACKAGE = Path(__file__).resolve().parent


def _is_project(path: Path) -> bool:
    return (path / "Snakefile").is_file() and (path / "pyproject.toml").is_file()


def package_checkout() -> Path | None:
    """The checkout that holds this package (``<checkout>/src/chainchaos``), or None for an
    installed wheel."""
    root = PACKAGE.parents[1]
    return root if (root / "pyproject.toml").is_file() else None


def project_root(needed_for: str | None = None) -> Path | None:
    """The project directory (module docstring), or None.

    Parameters
    ----------
    needed_for : str, optional
        What the caller reads there; given, a missing project raises instead of returning None.

    Returns
    -------
    pathlib.Path or None

    Raises
    ------
    FileNotFoundError
        When ``needed_for`` is given and there is no project directory, or ``CHAINCHAOS_PROJECT``
        names a directory that does not exist: the message names both and how to set one.
    """
    setting = os.environ.get(PROJECT_VARIABLE, "").strip()
    if setting:
        root = Path(setting).resolve()
        if not root.is_dir():
            raise FileNotFoundError(f"{PROJECT_VARIABLE}={setting!r} is not a directory; allowed is the directory "
                                    "of a chainchaos checkout (its Snakefile, config/, studies/)")
        return root
    here = Path.cwd().resolve()
    root = next((p for p in (here, *here.parents) if _is_project(p)), None) or package_checkout()
    if root is None and needed_for is not None:
        raise FileNotFoundError(f"{needed_for} needs the project's files, and no chainchaos checkout was found from "
                                f"{here} upward: run it in a checkout, or set {PROJECT_VARIABLE}")
    return root
