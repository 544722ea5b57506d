"""Where the package finds the project's files (chainchaos.project): a setting, else the working
directory or its parents, else the package's checkout; the installed-wheel case (no checkout) is
run in tests/project/test_packaging.py's library-only install."""

from pathlib import Path

import pytest

from chainchaos import project


def make_project(path: Path) -> Path:
    path.mkdir(parents=True, exist_ok=True)
    (path / "Snakefile").write_text("")
    (path / "pyproject.toml").write_text("")
    return path


def test_the_working_directory_or_its_nearest_project_parent_is_the_project(tmp_path, monkeypatch):
    monkeypatch.delenv(project.PROJECT_VARIABLE, raising=False)
    root = make_project(tmp_path / "mine")
    (root / "results" / "deep").mkdir(parents=True)
    monkeypatch.chdir(root / "results" / "deep")
    assert project.project_root() == root.resolve()


def test_the_setting_wins_and_a_missing_directory_is_named(tmp_path, monkeypatch):
    monkeypatch.chdir(make_project(tmp_path / "here"))
    monkeypatch.setenv(project.PROJECT_VARIABLE, str(tmp_path / "there"))
    with pytest.raises(FileNotFoundError, match="CHAINCHAOS_PROJECT=.*there.*is not a directory"):
        project.project_root()
    (tmp_path / "there").mkdir()
    assert project.project_root() == (tmp_path / "there").resolve()


def test_outside_a_project_the_package_checkout_is_the_project(tmp_path, monkeypatch):
    monkeypatch.delenv(project.PROJECT_VARIABLE, raising=False)
    monkeypatch.chdir(tmp_path)
    checkout = project.package_checkout()
    assert checkout is not None and (checkout / "src" / "chainchaos" / "project.py").is_file()
    assert project.project_root("a test") == checkout


def test_without_any_project_what_needs_one_says_so(tmp_path, monkeypatch):
    monkeypatch.delenv(project.PROJECT_VARIABLE, raising=False)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(project, "package_checkout", lambda: None)  # as for an installed wheel
    assert project.project_root() is None
    with pytest.raises(FileNotFoundError, match="the config schema needs the project's files.*CHAINCHAOS_PROJECT"):
        project.project_root("the config schema")


def test_no_module_finds_files_from_its_own_location_but_project():
    """Repository files come through chainchaos.project: no other module climbs its own path."""
    package = Path(project.__file__).parent
    climbing = [str(p.relative_to(package)) for p in package.rglob("*.py")
                if p.name != "project.py" and ".parents[" in p.read_text()]
    assert climbing == []
