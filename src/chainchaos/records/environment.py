"""Whether the running Python environment is the locked one (requirements/lock.txt): a line of the
run summary, so that a result made with other library versions says so."""

import re
from importlib import metadata
from pathlib import Path

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

#: At most this many differences are named; the rest are counted.
SHOWN = 5


def normalized(name: str) -> str:
    """A distribution name as PEP 503 compares it (``packaging.utils.canonicalize_name``).

    Parameters
    ----------
    name : str
        A distribution name as written (``netCDF4``, ``typing_extensions``).

    Returns
    -------
    str
        The normalised name (``netcdf4``, ``typing-extensions``).
    """
    return str(canonicalize_name(name))


def lock_requirements(text: str) -> dict[str, tuple[Requirement, list[str]]]:
    """Each requirement of a pip requirements lock file with its hashes, by normalised name
    (continuation lines joined, comments and options dropped), as ``packaging`` parses it.

    Parameters
    ----------
    text : str
        The lock file's text (as written by ``uv pip compile`` or ``pip-compile``).

    Returns
    -------
    dict of str to tuple of (packaging.requirements.Requirement, list of str)
        The requirement and its hashes, by normalised distribution name.
    """
    entries = {}
    for line in re.sub(r"\\\n", " ", text).splitlines():
        line = line.split("#", 1)[0].strip()
        if not line or line.startswith("-"):
            continue
        head, *hashes = re.split(r"\s+--hash=", line)
        requirement = Requirement(head)
        entries[normalized(requirement.name)] = (requirement, hashes)
    return entries


def lock_pins(text: str) -> dict[str, str]:
    """The ``name==version`` pins of a requirements lock file.

    Parameters
    ----------
    text : str
        The lock file's text (as written by ``uv pip compile`` or ``pip-compile``).

    Returns
    -------
    dict of str to str
        Version by normalised distribution name.
    """
    return {name: spec.version for name, (requirement, _) in lock_requirements(text).items()
            for spec in requirement.specifier if spec.operator == "=="}


def lock_status(lock_path) -> str:
    """Whether the installed distributions have the versions the lock pins, as one line.

    Only the locked distributions are compared: tools installed beside them (pip, uv) and the
    project itself, which the lock does not pin, do not change the answer.

    Parameters
    ----------
    lock_path : str or path-like
        The lock file (``requirements/lock.txt``), named as given in the answer.

    Returns
    -------
    str
        ``equals <lock> (N packages)``; ``differs from <lock>: numpy 2.4.6 installed, 2.3.0
        locked; ... (N packages)``, naming at most five differences and counting the rest; or
        ``no lock file`` when there is none.
    """
    path = Path(lock_path)
    if not path.is_file():
        return "no lock file"
    pins = lock_pins(path.read_text(encoding="utf-8"))
    installed = {}
    for dist in metadata.distributions():
        # the first on sys.path is the one imported, as importlib.metadata.version would answer
        installed.setdefault(normalized(dist.metadata["Name"] or ""), dist.version)
    differences = [f"{name} {installed.get(name, 'not')} installed, {version} locked"
                   for name, version in sorted(pins.items()) if installed.get(name) != version]
    count = f"({len(pins)} packages)"
    if not differences:
        return f"equals {lock_path} {count}"
    shown = "; ".join(differences[:SHOWN])
    more = f"; and {len(differences) - SHOWN} more" if len(differences) > SHOWN else ""
    return f"differs from {lock_path}: {shown}{more} {count}"
