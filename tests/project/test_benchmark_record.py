"""benchmarks/record.py outside a git checkout (a downloaded archive): it records that, not a
failure."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def load_record():
    spec = importlib.util.spec_from_file_location("record", ROOT / "benchmarks" / "record.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_outside_a_git_checkout_the_record_says_so(tmp_path, monkeypatch):
    record = load_record()
    assert len(record._git("rev-parse", "HEAD")) == 40  # this checkout
    monkeypatch.setattr(record, "ROOT", tmp_path)  # a folder with no .git above it
    monkeypatch.setenv("GIT_CEILING_DIRECTORIES", str(tmp_path.parent))
    assert record._git("rev-parse", "HEAD") == record.NOT_A_CHECKOUT == "not a git checkout"
