"""Keying an archived full search made before kept results recorded their settings: a maintenance
of the repository's kept files, which reads its git history (``chainchaos stamp-search-archive``)."""

from pathlib import Path

import xarray as xr

from chainchaos.paper import statements
from chainchaos.studies.search.archive import recorded_search_params, search_settings
from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION

#: The code that says what the statements are and how they are judged: unchanged since the commit
#: a kept search records, or its key cannot be read off the file (:func:`recorded_search_params`).
STATEMENT_CODE = ("src/chainchaos/paper/statements.py", "src/chainchaos/paper/criteria.py",
                  "src/chainchaos/paper/verdicts.py")


def _git(root: Path, *args: str) -> str:
    import subprocess

    return subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True, check=True).stdout


def stamp_search_archive(path, root=None) -> dict:
    """Key an archived full search made before kept results recorded their settings
    (``chainchaos.records.kept``): its settings from what the file records
    (``archive.recorded_search_params``) and result version 1, written into its global attributes
    with the checksum of its data (``kept.stamp``), every variable left byte for byte as it is.
    Re-runnable: a file already keyed is keyed again with the same settings.

    Refuses (``ValueError``) when the statements' code (:data:`STATEMENT_CODE`) changed since the
    commit the file records, when the file's statements (its variables ``statement``, ``scene``,
    ``kind``) are not today's, or when an attribute disagrees with the settings: the key would
    then say what the file was not made with. The engines' code is not compared here: the result
    version and the bit-identity tests speak for it. ``root``: the git checkout (default: the
    package's). Returns the settings written."""
    from chainchaos.project import package_checkout
    from chainchaos.records import kept

    root = Path(root or package_checkout())
    with xr.open_dataset(path) as ds:
        attrs = dict(ds.attrs)
        recorded = [(str(st), str(sc), str(k)) for st, sc, k in
                    zip(ds["statement"].values, ds["scene"].values, ds["kind"].values)]
    commit = str(attrs["git_commit"]).removesuffix("-dirty")
    if str(attrs["git_commit"]).endswith("-dirty"):
        raise ValueError(f"{path} was written by a checkout with uncommitted changes ({attrs['git_commit']})")
    changed = _git(root, "diff", "--name-only", commit, "HEAD", "--", *STATEMENT_CODE).split()
    if changed:
        raise ValueError(f"{', '.join(changed)} changed since {commit[:7]}, the commit {path} records")
    today = [(s.id, s.scene.name, s.kind) for s in statements.STATEMENTS]
    if recorded != today:
        raise ValueError(f"the statements {path} records are not those of paper.statements")
    import yaml

    config = yaml.safe_load(_git(root, "show", f"{commit}:config/config.yaml"))
    settings = search_settings(recorded_search_params(attrs, config))
    kept.stamp(path, settings, SEARCH_RESULT_VERSION)
    return settings
