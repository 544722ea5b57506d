"""The README, the project's front door: the library install beside the paper's two commands, no
commit hashes (measurements keep theirs in benchmarks/results/), and its Python example runs as a
user pastes it (``python -`` in an empty folder) and writes its figure."""

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()
PAPER_COMMANDS = ("bash workflow/setup.sh && snakemake --cores 2 all",
                  "bash workflow/setup.sh && python -m pytest -n 2")
#: A commit hash: 7 to 40 hexadecimal digits with at least one digit and one letter.
HASH = re.compile(r"\b(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}\b")


def section(title: str) -> str:
    start = README.index(f"\n## {title}\n")
    end = README.find("\n## ", start + 1)
    return README[start:end if end > 0 else None]


def test_the_quick_start_is_the_papers_two_commands_and_the_library_install_stands_beside_it():
    quick = section("Quick start")
    commands = [line for line in quick.splitlines() if line.startswith("bash ")]
    assert [line.split("  #")[0].strip() for line in commands] == list(PAPER_COMMANDS), commands
    library = section("The library alone")
    assert re.search(r"^pip install \.\s", library, re.M), library
    assert "pip install -e ." in library


def test_the_readme_has_no_commit_hashes():
    assert not HASH.findall(README), HASH.findall(README)


def test_the_python_example_runs_as_pasted_and_saves_its_figure(tmp_path):
    (code,) = re.findall(r"```python\n(.*?)```", section("In Python"), re.S)
    assert 'xscale="log"' in code and 'savefig("hertz.png")' in code
    env = {**os.environ, "MPLBACKEND": "Agg"}
    done = subprocess.run([sys.executable, "-"], input=code, cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=600, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    assert (tmp_path / "hertz.png").stat().st_size > 10_000
