import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from chainchaos import random_chain

ROOT = Path(__file__).resolve().parents[1]


# ---- one quick pipeline per test session, also under pytest-xdist (-n N) ----------------------
# Every test that uses the `quick` fixture is put in one xdist group, and `--dist load` (what -n
# selects) becomes `--dist loadgroup`, so those tests share one worker and the quick pipeline runs
# once per session rather than once per worker. Other tests are distributed as before.


class _QuickGrouping:
    """Controller-side xdist hook: tell each worker whether to tag its tests with their group."""

    @staticmethod
    def pytest_configure_node(node):
        node.workerinput["group_quick"] = node.config.getvalue("dist") == "loadgroup"


def pytest_configure(config):
    worker = getattr(config, "workerinput", None)
    if worker is not None:
        if worker.get("group_quick"):
            config.option.loadgroup = True
    elif config.pluginmanager.hasplugin("xdist"):
        if config.getvalue("dist") == "load":
            config.option.dist = "loadgroup"
        config.pluginmanager.register(_QuickGrouping(), "chainchaos-quick-grouping")


# ---- markers (pyproject.toml [tool.pytest.ini_options] markers; --strict-markers) ------------------
# A test that uses the `quick` fixture runs Snakemake: it is marked `pipeline`. Every test marked
# `pipeline`, `browser` or `docs` is also `slow`, beside those marked slow themselves (installs into a
# fresh environment, a second compilation), so `-m "not slow"` leaves the package's own tests. This
# hook runs first, before `-m` deselects (on every xdist worker too).

#: What a test needs beyond the package; each makes it slow.
SLOW_KINDS = ("pipeline", "browser", "docs")


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    for item in items:
        if "quick" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.xdist_group("quick"))
            item.add_marker(pytest.mark.pipeline)
        if not item.get_closest_marker("slow") and any(item.get_closest_marker(kind) for kind in SLOW_KINDS):
            item.add_marker(pytest.mark.slow)
# Where the quick run of the `quick` fixture puts the manuscript, inside its results directory
# (config manuscript.pdf), so that no test writes the project's manuscript/ms.pdf.
QUICK_MANUSCRIPT = "manuscript/ms.pdf"
# What Snakemake printed in that run, beside its results directory.
QUICK_RUN_OUTPUT = "quick_run_output.txt"


@pytest.fixture(scope="session")
def chain():
    """An alpha = 5 chain whose mode 34 is localised at site 21 (a candidate of the linear rule,
    docs/conventions.md#realization)."""
    return random_chain(879, 5.0)


@pytest.fixture(scope="session")
def homogeneous():
    from chainchaos import Chain

    return Chain(np.ones(40), 1.0)


@pytest.fixture(scope="session")
def quick(tmp_path_factory):
    """A results directory holding the whole quick-scale pipeline (`all` with config/quick.yaml):
    scenes, figures, claims and the manuscript (at QUICK_MANUSCRIPT inside it). Written into a
    temporary directory, so it neither needs nor touches the project's results/ or manuscript/.
    Session-scoped: each test process runs the pipeline at most once."""
    results = tmp_path_factory.mktemp("quick_results")
    pdf = results / QUICK_MANUSCRIPT
    done = subprocess.run(
        [sys.executable, "-m", "snakemake", "--cores", "2", "--nolock", "--configfile", "config/quick.yaml",
         "--config", f"results={results}", f"manuscript={{pdf: {pdf}}}"],
        cwd=ROOT, capture_output=True, text=True, timeout=1500)
    assert done.returncode == 0, (done.stdout + done.stderr)[-6000:]
    (results.parent / QUICK_RUN_OUTPUT).write_text(done.stdout + done.stderr)
    return results
