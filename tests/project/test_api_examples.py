"""The API reference's examples run, and the main entry points have them.

Every public name of ``chainchaos`` (``chainchaos.__all__``) that is a function or a class has a
numpydoc Parameters section (or, for a record of fields, Parameters or Attributes); the entry points
a new user starts from also have an Examples section. The examples of every module that defines a
public name, or an object docs/reference/api.md shows, run here, as ``pytest --doctest-modules``
would run them: what the reference shows is what the code does.
"""

import doctest
import importlib
import inspect
import re
from pathlib import Path

import pytest

import chainchaos

API_PAGE = Path(__file__).resolve().parents[2] / "docs" / "reference" / "api.md"

#: The entry points a new user starts from: each shows an example that runs.
ENTRY_POINTS = ("simulate", "sample", "run_study", "load_study", "Problem", "random_chain", "chain_from_radii",
                "kg_chain", "KGLattice", "Chain", "normal_modes", "SceneParameters", "check_model")


def page_modules(text: str) -> list[str]:
    """The module of every object a ``::: dotted.name`` line of the API page shows, in page order."""
    modules = []
    for dotted in re.findall(r"^::: (chainchaos[\w.]*)", text, flags=re.MULTILINE):
        parts = dotted.split(".")
        for end in range(len(parts), 0, -1):
            try:
                module = importlib.import_module(".".join(parts[:end])).__name__
                break
            except ImportError:
                continue
        if module not in modules:
            modules.append(module)
    return modules


def public_callables():
    return [name for name in chainchaos.__all__ if name != "__version__" and callable(getattr(chainchaos, name))
            and not isinstance(getattr(chainchaos, name), dict)]


@pytest.mark.parametrize("name", public_callables())
def test_every_public_function_and_class_documents_its_parameters(name):
    doc = inspect.getdoc(getattr(chainchaos, name)) or ""
    assert "Parameters\n----------" in doc, f"{name}: no numpydoc Parameters section"
    if inspect.isfunction(getattr(chainchaos, name)):
        assert "Returns\n-------" in doc or "-> None" in str(inspect.signature(getattr(chainchaos, name))), name


@pytest.mark.parametrize("name", ENTRY_POINTS)
def test_the_entry_points_show_an_example(name):
    assert "Examples\n--------" in (inspect.getdoc(getattr(chainchaos, name)) or ""), name


@pytest.mark.parametrize("module", sorted({chainchaos._EXPORTS[n][0] for n in chainchaos.__all__ if n in chainchaos._EXPORTS}
                                           | set(page_modules(API_PAGE.read_text()))))
def test_the_examples_of_every_module_with_a_public_name_run(module):
    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
                             report=True, verbose=False)
    assert result.failed == 0, f"{module}: {result.failed} of {result.attempted} examples failed (printed above)"
