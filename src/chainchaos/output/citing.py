"""What to cite: the software and the paper it reproduces (``CITATION.cff``, as BibTeX), and the
method papers behind each integrator and chaos indicator, read from the registries' own references
(``SCHEMES[name].reference``; an observable's ``reference`` and ``NEED_REFERENCES``, the method
behind what it needs: the tangent map). docs/reference/citing.md renders them when the site builds, and
the README carries the same BibTeX (tests/output/test_citing.py checks both), so neither can go stale.
"""

from __future__ import annotations

from pathlib import Path

import yaml


def scheme_references() -> dict[str, str]:
    """Every integration scheme (``chainchaos.engine.integrators.SCHEMES``): name -> its reference."""
    from chainchaos.engine.integrators import SCHEMES

    return {name: scheme.reference for name, scheme in SCHEMES.items()}


def indicator_references() -> dict[str, str]:
    """Every observable a scene or study may ask for that has a paper of its own (the chaos
    indicators): name -> that paper, in the registry's order."""
    from chainchaos.observe.registry import OBSERVABLES, REGISTRY

    return {name: REGISTRY[name].reference for name in OBSERVABLES if REGISTRY[name].reference}


def method_references() -> dict[str, list[str]]:
    """The methods behind what observables need (the tangent map, ``NEED_REFERENCES``): each
    method's reference -> the observables that rest on it, in the registry's order."""
    from chainchaos.observe.registry import NEED_REFERENCES, OBSERVABLES, REGISTRY

    return {reference: [name for name in OBSERVABLES if need in REGISTRY[name].needs]
            for need, reference in NEED_REFERENCES.items()}


def read_citation(path: Path | str = "CITATION.cff") -> dict:
    """The citation file (``CITATION.cff`` of a checkout; an installed wheel does not ship it)."""
    return yaml.safe_load(Path(path).read_text(encoding="utf-8"))


def _authors(people: list[dict]) -> str:
    """BibTeX's author list: "Family, Given" of a person, an entity's name in braces (kept whole)."""
    names = []
    for person in people:
        if "family-names" in person:
            given = person.get("given-names", "")
            names.append(f"{person['family-names']}, {given}" if given else person["family-names"])
        else:
            names.append("{" + person["name"] + "}")
    return " and ".join(names)


def _entry(kind: str, key: str, fields: dict) -> str:
    width = max(map(len, fields))
    body = "".join(f"  {name:<{width}} = {{{value}}},\n" for name, value in fields.items())
    return f"@{kind}{{{key},\n{body}}}\n"


def bibtex(citation: dict) -> str:
    """BibTeX for the software (title, authors, version as a note, year of ``date-released``, ``url``
    when the file has one) and for each of its ``references`` (authors and title, with journal, volume, year
    and DOI only where the file gives them: it gives none for the paper, whose journal reference
    could not be checked). Titles are braced whole, so that a style keeps their capitals."""
    fields = {"author": _authors(citation["authors"]), "title": "{" + citation["title"] + "}",
              "note": f"Version {citation['version']}"}
    if citation.get("date-released"):
        fields["year"] = str(citation["date-released"])[:4]
    if citation.get("url"):
        fields["url"] = citation["url"]
    out = [_entry("misc", citation["title"], fields)]  # @software is biblatex's only; BibTeX's styles know @misc
    for reference in citation.get("references", []):
        first = reference["authors"][0].get("family-names", "ref").lower()
        fields = {"author": _authors(reference["authors"]), "title": "{" + reference["title"] + "}"}
        for name in ("journal", "volume", "year", "doi"):
            if reference.get(name):
                fields[name] = str(reference[name])
        complete = "journal" in fields
        note = "" if complete else "% journal reference not given: none could be checked\n"
        out.append(note + _entry("article" if complete else "misc",
                                 f"{first}_{reference['title'].split()[0].lower()}", fields))
    return "\n".join(out)
