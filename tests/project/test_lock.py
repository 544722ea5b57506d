"""The locked environment (requirements/lock.txt, requirements/README.md): it satisfies the ranges
the library declares in pyproject.toml, every pin carries its hashes, and the run summary's line
says whether the running environment is the locked one (chainchaos.records.environment)."""

import re
import tomllib
from importlib import metadata
from pathlib import Path

from packaging.requirements import Requirement

from chainchaos.records.environment import lock_requirements as lock_entries
from chainchaos.records.environment import lock_status, normalized

ROOT = Path(__file__).resolve().parents[2]
LOCK = ROOT / "requirements" / "lock.txt"
#: The extras workflow/setup.sh installs from the lock.
EXTRAS = ("workflow", "test", "docs")


def lock_problems(pyproject_text: str, lock_text: str) -> list[str]:
    """What is wrong with a lock against pyproject.toml: a declared requirement (dependencies and
    the extras of EXTRAS) not pinned or pinned outside its range, a pin not exact or without a
    hash. Empty when the lock is sound."""
    project = tomllib.loads(pyproject_text)["project"]
    declared = [*project["dependencies"], *(r for e in EXTRAS for r in project["optional-dependencies"][e])]
    entries = lock_entries(lock_text)
    problems = []
    for requirement in map(Requirement, declared):
        entry = entries.get(normalized(requirement.name))
        if entry is None:
            problems.append(f"{requirement.name}: not in the lock")
            continue
        version = next(iter(entry[0].specifier)).version
        if not requirement.specifier.contains(version, prereleases=True):
            problems.append(f"{requirement.name}: locked {version}, outside {requirement.specifier}")
    for name, (requirement, hashes) in entries.items():
        specs = list(requirement.specifier)
        if len(specs) != 1 or specs[0].operator != "==":
            problems.append(f"{name}: not pinned exactly ({requirement.specifier})")
        if not hashes:
            problems.append(f"{name}: no hash")
    return problems


def test_the_lock_satisfies_the_declared_ranges_with_hashes():
    assert lock_problems((ROOT / "pyproject.toml").read_text(), LOCK.read_text()) == []


def test_a_doctored_lock_is_refused():
    """The check can fail: a pin outside its range, a missing package, a pin without hashes and
    a range instead of a pin are each named."""
    text = LOCK.read_text()
    numpy = re.search(r"^numpy==\S+", text, re.MULTILINE)[0]
    text = text.replace(numpy, "numpy==1.25.0")
    text = re.sub(r"^scipy==.*?(?=^\S)", "", text, flags=re.MULTILINE | re.DOTALL)  # scipy's block gone
    text = re.sub(r"^(pyyaml==\S+) \\\n(\s+--hash=\S+ \\\n)*\s+--hash=\S+", r"\1", text, flags=re.MULTILINE)
    text += "made-up-package>=3\n"
    problems = lock_problems((ROOT / "pyproject.toml").read_text(), text)
    assert sorted(problems) == ["made-up-package: no hash", "made-up-package: not pinned exactly (>=3)",
                                "numpy: locked 1.25.0, outside >=1.26", "pyyaml: no hash", "scipy: not in the lock"]


def _lock(tmp_path, pins: dict[str, str]) -> Path:
    """A small lock file in the lock's own layout: each pin, a (made-up) hash, its annotation."""
    path = tmp_path / "lock.txt"
    path.write_text("".join(f"{name}=={version} \\\n    --hash=sha256:{'0' * 64}\n    # via chainchaos\n"
                            for name, version in pins.items()))
    return path


def test_lock_status_says_the_environment_equals_the_lock(tmp_path):
    # names as the lock may spell them: PEP 503 makes them equal to the installed ones
    lock = _lock(tmp_path, {"NumPy": metadata.version("numpy"), "typing_extensions": metadata.version("typing-extensions")})
    assert lock_status(lock) == f"equals {lock} (2 packages)"


def test_lock_status_names_a_different_version_and_a_missing_package(tmp_path):
    numpy = metadata.version("numpy")
    lock = _lock(tmp_path, {"numpy": "1.0.0", "pytest": metadata.version("pytest"), "no-such-package": "1.0"})
    assert lock_status(lock) == (f"differs from {lock}: no-such-package not installed, 1.0 locked; "
                                 f"numpy {numpy} installed, 1.0.0 locked (3 packages)")


def test_lock_status_counts_the_differences_it_does_not_name(tmp_path):
    lock = _lock(tmp_path, {f"no-such-package-{i}": "1.0" for i in range(7)})
    status = lock_status(lock)
    assert status.count("not installed") == 5 and status.endswith("; and 2 more (7 packages)")


def test_lock_status_without_a_lock(tmp_path):
    assert lock_status(tmp_path / "missing.txt") == "no lock file"
