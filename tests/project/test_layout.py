"""The package's folders are its layers: each imports only the layers below it (the import-linter
contract of pyproject.toml), every module imports in a fresh interpreter, no module imports itself
back through others (at module level or inside a function), and nothing but the package's entry
points and its two base modules lives outside the layer folders."""

import ast
import shutil
import subprocess
import sys
from graphlib import CycleError, TopologicalSorter
from pathlib import Path

import chainchaos

PACKAGE = Path(chainchaos.__file__).resolve().parent
LAYERS = {"kernels", "system", "engine", "observe", "records", "run", "paper", "studies", "output", "workflow"}
TOP_LEVEL_MODULES = {"__init__.py", "errors.py", "project.py", "__main__.py"}  # __main__: python -m chainchaos
ROOT = PACKAGE.parents[1]


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def imported_modules(path: Path) -> set[str]:
    """The package's modules that ``path`` imports anywhere in it (``from a.b import c`` imports
    the module a.b.c when there is one, else a.b)."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names if a.name in MODULES}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module in MODULES:
            for a in node.names:
                sub = f"{node.module}.{a.name}"
                out.add(sub if sub in MODULES else node.module)
    return out


def lint_imports(config: Path, source: Path) -> subprocess.CompletedProcess:
    """``lint-imports`` (import-linter) with ``config``, on the package found in ``source``."""
    linter = shutil.which("lint-imports") or str(Path(sys.executable).with_name("lint-imports"))
    return subprocess.run([linter, "--config", str(config), "--no-cache"], capture_output=True, text=True,
                          env={"PATH": str(Path(sys.executable).parent) + ":/usr/bin:/bin", "PYTHONPATH": str(source)},
                          timeout=300, check=False)


def test_each_layer_imports_only_the_layers_below_it():
    done = lint_imports(ROOT / "pyproject.toml", PACKAGE.parent)
    assert done.returncode == 0 and "layers KEPT" in done.stdout, done.stdout[-3000:] + done.stderr[-2000:]


def test_an_import_against_the_layers_breaks_the_contract(tmp_path):
    """The contract can fail: a copy of the package whose kernels import the workflow breaks it."""
    copy = tmp_path / "src" / "chainchaos"
    shutil.copytree(PACKAGE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    kernels = copy / "kernels" / "exactmath.py"
    kernels.write_text(kernels.read_text() + "\nfrom chainchaos.workflow import plan  # noqa: E402\n")
    shutil.copy(ROOT / "pyproject.toml", tmp_path / "pyproject.toml")
    done = lint_imports(tmp_path / "pyproject.toml", copy.parent)
    assert done.returncode == 1 and "layers BROKEN" in done.stdout, done.stdout[-3000:] + done.stderr[-2000:]
    assert "chainchaos.kernels.exactmath -> chainchaos.workflow.plan" in done.stdout


def test_every_module_imports_in_a_fresh_interpreter():
    code = "import importlib, sys\nfor name in sys.argv[1:]:\n    importlib.import_module(name)\n"
    done = subprocess.run([sys.executable, "-c", code, *MODULES], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-3000:]


def test_the_import_graph_has_no_cycle():
    graph = {name: imported_modules(path) - {name} for name, path in MODULES.items()}
    try:
        list(TopologicalSorter(graph).static_order())
    except CycleError as cycle:
        raise AssertionError(f"import cycle: {' -> '.join(cycle.args[1])}") from None


def test_a_cycle_is_found_where_there_is_one():
    """The check above can fail: two modules importing each other form a cycle."""
    graph = {"a": {"b"}, "b": {"a"}}
    try:
        list(TopologicalSorter(graph).static_order())
    except CycleError:
        return
    raise AssertionError("no cycle found")


def test_only_entry_points_live_outside_the_layer_folders():
    top_files = {p.name for p in PACKAGE.glob("*.py")}
    assert top_files == TOP_LEVEL_MODULES
    folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and (p / "__init__.py").is_file()}
    assert folders == LAYERS


def test_every_package_says_what_it_holds():
    for init in PACKAGE.rglob("__init__.py"):
        assert ast.get_docstring(ast.parse(init.read_text())), init


def test_public_names_keep_working():
    for name in chainchaos.__all__:
        assert getattr(chainchaos, name) is not None, name
    from chainchaos.engine.integrators import SCHEMES
    from chainchaos.observe.registry import REGISTRY
    from chainchaos.paper.claims.catalogue import CATALOGUE
    from chainchaos.paper.statements import STATEMENTS
    from chainchaos.system.models import MODELS

    assert chainchaos.MODELS is MODELS and chainchaos.SCHEMES is SCHEMES and chainchaos.OBSERVABLES is REGISTRY
    assert chainchaos.STATEMENTS is STATEMENTS and chainchaos.CLAIMS is CATALOGUE
    assert chainchaos.random_chain(879, 5.0).N == 40


# ---- the tests mirror the package -------------------------------------------------------------------

TESTS = ROOT / "tests"
#: The folder of the tests of the whole project (docs, README, packaging, lock, layout, pipeline,
#: SLURM), beside one folder per layer of the package.
PROJECT_TESTS = "project"


def test_the_tests_mirror_the_package():
    """No test file at tests/ top level: each lives in the folder of the layer it tests (tests/kernels/,
    ..., tests/studies/scan/, ...) or in tests/project/, and each folder is a package, so that two
    folders may hold test files of one name."""
    assert not sorted(p.name for p in TESTS.glob("test_*.py")), "a test file at tests/ top level: move it to its layer"
    folders = {p.parent.relative_to(TESTS) for p in TESTS.rglob("test_*.py")}
    assert {f.parts[0] for f in folders} == LAYERS | {PROJECT_TESTS}, folders
    for folder in folders:
        assert folder.parts[0] == PROJECT_TESTS or (PACKAGE / folder).is_dir(), f"tests/{folder}: no such layer"
        for depth in range(1, len(folder.parts) + 1):
            assert (TESTS.joinpath(*folder.parts[:depth]) / "__init__.py").is_file(), f"tests/{folder}: no __init__.py"


def test_a_marker_pyproject_does_not_register_stops_the_tests(tmp_path):
    """--strict-markers (addopts): a test marked with a marker that pyproject.toml does not register
    is not collected; the registered ones are."""
    (tmp_path / "test_registered.py").write_text(
        "import pytest\n\n\n@pytest.mark.pipeline\n@pytest.mark.browser\n@pytest.mark.docs\n@pytest.mark.slow\n"
        "def test_it():\n    pass\n")
    (tmp_path / "test_unregistered.py").write_text("import pytest\n\n\n@pytest.mark.pipelin\ndef test_it():\n    pass\n")
    done = subprocess.run([sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"), "--rootdir", str(tmp_path),
                           "-p", "no:cacheprovider", "-p", "no:xdist", "-q", str(tmp_path)],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode != 0, done.stdout
    assert "'pipelin' not found in `markers` configuration option" in done.stdout, done.stdout
    assert "test_unregistered.py" in done.stdout and "ERROR test_registered.py" not in done.stdout, done.stdout
