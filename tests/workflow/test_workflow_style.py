"""Workflow conventions that CI enforces: snakefmt formatting and a clean snakemake --lint.

The one lint left is "Specify a conda environment or container for each rule": the environment
of every rule is this Python package with its pinned extras (README, Installation)."""

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SNAKEFILES = ["Snakefile", *sorted(str(p.relative_to(ROOT)) for p in (ROOT / "workflow" / "rules").glob("*.smk"))]
ACCEPTED_LINTS = {"Specify a conda environment or container for each rule."}


def test_snakefiles_are_formatted_with_snakefmt():
    done = subprocess.run([sys.executable, "-m", "snakefmt", "--check", *SNAKEFILES], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr


@pytest.mark.pipeline
def test_snakemake_lint_leaves_only_the_conda_note():
    done = subprocess.run([sys.executable, "-m", "snakemake", "--lint", "--nolock"], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)
    out = done.stdout + done.stderr
    lints = set(re.findall(r"^    \* (.+?):$", out, re.M))
    assert lints <= ACCEPTED_LINTS, out[-4000:]
    assert "Lints for snakefile" not in out, out[-4000:]
    assert done.returncode == 0 or lints == ACCEPTED_LINTS, out[-4000:]
