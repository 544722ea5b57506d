"""The claims as files: claims.csv, the LaTeX claims table and notes, the scenes table, and
macros.tex, every number the manuscript prints as ``\\cc{key}``."""

import csv
from dataclasses import fields

import numpy as np
import xarray as xr

from chainchaos.paper.claims import quantities as q
from chainchaos.paper.claims.framework import (
    DIFFERS,
    REPRODUCED,
    UNDECIDED,
    UNTESTABLE,
    Claim,
)
from chainchaos.paper.criteria import Criteria
from chainchaos.records.formatting import (
    round_significant,
    tex_escape,
    tex_math,
    tex_number,
    tex_parameter,
)
from chainchaos.paper.thresholds import thresholds_table
from chainchaos.system.models import model_label

CSV_FIELDS = [f.name for f in fields(Claim)]


def write_csv(claims: list[Claim], path) -> None:
    with open(path, "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=CSV_FIELDS)
        writer.writeheader()
        for claim in claims:
            row = claim.row()
            writer.writerow({k: ("" if v is None else v) for k, v in row.items()})


VERDICT_TEX = {REPRODUCED: r"\verdictok", DIFFERS: r"\verdictdiffers", UNDECIDED: r"\verdictundecided",
               UNTESTABLE: r"\verdictuntestable"}


def _error(claim: Claim) -> str:
    return tex_math(claim.max_energy_error, 2) if claim.max_energy_error is not None else "--"


def claims_table_tex(claims: list[Claim]) -> str:
    """A longtable of the claims (needs the array and longtable packages; \\verdictok etc. are
    defined in macros.tex)."""
    col = r">{\raggedright\arraybackslash}p"
    head = r"\# & Statement of the paper & Paper & Measured here & Error & Verdict\\ \hline"
    lines = [
        r"\begingroup\footnotesize\setlength{\LTcapwidth}{\linewidth}\setlength{\tabcolsep}{3pt}",
        rf"\begin{{longtable}}{{@{{}}r {col}{{0.32\linewidth}} {col}{{0.085\linewidth}} {col}{{0.30\linewidth}} "
        rf"{col}{{0.085\linewidth}} {col}{{0.095\linewidth}}@{{}}}}",
        r"\caption{\label{tab:claims}The paper's quantitative statements beside the values this build "
        r"measured. ``Error'' is the largest relative energy error $|H(t)-H(0)|/H(0)$ of the scenes "
        r"the claim rests on. A verdict with a fraction was decided on an ensemble of orbits of the "
        r"scene, perturbed at the $10^{-9}$ level: the fraction of them that satisfy each statement "
        r"the claim rests on; a statement about chaos is decided by $\Lambda$ and by GALI$_k$ separately "
        r"(each fraction over the orbits it decides), and is undecided where they disagree. Criteria and "
        r"reasons follow the table.}\\",
        r"\hline\hline",
        head,
        r"\endfirsthead",
        r"\hline " + head,
        r"\endhead",
        r"\hline\hline",
        r"\endlastfoot",
    ]
    for i, claim in enumerate(claims, 1):
        lines.append(f"{i} & {claim.statement}\\newline{{\\scriptsize [{claim.where}]}} & {claim.paper} & "
                     f"{claim.measured_text} & {_error(claim)} & {VERDICT_TEX[claim.verdict]}"
                     + (f"\\newline{{\\scriptsize {claim.fraction}}}" if claim.fraction else "") + "\\\\[2pt]")
    lines += [r"\end{longtable}", r"\endgroup", ""]
    return "\n".join(lines)


def scenes_table_tex(scenes: dict) -> str:
    """One row per scene: model, H, u_21(0), scheme, dt, t_final, largest relative energy error."""
    lines = [
        r"\begin{table}[htbp]",
        r"\caption{\label{tab:scenes}The simulated scenes as run: initial displacement of bead 21 solved "
        r"from each model's exact potential, scheme, step, final time, and the largest relative energy "
        r"error $\max_t |H(t)-H(0)|/H(0)$ over the samples.}",
        r"\begin{ruledtabular}",
        r"\begin{tabular}{llllllll}",
        r"Scene & Model & $H$ & $u_{21}(0)$ & Scheme & $\Delta t$ & $t_\mathrm{end}$ & max.\ energy error\\ \hline",
    ]
    order = sorted(scenes, key=lambda n: (scenes[n].attrs["model"] != "hertz", float(scenes[n].attrs["energy"])))
    for name in order:
        a = scenes[name].attrs
        cells = [rf"\texttt{{{tex_escape(name)}}}", model_label(a["model"]), f"${tex_parameter(a['energy'])}$",
                 tex_math(float(a["u0"]), 4), tex_escape(a["integrator"]), f"${tex_parameter(a['dt'])}$",
                 f"${tex_parameter(a['t_final'])}$", tex_math(float(a["max_energy_error"]), 2)]
        lines.append(" & ".join(cells) + r"\\")
    lines += [r"\end{tabular}", r"\end{ruledtabular}", r"\end{table}", ""]
    return "\n".join(lines)


def claims_notes_tex(claims: list[Claim]) -> str:
    """Criterion of every claim, and the reason of every verdict other than reproduced."""
    lines = [r"\begin{enumerate}\small"]
    for claim in claims:
        note = f"\\item \\texttt{{{tex_escape(claim.id)}}}: {claim.criterion}."
        if claim.reason:
            note += f" \\emph{{{claim.verdict.capitalize()}}}: {claim.reason.rstrip('.')}."
        lines.append(note)
    lines += [r"\end{enumerate}", ""]
    return "\n".join(lines)


# --------------------------------------------------------------------------------------------
# macros.tex
# --------------------------------------------------------------------------------------------


def tex_macro(key: str, value: str) -> str:
    """A \\newcommand for key (any characters but braces and backslashes), read with \\cc{key}."""
    if any(ch in key for ch in "{}\\%#"):
        raise ValueError(f"macro key {key!r} contains a TeX special character")
    return f"\\expandafter\\newcommand\\csname cc@{key}\\endcsname{{{value}}}"


MACRO_PREAMBLE = r"""% Generated by workflow/scripts/evaluate_claims.py: every measured number of the manuscript.
% Use \cc{key}; an unknown key stops the build (no number is typed by hand in ms.tex).
\makeatletter
\providecommand{\cc}[1]{\ifcsname cc@#1\endcsname\csname cc@#1\endcsname\else
  \PackageError{claims}{Unknown measured value '#1'}{macros.tex defines no such key}\fi}
\makeatother
\providecommand{\verdictok}{reproduced}
\providecommand{\verdictdiffers}{\textbf{differs}}
\providecommand{\verdictundecided}{\emph{undecided}}
\providecommand{\verdictuntestable}{\emph{not testable}}
"""


def macros_tex(values: dict[str, str]) -> str:
    return MACRO_PREAMBLE + "\n".join(tex_macro(k, v) for k, v in sorted(values.items())) + "\n"


def claim_macros(claims: list[Claim]) -> dict[str, str]:
    """claim.<id>.measured / .paper / .verdict / .error for every claim, and verdict counts."""
    out = {}
    for number, claim in enumerate(claims, 1):
        out[f"claim.{claim.id}.n"] = str(number)
        out[f"claim.{claim.id}.measured"] = claim.measured_text
        out[f"claim.{claim.id}.value"] = tex_math(claim.measured) if claim.measured is not None else "--"
        out[f"claim.{claim.id}.paper"] = claim.paper
        out[f"claim.{claim.id}.verdict"] = claim.verdict
        out[f"claim.{claim.id}.error"] = _error(claim)
    for verdict, key in ((REPRODUCED, "reproduced"), (DIFFERS, "differs"), (UNDECIDED, "undecided"),
                         (UNTESTABLE, "untestable")):
        numbers = [str(i) for i, c in enumerate(claims, 1) if c.verdict == verdict]
        out[f"list.{key}"] = ", ".join(numbers) if numbers else "none"
    out["count.total"] = str(len(claims))
    out["count.reproduced"] = str(sum(c.verdict == REPRODUCED for c in claims))
    out["count.differs"] = str(sum(c.verdict == DIFFERS for c in claims))
    out["count.undecided"] = str(sum(c.verdict == UNDECIDED for c in claims))
    out["count.untestable"] = str(sum(c.verdict == UNTESTABLE for c in claims))
    return out


def scene_macros(name: str, ds: xr.Dataset, criteria: Criteria) -> dict[str, str]:
    """Numbers of one scene: u0, run parameters, energy errors, final P, Lambda, eta."""
    a = ds.attrs
    out = {
        f"scene.{name}.u0": tex_number(float(a["u0"]), 4),
        f"scene.{name}.dt": tex_parameter(float(a["dt"])),
        f"scene.{name}.tfinal": tex_parameter(float(a["t_final"])),
        f"scene.{name}.integrator": str(a["integrator"]),
        f"scene.{name}.maxerr": tex_number(float(a["max_energy_error"]), 2),
        f"scene.{name}.finalerr": tex_number(float(a["final_energy_error"]), 2),
    }
    if "participation" in ds:
        out[f"scene.{name}.Pfinal"] = tex_number(q.final_mean(ds, "participation", criteria.final_window_decades))
    if "mlce" in ds:
        out[f"scene.{name}.mlce"] = tex_number(q.final_mlce(ds))
        out[f"scene.{name}.slope"] = tex_number(q.mlce_slope(ds, criteria.chaos_window_decades), 2)
        out[f"scene.{name}.growth"] = tex_number(q.growth_excess(ds, criteria.chaos_window_decades), 2)
    if "eta" in ds:
        out[f"scene.{name}.etafinal"] = tex_number(q.final_mean(ds, "eta", criteria.eta_final_window_decades))
        out[f"scene.{name}.etaeq"] = tex_number(q.equipartition_eta(ds))
    return out


def _first_phrase(adjective: str, first: float) -> str:
    """The lowest scanned energy where a criterion holds, as a phrase for running text (NaN:
    it holds nowhere)."""
    return (f"first {adjective} at $H = {tex_number(first)}$" if np.isfinite(first)
            else f"{adjective} at no scanned energy")


def _always_phrase(adjective: str, always: float, first: float, top: float) -> str:
    """The energy above which a criterion always holds, as a phrase for running text (NaN: it
    fails at the highest scanned energy ``top``, or, with ``first`` NaN too, everywhere)."""
    if np.isfinite(always):
        return f"{adjective} at every scanned $H \\ge {tex_number(always)}$"
    if not np.isfinite(first):
        return f"{adjective} at no scanned energy"
    return f"not {adjective} at the highest scanned energy, $H = {tex_parameter(round_significant(top))}$"


def _half_phrase(model: str, verb: str, half: float) -> str:
    """The lowest grid energy at which at least half of a model's realizations ``verb`` (e.g.
    delocalize), as a clause for running text (NaN: no energy of the grid)."""
    runs = f"the {model_label(model)} realizations"
    if np.isfinite(half):
        return f"the lowest energy of the grid at which at least half of {runs} {verb} is $H = {tex_number(half)}$"
    return f"at no energy of the grid do at least half of {runs} {verb}"


def scan_macros(energy_scan: xr.Dataset, disorder: xr.Dataset) -> dict[str, str]:
    """Numbers of the energy scan (grid, run, thresholds per model and criterion) and of the
    disorder statistics (realizations, grid, and per model and criterion: the probability at the
    highest energy with its 95% band, the lowest energy where at least half of the runs qualify).
    The thresholds are phrases for running text, which say so when no energy of the grid qualifies."""
    out = {}
    for prefix, ds in (("scan", energy_scan), ("disorder", disorder)):
        a = ds.attrs
        E = ds.energy.values
        out.update({f"{prefix}.nenergies": str(E.size), f"{prefix}.emin": tex_parameter(round_significant(E[0])),
                    f"{prefix}.emax": tex_parameter(round_significant(E[-1])),
                    f"{prefix}.tfinal": tex_parameter(a["t_final"]), f"{prefix}.dt": tex_parameter(a["dt"]),
                    f"{prefix}.integrator": tex_escape(a["integrator"]),
                    f"{prefix}.pdeloc": tex_parameter(a["p_delocalized"]),
                    f"{prefix}.chaosslope": tex_parameter(a["chaos_slope"])})
        out[f"{prefix}.invalid"] = str(int((ds["valid"].values != 1).sum()))
        out[f"{prefix}.maxerr"] = tex_number(q.max_energy_error(ds), 2)
    # criterion of the thresholds table -> (macro key, adjective in the text)
    flags = {"delocalization": ("delocalized", "delocalized"), "chaos": ("chaotic", "chaotic"),
             "chaos by GALI": ("chaoticgali", "chaotic by GALI$_k$")}
    top = float(energy_scan.energy.values[-1])
    for row in thresholds_table(energy_scan):
        name, adjective = flags[row["criterion"]]
        key = f"scan.{row['model']}.{name}"
        out[f"{key}.first"] = _first_phrase(adjective, row["first_energy"])
        out[f"{key}.always"] = _always_phrase(adjective, row["always_above"], row["first_energy"], top)
    out["disorder.realizations"] = str(disorder.sizes["realization"])
    out["disorder.alpha"] = tex_parameter(disorder.attrs["alpha"])
    E = disorder.energy.values
    verbs = {"delocalized": "delocalize", "chaotic": "turn chaotic", "chaotic_gali": "turn chaotic by GALI$_k$"}
    for model in disorder.model.values:
        for key in (k for k in verbs if f"probability_{k}" in disorder):
            p = disorder[f"probability_{key}"].sel(model=model).values
            lo = disorder[f"probability_{key}_lower"].sel(model=model).values
            hi = disorder[f"probability_{key}_upper"].sel(model=model).values
            share, low, high = (tex_number(100 * x[-1], 2) for x in (p, lo, hi))
            out[f"disorder.{model}.{key.replace('_', '')}.top"] = f"{share}\\,\\% ({low}--{high}\\,\\%)"
            half = E[np.nan_to_num(p) >= 0.5]
            out[f"disorder.{model}.{key.replace('_', '')}.half"] = _half_phrase(str(model), verbs[key],
                                                               float(half[0]) if half.size else np.nan)
    return out


def run_macros(scenes: dict, chain: xr.Dataset, ensemble: xr.Dataset, simulation: dict, criteria: Criteria,
               taylor_barrier: float) -> dict[str, str]:
    """The run's numbers: its settings (from the scenes, overridden by the config block
    ``simulation``), energy errors, the ensemble and the chosen chain, and every criterion and
    tolerance of the claims (``crit.*``, ``tol.*``)."""
    any_scene = next(iter(scenes.values()))
    simulation = {"t_final": any_scene.attrs["t_final"], "dt": any_scene.attrs["dt"],
                  "integrator": any_scene.attrs["integrator"], **(simulation or {})}
    errors = {n: float(ds.attrs["max_energy_error"]) for n, ds in scenes.items()}
    t_final = float(simulation["t_final"])
    dt = float(simulation["dt"])
    realizations = int(ensemble.attrs["n_realizations"])
    paper_scale = t_final >= 1e5 and dt <= 5e-4 and realizations >= 1000
    alphas = [float(a) for a in ensemble["alpha"].values]
    out = {
        "run.integrator": tex_escape(simulation["integrator"]),
        "run.order": str(int(any_scene.attrs.get("integrator_order", 0))),
        "run.dt": tex_parameter(dt),
        "run.tfinal": tex_parameter(t_final),
        "run.samples": str(int(simulation.get("samples_per_decade", 40))),
        "run.checkevery": str(int(simulation.get("check_every", 1000))),
        "run.errorbound": tex_number(float(simulation.get("max_energy_error", 1e-2)), 2),
        "run.kfoursign": "+1" if float(simulation.get("k4_sign", 1)) > 0 else "-1",
        "run.deviationseed": str(int(simulation.get("deviation_seed", 0))),
        "run.site": str(int(simulation.get("excited_site", 21))),
        "run.scale": "paper" if paper_scale else "reduced",
        "run.nscenes": str(len(scenes)),
        "run.maxerr": tex_number(max(errors.values()), 2),
        "run.maxerr.hertz": tex_number(max(v for n, v in errors.items() if n.startswith("hertz")), 2),
        "run.maxerr.fput": tex_number(max(v for n, v in errors.items() if n.startswith("fput")), 2),
        "run.commit": str(any_scene.attrs.get("git_commit", "unknown"))[:12],
        "run.version": str(any_scene.attrs.get("chainchaos_version", "unknown")),
        "ensemble.realizations": str(realizations),
        "ensemble.alphas": ", ".join(f"{a:g}" for a in alphas),
        "ensemble.firstseed": str(int(ensemble.attrs.get("first_seed", 0))),
        "ensemble.convention": str(ensemble.attrs.get("convention", "potential")).replace("_", "-"),
        "chain.alpha": f"{float(chain.attrs['alpha']):g}",
        "chain.N": str(chain.sizes["site"]),
        "chain.seed": str(int(chain.attrs["seed"])),
        "chain.generator": tex_escape(chain.attrs.get("generator", "")),
        "chain.wallradius": f"{float(chain.attrs.get('wall_radius', 1.0)):g}",
        "chain.P34": tex_number(float(chain["mode_participation"].values[33])),
        "chain.Pmax": tex_number(float(np.max(chain["mode_participation"].values))),
        "chain.omegamin": tex_number(float(np.min(chain["frequency"].values))),
        "chain.omegamax": tex_number(float(np.max(chain["frequency"].values))),
        "chain.omega34": tex_number(float(chain["frequency"].values[33])),
        "chain.delta21": tex_number(float(chain["delta"].values[20])),
        "chain.delta22": tex_number(float(chain["delta"].values[21])),
        "chain.taylorbarrier": tex_number(taylor_barrier),
    }
    if "mode_participation_period_averaged" in chain:
        out["chain.P34pa"] = tex_number(float(chain["mode_participation_period_averaged"].values[33]))
    for key in ("candidates", "seeds_scanned", "score", "mode_participation"):
        attr = f"selection_{key}"
        if attr in chain.attrs:
            value = chain.attrs[attr]
            out[f"chain.selection.{key.replace('_', '')}"] = (
                str(int(value)) if float(value).is_integer() else tex_number(float(value)))
    for key, value in vars(criteria).items():
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[f"crit.{key.replace('_', '')}"] = tex_parameter(value)
    for key, value in vars(criteria.tolerance).items():
        out[f"tol.{key.replace('_', '')}"] = tex_parameter(value)
    for name, end in criteria.plateau_end.items():
        out[f"crit.plateauend.{name}"] = tex_parameter(float(end))
    return out
