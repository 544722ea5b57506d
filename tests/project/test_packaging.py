"""The package as others get it: one version everywhere (package, pyproject, CITATION.cff, the
changelog), a valid citation of the software with the paper under its references, the licence,
the command's ``--version`` and ``python -m chainchaos``, the lazy public names in ``dir()``, and a
library-only install (a wheel in a fresh virtual environment, without the workflow extra) that
imports the package and integrates an orbit."""

import json
import re
import shutil
import subprocess
import sys
import textwrap
import time
import tomllib
import zipfile
from pathlib import Path

import pytest
import yaml
from jsonschema import Draft7Validator

import chainchaos
from chainchaos.workflow import cli

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = Path(chainchaos.__file__).resolve().parent
DEVELOPERS = "The chainchaos developers"
#: The Citation File Format's schema, version 1.2.0, as published by the format
#: (https://citation-file-format.github.io/1.2.0/schema.json, CC-BY-4.0; tests/data/README.md).
CFF_SCHEMA = Path(__file__).resolve().parents[1] / "data" / "cff-1.2.0.schema.json"
PAPER_TITLE = "Chaos and Anderson Localisation in Disordered Classical Chains: Hertzian vs FPUT models"
PAPER_AUTHORS = [("Ngapasare", "A."), ("Theocharis", "G."), ("Richoux", "O."), ("Skokos", "Ch."),
                 ("Achilleos", "V.")]


def pyproject() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


def citation() -> dict:
    return yaml.safe_load((ROOT / "CITATION.cff").read_text())


def changelog_versions() -> list[str]:
    """The changelog's section names (``## [name]``), newest first."""
    return re.findall(r"^## \[([^\]]+)\]", (ROOT / "CHANGELOG.md").read_text(), flags=re.MULTILINE)


# ---- one version ---------------------------------------------------------------------------------


def test_the_version_is_one_in_package_pyproject_citation_and_changelog():
    version = chainchaos.__version__
    assert re.fullmatch(r"\d+\.\d+\.\d+", version), version
    project = pyproject()["project"]
    if "version" in project.get("dynamic", []):
        assert "version" not in project
    else:
        assert project["version"] == version
    assert str(citation()["version"]) == version
    sections = changelog_versions()
    assert sections[0] == "Unreleased", sections
    released = [s for s in sections if s != "Unreleased"]
    assert released and released[0] == version, f"newest released section {released[:1]}, package {version}"


def test_a_version_mismatch_is_seen():
    """The check above reads the newest released section, not any section naming the version."""
    text = "## [Unreleased]\n\n## [0.2.0]\n\n## [0.1.0]\n"
    sections = re.findall(r"^## \[([^\]]+)\]", text, flags=re.MULTILINE)
    assert next(s for s in sections if s != "Unreleased") != "0.1.0"


# ---- citation, authors, licence ------------------------------------------------------------------


def test_the_citation_is_valid_cff_1_2_0():
    validator = Draft7Validator(json.loads(CFF_SCHEMA.read_text()))
    errors = sorted(validator.iter_errors(citation()), key=lambda e: list(e.path))
    assert not errors, "\n".join(f"{list(e.path)}: {e.message}" for e in errors)


def test_the_schema_rejects_an_invalid_citation():
    validator = Draft7Validator(json.loads(CFF_SCHEMA.read_text()))
    broken = {k: v for k, v in citation().items() if k != "title"}
    assert not validator.is_valid(broken)
    assert not validator.is_valid({**citation(), "authors": [{"name": ""}]})
    assert not validator.is_valid({**citation(), "type": "book"})


def test_the_software_is_cited_by_its_developers_and_the_paper_by_its_authors():
    cff = citation()
    assert cff["cff-version"] == "1.2.0" and cff["type"] == "software" and cff["title"] == "chainchaos"
    assert cff["authors"] == [{"name": DEVELOPERS}]
    assert cff["license"] == "MIT"
    (paper,) = [r for r in cff["references"] if r["type"] == "article"]
    assert paper["title"] == PAPER_TITLE
    assert [(a["family-names"], a["given-names"]) for a in paper["authors"]] == PAPER_AUTHORS


def test_the_paper_title_is_the_papers():
    """The reference's title is the one the paper's source gives, where the source is present."""
    source = ROOT.parent / "shared" / "paper"
    texts = [p.read_text(errors="replace") for p in sorted(source.glob("*"))] if source.is_dir() else []
    if not texts:
        pytest.skip(f"the paper's source is not at {source}")
    titles = [re.search(r"\\title\{(.*?)\}\n", t, flags=re.DOTALL) for t in texts]
    title = next(m.group(1) for m in titles if m)
    assert " ".join(title.replace("\\\\", " ").split()) == PAPER_TITLE


def test_pyproject_names_the_developers_and_the_licence():
    project = pyproject()["project"]
    assert project["authors"] == [{"name": DEVELOPERS}]
    assert project["license"] == {"text": "MIT"}
    licence = (ROOT / "LICENSE").read_text()
    assert licence.startswith("MIT License") and f"Copyright (c) 2026 {DEVELOPERS}" in licence
    # the type marker, and the study schema run_study validates a study file against
    assert pyproject()["tool"]["setuptools"]["package-data"]["chainchaos"] == ["py.typed", "studies/study/schema.yaml"]
    assert (PACKAGE / "py.typed").is_file()


# ---- command, module, names ----------------------------------------------------------------------


def test_version_option_prints_the_package_version(capsys):
    with pytest.raises(SystemExit) as stop:
        cli.main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"chainchaos {chainchaos.__version__} ({PACKAGE})"


def test_python_dash_m_runs_the_command():
    done = subprocess.run([sys.executable, "-m", "chainchaos", "--version"], capture_output=True, text=True,
                          cwd=ROOT, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == f"chainchaos {chainchaos.__version__} ({PACKAGE})"
    done = subprocess.run([sys.executable, "-m", "chainchaos"], capture_output=True, text=True, cwd=ROOT,
                          check=False)
    assert done.returncode == 2 and "arguments are required: {chain,ensemble,simulate" in done.stderr


def test_dir_shows_the_lazy_public_names_without_importing_them():
    code = textwrap.dedent("""
        import sys
        import chainchaos
        names = dir(chainchaos)
        assert names == sorted(names)
        assert set(chainchaos.__all__) <= set(names), set(chainchaos.__all__) - set(names)
        assert {"__version__", "__doc__", "configure_numba_cache"} <= set(names)
        assert "chainchaos.run.scenes" not in sys.modules
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert set(chainchaos._EXPORTS) <= set(dir(chainchaos))


def test_the_package_says_what_importing_it_sets():
    doc = chainchaos.__doc__
    for said in ("NUMBA_CACHE_DIR", "NUMBA_DISABLE_INTEL_SVML", "process-wide", "every x86-64 CPU",
                 ".numba_cache", "~/.cache/chainchaos/numba"):
        assert said in doc, said


# ---- a library-only install ----------------------------------------------------------------------

#: Run in the fresh environment: the package imports without the workflow extra, every public
#: name resolves, importing it sets what its docstring says, and an orbit integrates.
LIBRARY_SNIPPET = textwrap.dedent("""
    import importlib.util, os, sys
    from importlib.resources import files
    from pathlib import Path

    import chainchaos
    from chainchaos import SceneParameters, random_chain, simulate

    assert importlib.util.find_spec("snakemake") is None, "snakemake importable"
    assert Path(chainchaos.__file__).resolve().is_relative_to(Path(sys.prefix).resolve()), chainchaos.__file__
    assert files("chainchaos").joinpath("py.typed").is_file(), "no py.typed"
    for name in chainchaos.__all__:
        getattr(chainchaos, name)
    assert os.environ["NUMBA_DISABLE_INTEL_SVML"] == "1"
    cache = Path(os.environ["NUMBA_CACHE_DIR"])
    from platformdirs import user_cache_dir
    assert cache.parent == Path(user_cache_dir("chainchaos")) / "numba" == Path.home() / ".cache/chainchaos/numba", cache
    chain = random_chain(seed=1, alpha=3.0, N=20)
    ds = simulate(chain, SceneParameters(model="fput", energy=0.5, t_final=10.0, dt=0.01, excited_site=10,
                                         observables=("participation",)))
    error = float(abs(ds.energy_error).max())
    assert 0 < error < 1e-8, error
    assert ds.time.values[-1] == 10.0 and 1 <= float(ds.participation[-1]) <= 20
    # outside a checkout: no project, and what needs one says so; the package's own data is there
    from chainchaos.project import package_checkout, project_root
    from chainchaos.studies.study.spec import SCHEMA, load_study
    assert package_checkout() is None and project_root() is None and SCHEMA.is_file()
    try:
        load_study("hertz100")
    except FileNotFoundError as err:
        assert "CHAINCHAOS_PROJECT" in str(err), err
    else:
        raise AssertionError("a study named without a path found outside a checkout")
    load_study({"lattice": {"model": "fput", "N": 8, "realizations": 1}, "excitation": {"energies": [0.5]},
                "integration": {"t_final": 1.0, "dt": 0.1}})  # a study given whole needs no project
    print(chainchaos.__version__, error)
""")


def project_copy(destination: Path) -> Path:
    """The files a wheel is built from, copied so that the build writes nothing into the checkout
    (setuptools puts build/ and *.egg-info beside the sources)."""
    for name in ("pyproject.toml", "README.md", "LICENSE"):
        shutil.copy2(ROOT / name, destination / name)
    shutil.copytree(ROOT / "src", destination / "src", ignore=shutil.ignore_patterns("__pycache__", "*.egg-info"))
    return destination


def run(*command, **options) -> subprocess.CompletedProcess:
    """``command`` (paths as they are), its output captured as text; its return code is checked by
    the caller, with the output in the message."""
    return subprocess.run([str(c) for c in command], capture_output=True, text=True, timeout=600, check=False,
                          **options)


@pytest.mark.slow
def test_a_library_only_install_imports_and_runs_an_orbit(tmp_path):
    """``pip install`` of the wheel into a virtual environment without system site packages: the
    dependencies come from the package index (PyPI or a local mirror; setuptools and wheel for the
    isolated build too), so this test needs one. Byte-compilation is skipped to save time."""
    started = time.monotonic()
    (tmp_path / "project").mkdir()
    source = project_copy(tmp_path / "project")
    wheels = tmp_path / "wheels"
    done = run(sys.executable, "-m", "pip", "wheel", "--no-deps", "-w", wheels, source)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    (wheel,) = wheels.glob("chainchaos-*.whl")
    assert wheel.name.startswith(f"chainchaos-{chainchaos.__version__}-")
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    assert {"chainchaos/py.typed", "chainchaos/__main__.py"} <= names
    assert any(n.endswith("/LICENSE") and ".dist-info/" in n for n in names), sorted(names)[-10:]

    venv = tmp_path / "venv"
    done = run(sys.executable, "-m", "venv", venv)
    assert done.returncode == 0, done.stderr
    python = venv / "bin" / "python"
    done = run(python, "-m", "pip", "install", "--no-compile", wheel)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]

    # HOME in the test's directory: the Numba cache of an installed package goes there, not to the
    # user's ~/.cache; nothing of the checkout's environment (NUMBA_CACHE_DIR, PYTHONPATH) leaks in.
    env = {"PATH": f"{venv / 'bin'}:/usr/bin:/bin", "HOME": str(tmp_path / "home"), "LANG": "C.UTF-8"}
    done = run(python, "-c", LIBRARY_SNIPPET, env=env, cwd=tmp_path)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-3000:]
    assert done.stdout.split()[0] == chainchaos.__version__
    done = run(venv / "bin" / "chainchaos", "--version", env=env, cwd=tmp_path)
    installed = f"{venv}/lib/python{sys.version_info.major}.{sys.version_info.minor}/site-packages/chainchaos"
    assert done.returncode == 0 and done.stdout.strip() == f"chainchaos {chainchaos.__version__} ({installed})", \
        done.stdout + done.stderr
    print(f"library-only install and orbit: {time.monotonic() - started:.0f} s")
