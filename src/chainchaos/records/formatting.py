"""Numbers and names as the manuscript, the tables and the figures print them.

One module for every number written into LaTeX (claims, scans, numerics, the realization search)
so that a value reads the same wherever it appears:

- :func:`tex_number`: a measured number, three significant digits, 10^{k} for large and small;
- :func:`tex_parameter`: a parameter as one would type it (3, 0.25, 8.7381, 10^{5});
- :func:`tex_math`: :func:`tex_number` in $...$;
- :func:`tex_scientific`: always mantissa times a power of ten (the numerics tables);
- :func:`plain_number`: a number for a CSV file or a table cell without math;
- :func:`tex_escape`: a name (scene, scheme, claim id) with its underscores escaped.

A model's printed name is its registry label (``chainchaos.system.models.model_label``).
"""

import math

import numpy as np


def tex_number(x, digits: int = 3) -> str:
    """A number for LaTeX (math mode content): ``digits`` significant digits, written out for
    10^-2 <= |x| < 10^4, else as m\\times 10^{k} (10^{k} when m = 1). None and non-finite
    numbers print as --, booleans as yes/no, integers in full."""
    if x is None:
        return "--"
    if isinstance(x, (bool, np.bool_)):
        return "yes" if x else "no"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    x = float(x)
    if not math.isfinite(x):
        return "--"
    if x == 0:
        return "0"
    exponent = int(math.floor(math.log10(abs(x))))
    if -2 <= exponent <= 3:
        return f"{x:.{max(digits - 1 - exponent, 0)}f}"
    mantissa = f"{x / 10**exponent:.{digits - 1}f}"
    if float(mantissa) == 10.0:
        mantissa, exponent = f"{1:.{digits - 1}f}", exponent + 1
    if float(mantissa) == 1.0:
        return f"10^{{{exponent}}}"
    return f"{mantissa}\\times 10^{{{exponent}}}"


def tex_parameter(x) -> str:
    """A parameter (threshold, energy, tolerance) for LaTeX math as one would type it: 3, 0.25,
    8.7381, and 10^{5} or 5\\times 10^{-4} for |x| >= 10^5 or |x| < 10^-3."""
    x = float(x)
    if x != 0 and (abs(x) >= 1e5 or abs(x) < 1e-3):
        exponent = int(math.floor(math.log10(abs(x))))
        mantissa = f"{x / 10**exponent:.4g}"
        return f"10^{{{exponent}}}" if mantissa == "1" else f"{mantissa}\\times 10^{{{exponent}}}"
    return f"{x:.6g}"


def tex_math(x, digits: int = 3) -> str:
    """:func:`tex_number` wrapped in $...$."""
    return f"${tex_number(x, digits)}$"


def tex_scientific(x: float, digits: int = 2) -> str:
    """x as m\\times10^{k} with ``digits`` significant digits (math mode content), e.g.
    1.2e-05 -> 1.2\\times10^{-5}; -- when not finite."""
    if not math.isfinite(x):
        return "--"
    if x == 0:
        return "0"
    exponent = int(math.floor(math.log10(abs(x))))
    mantissa = x / 10**exponent
    if round(mantissa, digits - 1) >= 10:
        mantissa, exponent = mantissa / 10, exponent + 1
    return f"{mantissa:.{digits - 1}f}\\times10^{{{exponent}}}"


def round_significant(x: float, digits: int = 3) -> float:
    """x rounded to ``digits`` significant digits (a grid energy as the text quotes it)."""
    return float(f"{x:.{digits}g}")


def plain_number(x, digits: int = 6, missing: str = "nan") -> str:
    """A number without math: ``digits`` significant digits (%g), ``missing`` when not finite."""
    return f"{x:.{digits}g}" if math.isfinite(x) else missing


def tex_escape(name) -> str:
    """A name (scene, scheme, claim id) for LaTeX text: underscores escaped."""
    return str(name).replace("_", r"\_")
