"""numpydoc's own validation of the API reference's docstrings (issue 51, item 3).

What is checked: every function and class of ``chainchaos.__all__``, and every public function and
class *defined* in a module that docs/reference/api.md shows (its ``::: chainchaos....`` lines: the
module of each object shown, not the names it imports), with the public methods and properties of
those classes. Each passes the numpydoc checks of :data:`CHECKS` (``numpydoc.validate.validate``, as
``python -m numpydoc validate <name>`` runs it). The registries of ``__all__`` (MODELS, SCHEMES, ...) are dicts:
data, not docstrings; the page shows their entries in tables and their types are checked here.
"""

import dataclasses
import importlib
import inspect
import re
from functools import cached_property

import pytest

import chainchaos
from project.test_api_examples import API_PAGE, page_modules

validate = pytest.importorskip("numpydoc.validate", reason="the test extra is not installed: pip install -e '.[test]'").validate

#: The numpydoc checks every object must pass, and why these:
#:
#: - GL08 (no docstring): an object without one is a bare name on the page.
#: - GL06 (unknown section): a misspelt heading ("Return", "Attribute") is not parsed as a section,
#:   and the page shows it as text instead of a table.
#: - SS01 (no summary): also catches a dataclass without a docstring of its own, whose ``__doc__`` is
#:   its generated signature (GL08 does not see it). SS03 (summary ends with a period) and SS04 (no
#:   leading whitespace): the summary is a sentence, what the page and ``help()`` show first.
#: - PR01 (a parameter not documented), PR02 (a documented parameter the signature lacks), PR04 (a
#:   parameter without a type), PR07 (a parameter without a description), PR10 (``name: type``
#:   without the space before the colon, read as one name without a type): the parameter table is
#:   complete, true to the signature, and each row says what and, in the type or the text, what
#:   units. For a class the signature is its constructor's: a dataclass documents its fields.
#: - RT01 (a function that returns a value has no Returns section), RT03 (a return value without a
#:   description), YD01 (a generator has no Yields section).
#:
#: Left out, on purpose: GL01/GL02 (where the quotes sit), SS02 (summaries here may start with a
#: symbol, ``m = r^3``), SS05 (the package's summaries are noun phrases, "The chain ..."), SS06
#: (the summary is the first paragraph, which mkdocstrings shows whole), PR03 (a subclass dataclass's
#: constructor lists the base class's fields first; the docstring puts the class's own first),
#: PR05/PR06/PR08/PR09, RT02/RT04/RT05 (wording), ES01, SA01 and EX01 (an extended summary, See Also
#: and Examples are not asked of every object: test_api_examples.py asks Examples of the entry points).
CHECKS = frozenset({"GL06", "GL08", "SS01", "SS03", "SS04", "PR01", "PR02", "PR04", "PR07", "PR10",
                    "RT01", "RT03", "YD01"})

#: Objects excused from some checks, each with its reason.
EXCUSED = {
    # A Numba type: Numba's metaclass (types.Type) interns its instances and its __call__ takes
    # (*args, **kwargs), which is the signature numpydoc reads; the docstring documents __init__'s.
    "chainchaos.system.models.base.ModelType": {"PR01", "PR02"},
}


def _members(cls) -> dict[str, object]:
    """A class's own public methods and properties (not its dataclass fields, whose defaults may
    be functions; the class documents its fields)."""
    fields = {f.name for f in dataclasses.fields(cls)} if dataclasses.is_dataclass(cls) else set()
    return {name: value for name, value in vars(cls).items()
            if not name.startswith("_") and name not in fields
            and (inspect.isfunction(value) or isinstance(value, (staticmethod, classmethod, property, cached_property)))}


def documented_objects(page_text: str) -> list[str]:
    """The dotted names (module.qualname) of every object to validate, each once, sorted."""
    found = {}
    for name in chainchaos.__all__:
        value = getattr(chainchaos, name)
        if inspect.isfunction(value) or inspect.isclass(value):
            found[f"{value.__module__}.{value.__qualname__}"] = value
    for module_name in page_modules(page_text):
        for name, value in vars(importlib.import_module(module_name)).items():
            if (not name.startswith("_") and (inspect.isfunction(value) or inspect.isclass(value))
                    and value.__module__ == module_name):
                found[f"{module_name}.{value.__qualname__}"] = value
    for dotted, value in list(found.items()):
        if inspect.isclass(value):
            found.update({f"{dotted}.{name}": member for name, member in _members(value).items()})
    return sorted(found)


OBJECTS = documented_objects(API_PAGE.read_text())


def problems(dotted: str) -> list[str]:
    """The failed checks of CHECKS, less the object's excused ones, as 'CODE: message'."""
    excused = EXCUSED.get(dotted, set())
    return [f"{code}: {message}" for code, message in validate(dotted)["errors"]
            if code in CHECKS and code not in excused]


def test_the_objects_cover_the_page_and_the_public_names():
    modules = page_modules(API_PAGE.read_text())
    assert {"chainchaos.system.chain", "chainchaos.run.driver", "chainchaos.errors"} <= set(modules)
    for name in ("chainchaos.system.chain.random_chain", "chainchaos.run.driver.Samples",
                 "chainchaos.errors.SimulationError", "chainchaos.system.chain.Chain.with_k4_sign",
                 "chainchaos.studies.study.spec.Study.N"):
        assert name in OBJECTS, name
    assert "chainchaos.system.chain.require" not in OBJECTS  # imported there, defined in chainchaos.errors
    assert len(OBJECTS) > 150


@pytest.mark.parametrize("dotted", OBJECTS)
def test_the_docstring_passes_numpydoc_validation(dotted):
    assert problems(dotted) == []


def test_a_lost_parameters_section_fails(monkeypatch):
    """The check can fail: ``random_chain`` without its Parameters section misses PR01."""
    function = chainchaos.random_chain
    doc = re.sub(r"Parameters\n\s*-+\n.*?(?=\n\s*Returns\n)", "", function.__doc__, flags=re.DOTALL)
    assert doc != function.__doc__
    monkeypatch.setattr(function, "__doc__", doc)
    assert [p[:4] for p in problems("chainchaos.system.chain.random_chain")] == ["PR01"]
