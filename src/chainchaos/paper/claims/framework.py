"""What a claim is: a row of the catalogue, what its measure returns, and the verdict it gets.

A :class:`ClaimRow` is data: the paper's words it encodes (``quote``, passages of the paper's
LaTeX source, found there by the tests), its statement and value, the name of the measure that reads
the stored results (:data:`chainchaos.paper.claims.measures.MEASURES`), the :class:`Check` s its
measurement must pass, the time the statement needs, and LaTeX templates for the criterion and the
measured text. Evaluating a row (:mod:`chainchaos.paper.claims.evaluation`) gives a :class:`Claim`, one
line of claims.csv.

Numbers a row takes from the config block ``claims:`` are written as references (:func:`resolve`):
``"localized_p_max"`` (a field of :class:`Criteria`), ``"tolerance.time_factor"`` (of its
tolerances), ``"plateau_end[hertz_H1.8]"`` (a scene's plateau end), optionally scaled or subtracted
from a number: ``"2e2 * tolerance.time_factor"``, ``"1 - tolerance.participation_relative"``.

Templates (:func:`render`) are Python format strings (literal braces doubled) whose fields are the
measurement's numbers, the row's arguments, ``target`` (the paper's number), ``c`` (the criteria),
``tol`` (the tolerances) and ``scan_criterion`` (the energy scan's criteria by name); the format
spec names how a number is printed (:data:`FORMATS`); None prints as --.
"""

from __future__ import annotations

import math
import re
import string
from dataclasses import asdict, dataclass, field

import numpy as np
import xarray as xr

from chainchaos.observe.reductions import within_factor
from chainchaos.paper.claims.quantities import max_energy_error
from chainchaos.paper.criteria import Criteria
from chainchaos.records.formatting import (
    round_significant,
    tex_math,
    tex_number,
    tex_parameter,
)

VERDICTS = ("reproduced", "differs", "undecided", "not testable at this scale")
REPRODUCED, DIFFERS, UNDECIDED, UNTESTABLE = VERDICTS

#: The name under which the energy scan (results/scan/energy_scan.nc) joins the scenes of a claim.
ENERGY_SCAN = "energy_scan"


@dataclass(kw_only=True)
class Claim:
    """One statement of the paper and what the pipeline measured for it (a line of claims.csv)."""

    id: str
    where: str                      # place in the paper, e.g. "Fig. 4(c), Sec. III B"
    statement: str                  # the paper's statement in this project's words (LaTeX)
    paper: str                      # the paper's value (LaTeX)
    measured: float | None          # the headline measured number (None: nothing measurable)
    measured_text: str              # everything measured for the claim (LaTeX)
    unit: str                       # unit of `measured` ("1": dimensionless; time: 1/omega_max)
    criterion: str                  # how the verdict follows from the measurement (LaTeX)
    verdict: str
    reason: str = ""                # why it differs or cannot be tested
    scenes: tuple = ()
    max_energy_error: float | None = None
    t_final: float | None = None
    t_required: float | None = None
    fraction: str = ""              # ensemble: lanes satisfying each statement the verdict rests on
    statements: tuple = ()          # ids of statements.STATEMENTS the verdict rests on

    def row(self) -> dict:
        d = asdict(self)
        d["scenes"] = " ".join(self.scenes)
        d["statements"] = " ".join(self.statements)
        return d


def decide(passed: bool | None, t_final: float | None = None, t_required: float | None = None,
           refutable_early: bool = False) -> str:
    """Verdict: ``reproduced`` when passed; ``differs`` when not; ``not testable at this scale``
    when the run ends before ``t_required`` (unless the claim holds for the whole run and a
    shorter run already violates it: then ``differs``), or when nothing could be measured."""
    short = t_final is not None and t_required is not None and t_final < t_required * (1 - 1e-9)
    if passed is None:
        return UNTESTABLE
    if short:
        return DIFFERS if (refutable_early and not passed) else UNTESTABLE
    return REPRODUCED if passed else DIFFERS


# --------------------------------------------------------------------------------------------
# References to the criteria
# --------------------------------------------------------------------------------------------

_REFERENCE = re.compile(r"^(?:(?P<number>[-+0-9.e]+)\s*(?P<op>[*-])\s*)?(?P<path>[a-z_]+(?:\.[a-z_]+)?)"
                        r"(?:\[(?P<key>[^\]]+)\])?$")


def resolve(value, criteria: Criteria):
    """A number of a row: itself, or the criteria value a string names (see the module docstring);
    None stays None."""
    if value is None or not isinstance(value, str):
        return value
    found = _REFERENCE.match(value)
    if found is None:
        raise ValueError(f"criteria reference {value!r}: allowed is [NUMBER * | NUMBER -] NAME[.NAME][[KEY]]")
    owner = criteria
    for part in found["path"].split("."):
        if not hasattr(owner, part):
            raise ValueError(f"criteria reference {value!r}: {part!r} is no field of {type(owner).__name__}")
        owner = getattr(owner, part)
    x = owner if found["key"] is None else owner.get(found["key"], math.nan)
    if found["op"] == "*":
        return float(found["number"]) * x
    if found["op"] == "-":
        return float(found["number"]) - x
    return x


# --------------------------------------------------------------------------------------------
# What a measure returns, and the checks it must pass
# --------------------------------------------------------------------------------------------


@dataclass
class Measurement:
    """What a measure read from the stored results for one claim."""

    value: float | None              # the headline number (claims.csv ``measured``)
    details: dict = field(default_factory=dict)  # further numbers, named, for the checks and texts
    case: str = ""                   # which of the row's measured texts applies (e.g. "never")
    decided: bool = True             # False: the numbers cannot decide the claim (nothing to test)
    split: str = ""                  # why two chaos indicators lead to different answers (undecided)

    def __getitem__(self, name: str):
        return self.value if name == "value" else self.details[name]


#: How a check compares a measured number x with its reference (and tolerance).
COMPARISONS = {
    "<": lambda x, ref, tol: x < ref,
    "<=": lambda x, ref, tol: x <= ref,
    ">": lambda x, ref, tol: x > ref,
    ">=": lambda x, ref, tol: x >= ref,
    "==": lambda x, ref, tol: x == ref,
    "near": lambda x, ref, tol: abs(x - ref) <= tol,               # |x - ref| <= tol
    "near_relative": lambda x, ref, tol: abs(x / ref - 1) <= tol,  # |x / ref - 1| <= tol
    "within_factor": lambda x, ref, tol: within_factor(x, ref, tol),  # x / ref in [1/tol, tol]
}


@dataclass(frozen=True)
class Check:
    """``measurement[field] <comparison> reference`` (with ``tolerance`` for near, near_relative and
    within_factor); on an array every element must pass. Reference and tolerance are numbers or
    criteria references (:func:`resolve`)."""

    field: str
    comparison: str
    reference: float | str | None = None
    tolerance: float | str | None = None

    def passes(self, measurement: Measurement, criteria: Criteria) -> bool:
        x = measurement[self.field]
        result = COMPARISONS[self.comparison](x, resolve(self.reference, criteria), resolve(self.tolerance, criteria))
        return bool(np.all(result))


@dataclass(frozen=True, kw_only=True)
class ClaimRow:
    """One claim of the catalogue: a statement of the paper and how to test it (keyword-only:
    every row of the catalogue names what it sets)."""

    id: str
    where: str                      # place in the paper, e.g. "Fig. 4(c), Sec. III B"
    statement: str                  # the paper's statement in this project's words (LaTeX)
    paper: str                      # the paper's value as printed (LaTeX)
    measure: str                    # name in measures.MEASURES, called with the scenes and args
    unit: str                       # unit of the headline number
    criterion: str                  # template: how the verdict follows from the measurement
    measured: str | dict            # template of the measured text, or templates by Measurement.case
    checks: tuple = ()              # Checks that must all pass
    scenes: tuple = ()              # scene names (or ENERGY_SCAN) the measure reads
    args: dict = field(default_factory=dict)  # further arguments of the measure
    target: float | None = None     # the paper's number, ``target`` in the templates
    variables: tuple = ()           # variables the scenes must hold
    t_required: float | str | None = None  # the time the statement needs (number or reference)
    refutable_early: bool = False   # holds for the whole run: a shorter run can refute it
    statements: tuple = ()          # ids of statements.STATEMENTS whose ensemble verdicts decide it
    reason: str | tuple = ""        # why it differs: a text, or (name, *args) of evidence.REASONS
    quote: tuple = ()               # the paper's words it encodes: passages of the paper's LaTeX, in `where`


# --------------------------------------------------------------------------------------------
# What the measures read
# --------------------------------------------------------------------------------------------


@dataclass(kw_only=True)
class Inputs:
    """The stored results a claim is measured on, and the criteria of the measurements."""

    scenes: dict                    # scene name -> Dataset (and ENERGY_SCAN -> the energy scan)
    chain: xr.Dataset               # the chain file
    ensemble: xr.Dataset            # the ensemble statistics of Fig. 1(a)
    criteria: Criteria
    site: int                       # the excited bead
    verdicts: dict = field(default_factory=dict)  # scene name -> ensemble verdicts (verdicts.verdict_dataset)
    search: xr.Dataset | None = None    # the realization search (stages.merge)
    disorder: xr.Dataset | None = None  # the disorder statistics of the energy scan

    def has(self, names, *variables) -> bool:
        return all(n in self.scenes and all(v in self.scenes[n] for v in variables) for n in names)

    def max_energy_error(self, names) -> float | None:
        errs = [max_energy_error(self.scenes[n]) for n in names if n in self.scenes]
        errs = [e for e in errs if e is not None]
        return max(errs) if errs else None

    def t_final(self, names) -> float | None:
        ts = [float(self.scenes[n]["time"].values[-1]) for n in names if n in self.scenes]
        return min(ts) if ts else None

    def scan_criterion(self) -> dict[str, str]:
        """The energy scan's criteria, as the threshold claims print them ("delocalized":
        final P above the scan's bound; "chaotic": the chaos criterion); the bare name without a scan."""
        scan = self.scenes.get(ENERGY_SCAN)
        if scan is None or not all(v in scan for v in ("delocalized", "chaotic", "valid")):
            return {"delocalized": "delocalized", "chaotic": "chaotic"}
        chaotic = CHAOS_CRITERION_TEXT
        if int(scan.attrs.get("gali_order", 0)) > 1:
            chaotic += (f" (and, the second indicator, GALI$_{{{int(scan.attrs['gali_order'])}}}$ below "
                        f"$\\cc{{crit.galithreshold}}$ by the end)")
        return {"delocalized": f"final $P > {tex_parameter(scan.attrs['p_delocalized'])}$", "chaotic": chaotic}


# The chaos criterion as printed (\cc{...} reads the criteria's values from macros.tex).
CHAOS_CRITERION_TEXT = (r"chaotic: over the last decade the slope of $\log\Lambda$ against $\log t$ exceeds "
                        r"\cc{crit.chaosslope} and $\ln|v|$ grows by more than $\ln 10 + "
                        r"\cc{crit.chaosgrowthmargin}$")


# --------------------------------------------------------------------------------------------
# Templates
# --------------------------------------------------------------------------------------------


def _bond_list(bonds) -> str:
    return ", ".join(str(int(b)) for b in bonds) or "none"


def _energy_list(energies) -> str:
    return ", ".join(f"${tex_parameter(round_significant(x))}$" for x in energies) or "none"


def _scene_states(states) -> str:
    return "; ".join(f"$H = {tex_parameter(energy)}$: $P = {tex_number(P)}$, {'chaotic' if chaotic else 'regular'}"
                     for energy, P, chaotic in states)


#: Format specs of the templates: how a field is printed.
FORMATS = {
    "tex": tex_number,                                  # 2.69, 1.5\times 10^{4}
    "tex2": lambda x: tex_number(x, 2),
    "math": tex_math,                                   # $2.69$
    "math2": lambda x: tex_math(x, 2),
    "math4": lambda x: tex_math(x, 4),
    "math%2": lambda x: tex_math(100 * x, 2),           # a fraction in percent, in $...$
    "param": tex_parameter,                             # 0.25, 10^{5}
    "param%": lambda x: tex_parameter(100 * x),         # a fraction in percent
    "bonds": _bond_list,                                # 21, 22 (or none)
    "energies": _energy_list,                           # $1.87$, $4.33$ (or none)
    "states": _scene_states,                            # (energy, P, chaotic) per scene
}


class _TexFormatter(string.Formatter):
    def format_field(self, value, format_spec):
        if value is None:
            return "--"
        if format_spec in FORMATS:
            return FORMATS[format_spec](value)
        return format(value, format_spec)


_FORMATTER = _TexFormatter()


def render(template: str, context: dict) -> str:
    """The template with its fields filled from ``context`` (see the module docstring)."""
    return _FORMATTER.vformat(template, (), context)


def literal(text: str) -> str:
    """Text that a template prints as it is (its braces doubled)."""
    return text.replace("{", "{{").replace("}", "}}")
