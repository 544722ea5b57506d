"""The manuscript's "Beyond the paper" table: the power laws of kept studies beside published values.

One row per (study, model, energy, law) of the studies' ``laws.nc`` files
(``chainchaos.studies.study.laws``): the exponent fitted over its window, its 95% bootstrap
interval over realizations, whether the window settled, the published exponent and whether it
lies inside the interval (where the publication gives an uncertainty, whether the two intervals
overlap); and one per crossover: the largest local derivative, its band and when, beside the
published slopes. Every number comes from the files.
"""

import math
import re

import xarray as xr

from chainchaos.records.formatting import tex_parameter, tex_scientific

#: How a law's series reads in the table.
SYMBOLS = {"second_moment": r"$\langle\log_{10} m_2\rangle$", "participation": r"$\langle\log_{10} P\rangle$",
           "mlce": r"$\langle\log_{10}\Lambda\rangle$", "abs_mlce": r"$\langle\log_{10}|\Lambda|\rangle$"}


#: How a crossover's local derivative reads in the table.
CROSSOVER_SYMBOLS = {"second_moment": r"$d\langle\log_{10} m_2\rangle/d\log_{10}t$",
                     "participation": r"$d\langle\log_{10} P\rangle/d\log_{10}t$"}


_TEX_SPECIAL = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "#": r"\#", "_": r"\_", "$": r"\$",
                "^": r"\^{}", "~": r"\~{}", "{": r"\{", "}": r"\}", "|": r"\textbar{}", "<": r"\textless{}",
                ">": r"\textgreater{}"}


def tex_text(text: str) -> str:
    """Plain text set in LaTeX: its special characters escaped (in one pass)."""
    return re.sub(r"[\\&%#_$^~{}|<>]", lambda m: _TEX_SPECIAL[m.group(0)], text)


def _number(x: float) -> str:
    return f"${x:.3f}$" if math.isfinite(x) else "---"


def _decade(t: float) -> str:
    return f"$10^{{{math.log10(t):.1f}}}$"


def law_rows(name: str, ds: xr.Dataset) -> list[dict]:
    """The rows of one study's laws file, plain values."""
    rows = []
    for model in ds["model"].values:
        for energy in ds["energy"].values:
            for law in range(ds.sizes["law"]):
                fit = ds.sel(model=model, energy=energy).isel(law=law)
                lower, upper, expected = float(fit["lower"]), float(fit["upper"]), float(fit["expected"])
                uncertainty = float(fit["uncertainty"]) if "uncertainty" in fit else math.nan
                # a published interval: do the two overlap? a bare value: is it inside ours?
                inside = (lower <= expected + uncertainty and expected - uncertainty <= upper
                          if math.isfinite(uncertainty) else lower <= expected <= upper)
                rows.append({
                    "study": name, "model": str(model), "energy": float(energy),
                    "series": str(fit["series"].values), "exponent": float(fit["exponent"]),
                    "lower": lower, "upper": upper, "t_start": float(fit["t_start"]), "t_end": float(fit["t_end"]),
                    "settled": bool(int(fit["settled"])), "realizations": int(fit["realizations"]),
                    "t_walls": float(fit["t_walls"]),
                    "expected": expected, "uncertainty": uncertainty, "reference": str(fit["reference"].values),
                    "inside": inside,
                    "self_trapped": float(fit["self_trapped"]) if "self_trapped" in fit else math.nan,
                })
    return rows


def crossover_rows(name: str, ds: xr.Dataset) -> list[dict]:
    """The crossovers of one study's laws file (``laws.crossovers``): the largest local derivative,
    its band and when, beside the published slopes; ``inside`` whether the first slope (the
    strong-chaos 1/2) lies in the band there."""
    rows = []
    if "crossover_max" not in ds:
        return rows
    for model in ds["model"].values:
        for energy in ds["energy"].values:
            for c in range(ds.sizes["crossover"]):
                found = ds.sel(model=model, energy=energy).isel(crossover=c)
                lines = [float(x) for x in ds["crossover_lines"].isel(crossover=c).values]
                lower, upper = float(found["crossover_max_lower"]), float(found["crossover_max_upper"])
                rows.append({"study": name, "model": str(model), "energy": float(energy),
                             "series": str(ds["crossover"].values[c]), "max": float(found["crossover_max"]),
                             "lower": lower, "upper": upper, "t_max": float(found["crossover_t_max"]),
                             "lines": lines, "reference": str(ds["crossover_reference"].values[c]),
                             "inside": lower <= lines[0] <= upper})
    return rows


def beyond_table(named: dict[str, xr.Dataset]) -> str:
    """The LaTeX table (a tabular) of every law of the studies ``named`` (name -> laws Dataset)."""
    split = any("norm_error_max" in ds for ds in named.values())  # a split model's amount is its norm S
    amount = r"$H$ or norm $S$" if split else "$H$"
    lines = [r"\begin{tabular}{llllllll}", r"\hline",
             rf"study & model, {amount} & law & exponent [95\,\%] & window & $R$ & published & inside \\", r"\hline"]
    for name, ds in named.items():
        for r in law_rows(name, ds):
            study, model = tex_text(r["study"]), tex_text(r["model"])
            bounded = math.isfinite(r["lower"]) and math.isfinite(r["upper"])
            interval = f"[{_number(r['lower'])}, {_number(r['upper'])}]" if bounded else "(no interval)"
            inside = ("yes" if r["inside"] else "no") if bounded else "---"
            walls = r"$^\ddagger$" if math.isfinite(r["t_walls"]) else ""
            if math.isfinite(r["exponent"]):
                window = f"{_decade(r['t_start'])}--{_decade(r['t_end'])}" + ("" if r["settled"] else r"$^\dagger$")
            elif math.isfinite(r["t_walls"]):
                interval, window = "(chain too short)", f"ends felt at {_decade(r['t_walls'])}"
            else:
                interval, window = "(run too short)", "---"
            window += walls
            if r["self_trapped"] > 0.5:  # most realizations keep most of the packet on one site
                interval += f" (self-trapped in {100 * r['self_trapped']:.0f}\\,\\%: not a spreading law)"
                inside = "---"
            published = (f"${r['expected']:.3g} \\pm {r['uncertainty']:.2g}$" if math.isfinite(r["uncertainty"])
                         else f"${r['expected']:.3g}$")
            lines.append(f"\\texttt{{{study}}} & {model}, {r['energy']:g} & {SYMBOLS[r['series']]} & "
                         f"{_number(r['exponent'])} {interval} & {window} & "
                         f"{r['realizations']} & {published} & {inside} \\\\")
        for r in crossover_rows(name, ds):
            band = f"[{_number(r['lower'])}, {_number(r['upper'])}]" if math.isfinite(r["lower"]) else "(no band)"
            at = f"largest at {_decade(r['t_max'])}" if math.isfinite(r["t_max"]) else "---"
            slopes = r" $\to$ ".join(f"${x:.3g}$" for x in r["lines"])
            lines.append(f"\\texttt{{{tex_text(r['study'])}}} & {tex_text(r['model'])}, {r['energy']:g} & "
                         f"{CROSSOVER_SYMBOLS[r['series']]} & {_number(r['max'])} {band} & {at} & --- & {slopes} & "
                         f"{'yes' if r['inside'] else 'no'} \\\\")
    lines += [r"\hline", r"\end{tabular}"]
    return "\n".join(lines) + "\n"


def _walls_rule(attrs) -> str:
    """How a laws file's runs were cut at the chain's ends (its ``walls_*`` attributes)."""
    edge, fraction = attrs.get("walls_edge_energy", "none"), attrs.get("walls_participation_fraction", "none")
    cuts = ""
    if edge != "none":
        cuts += f", $m_2$ cut where $\\langle\\log_{{10}} E_{{\\rm edge}}/H\\rangle$ exceeds $\\log_{{10}} {tex_parameter(edge)}$"
    if fraction != "none":
        cuts += f", every law cut where $\\langle\\log_{{10}} P\\rangle$ exceeds $\\log_{{10}}({tex_parameter(fraction)} N)$"
    return cuts


def figure_key(study: str, figure: str) -> str:
    """The name of a study's figure among the manuscript's "beyond" files."""
    return f"{study}_{figure}"


def body(named: dict[str, xr.Dataset], figures: dict[str, list[str]]) -> str:
    """The generated part of the section: the table of laws with its sources, and each study's
    ``figures`` (study -> figure names, files ``beyond/<study>_<figure>.pdf``)."""
    sources = dict.fromkeys(r["reference"] for name, ds in named.items()
                            for r in [*law_rows(name, ds), *crossover_rows(name, ds)])
    by_rule: dict[str, list[str]] = {}
    for name, ds in named.items():
        rule = (f"from $t = {ds.attrs['fit_t_min']:g}$, band ${ds.attrs['fit_band']:g}$ around the median running "
                f"slope (over {ds.attrs['fit_window_decades']:g} decade) of the last {ds.attrs['fit_min_decades']:g} "
                f"decade, {ds.attrs['fit_bootstrap']} resamples" + _walls_rule(ds.attrs))
        by_rule.setdefault(rule, []).append(name)
    rules = "; ".join(rule if len(by_rule) == 1 else
                      ", ".join(f"\\texttt{{{tex_text(n)}}}" for n in names) + ": " + rule
                      for rule, names in by_rule.items())
    out = [r"\begin{table}[htbp]",
           r"\caption{\label{tab:laws}Exponents of the ensemble means against $\log_{10} t$ (valid realizations, "
           r"$R$ the fewest in the window), with 95\,\% bootstrap intervals over realizations and the window "
           r"chosen by the running slope (Sec.~\ref{sec:beyond}; $^\dagger$: the slope has not settled, the window "
           r"is the minimum; $^\ddagger$: the run is cut where the chain's ends are felt, and a law left with less "
           r"than the minimum window is not fitted), beside the published exponents; inside: the published "
           r"exponent lies in our interval or, where the publication gives an uncertainty ($\pm$), the two intervals "
           r"overlap; a crossover's row gives the largest local derivative with its band there and when, and whether "
           r"the first published slope lies in that band. Rules: " + rules + ". Sources: " + "; ".join(tex_text(s) for s in sources) + ".}",
           r"\centering\small", r"\fitwidth{" + beyond_table(named).rstrip() + "}", r"\end{table}"]
    out.append("Runs (the kept groups' job time, CPU or else wall): " + "; ".join(
        f"\\texttt{{{tex_text(name)}}} {ds.attrs['cost_s'] / 60:.0f} {ds.attrs['cost_kind']}-min, largest relative energy error "
        f"${tex_scientific(float(ds['energy_error_max'].max()))}$" + _norm_error(ds) for name, ds in named.items())
               + ".\n")
    for study, names in figures.items():
        for figure in names:
            label = tex_text(study)
            out += [r"\begin{figure}[htbp]", r"\centering",
                    (f"\\includegraphics[width=\\linewidth,height=0.42\\textheight,keepaspectratio]"
                     f"{{beyond/{figure_key(study, figure)}}}"),
                    (f"\\caption{{\\label{{fig:beyond-{study}-{figure}}}Study \\texttt{{{label}}}: its {figure} "
                     f"figure ({FIGURE_TEXT[figure]}).}}"), r"\end{figure}"]
    return "\n".join(out) + "\n"


def _norm_error(ds: xr.Dataset) -> str:
    """", largest relative norm error ..." of a split model's study (nothing for a bond model's)."""
    if "norm_error_max" not in ds:
        return ""
    return f", largest relative norm error ${tex_scientific(float(ds['norm_error_max'].max()))}$"


FIGURE_TEXT = {
    "spreading": r"$\langle\log_{10} m_2\rangle$ and $\langle\log_{10} P\rangle$ against $\log_{10} t$ with "
                 r"quantile bands and running slopes",
    "chaos": r"$\langle\log_{10}\Lambda\rangle$ against $\log_{10} t$ with quantile bands and its running slope",
    "comparison": ("the ensemble means of the study beside those of the studies it compares with; a Klein--Gordon "
                   "or DNLS chain's times are in the units of its Hamiltonian, the bead chains' in $1/\\omega_{\\max}$"),
    "fractions": "fractions chaotic and delocalized against the energy, Wilson 95\\,\\% bands",
    "maps": ("the density of one orbit, its first valid realization, at the study's map times: on a square "
             "lattice the sites $(i, j)$ on a logarithmic colour scale from $10^{-8}$ to 1, cropped to the sites "
             "above $10^{-8}$; on a chain its profiles on a logarithmic axis"),
}
