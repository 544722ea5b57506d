"""The suite's grouping under pytest-xdist: tests of one ``xdist_group`` (a module's Snakemake
runs, the users of the `quick` fixture) share one worker, so that their module- and session-scoped
runs happen once. A pytest that silently ignores the groups (pytest 9.2 with xdist 3.8,
pytest-xdist#1386) doubles those runs and the time of CI."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

GROUPED = """\
import os
import pytest

pytestmark = pytest.mark.xdist_group("one")


@pytest.mark.parametrize("i", range(6))
def test_grouped(i):
    with open(os.path.join(os.environ["RAN_IN"], f"ran_{i}"), "w") as f:
        f.write(os.environ["PYTEST_XDIST_WORKER"])
"""


def test_tests_of_one_group_run_on_one_worker_under_dash_n_2(tmp_path):
    suite = tmp_path / "suite"
    suite.mkdir()
    shutil.copy(Path(__file__).parents[1] / "conftest.py", suite / "conftest.py")
    (suite / "test_grouped.py").write_text(GROUPED)
    ran = tmp_path / "ran"
    ran.mkdir()
    done = subprocess.run([sys.executable, "-m", "pytest", "-n", "2", "-q", "-p", "no:cacheprovider", "--rootdir",
                           str(suite), str(suite)], cwd=suite, capture_output=True, text=True, timeout=300,
                          env={**os.environ, "RAN_IN": str(ran)})
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    workers = [path.read_text() for path in ran.glob("ran_*")]
    assert len(workers) == 6 and len(set(workers)) == 1, workers
