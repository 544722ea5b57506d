"""Provenance recorded in every NetCDF file: package version, git commit, parameters."""

import json
import subprocess

from chainchaos._numba_cache import project_root


def git_commit() -> str:
    """The checkout's commit, with ``-dirty`` when tracked files differ, or ``unknown``."""
    root = project_root()
    if root is None:
        return "unknown"
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def provenance_attrs(parameters: dict) -> dict:
    from chainchaos import __version__

    return {
        "Conventions": "CF-1.10",
        "source": f"chainchaos {__version__}",
        "chainchaos_version": __version__,
        "git_commit": git_commit(),
        "parameters": json.dumps(parameters, sort_keys=True),
    }
