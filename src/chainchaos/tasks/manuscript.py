"""Tasks of workflow/rules/manuscript.smk: the paper's claims measured on the results, and the
manuscript built from them (chainchaos.manuscript)."""

import sys

import numpy as np
import xarray as xr

from chainchaos import claims as cl
from chainchaos import manuscript, search_report
from chainchaos.io import atomic_output, write_text


def run_macros(scenes: dict, chain: xr.Dataset, ensemble: xr.Dataset, simulation: dict, criteria) -> dict:
    """The manuscript's numbers (key -> LaTeX) of the run settings, the ensemble, the chain and its
    selection, and the claims' criteria and tolerances."""
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
        "run.integrator": str(simulation["integrator"]).replace("_", r"\_"),
        "run.order": str(int(any_scene.attrs.get("integrator_order", 0))),
        "run.dt": cl.g(dt),
        "run.tfinal": cl.g(t_final),
        "run.samples": str(int(simulation.get("samples_per_decade", 40))),
        "run.checkevery": str(int(simulation.get("check_every", 1000))),
        "run.errorbound": cl.fmt(float(simulation.get("max_energy_error", 1e-2)), 2),
        "run.kfoursign": "+1" if float(simulation.get("k4_sign", 1)) > 0 else "-1",
        "run.deviationseed": str(int(simulation.get("deviation_seed", 0))),
        "run.site": str(int(simulation.get("excited_site", 21))),
        "run.scale": "paper" if paper_scale else "reduced",
        "run.nscenes": str(len(scenes)),
        "run.maxerr": cl.fmt(max(errors.values()), 2),
        "run.maxerr.hertz": cl.fmt(max(v for n, v in errors.items() if n.startswith("hertz")), 2),
        "run.maxerr.fput": cl.fmt(max(v for n, v in errors.items() if n.startswith("fput")), 2),
        "run.commit": str(any_scene.attrs.get("git_commit", "unknown"))[:12],
        "run.version": str(any_scene.attrs.get("chainchaos_version", "unknown")),
        "ensemble.realizations": str(realizations),
        "ensemble.alphas": ", ".join(f"{a:g}" for a in alphas),
        "ensemble.firstseed": str(int(ensemble.attrs.get("first_seed", 0))),
        "ensemble.convention": str(ensemble.attrs.get("convention", "potential")).replace("_", "-"),
        "chain.alpha": f"{float(chain.attrs['alpha']):g}",
        "chain.N": str(chain.sizes["site"]),
        "chain.seed": str(int(chain.attrs["seed"])),
        "chain.generator": str(chain.attrs.get("generator", "")).replace("_", r"\_"),
        "chain.wallradius": f"{float(chain.attrs.get('wall_radius', 1.0)):g}",
        "chain.P34": cl.fmt(float(chain["mode_participation"].values[33])),
        "chain.Pmax": cl.fmt(float(np.max(chain["mode_participation"].values))),
        "chain.omegamin": cl.fmt(float(np.min(chain["frequency"].values))),
        "chain.omegamax": cl.fmt(float(np.max(chain["frequency"].values))),
        "chain.omega34": cl.fmt(float(chain["frequency"].values[33])),
        "chain.delta21": cl.fmt(float(chain["delta"].values[20])),
        "chain.delta22": cl.fmt(float(chain["delta"].values[21])),
    }
    out["chain.taylorbarrier"] = cl.fmt(cl.taylor_sign_barrier(chain, int(simulation.get("excited_site", 21))))
    if "mode_participation_period_averaged" in chain:
        out["chain.P34pa"] = cl.fmt(float(chain["mode_participation_period_averaged"].values[33]))
    for key in ("candidates", "seeds_scanned", "score", "mode_participation"):
        attr = f"selection_{key}"
        if attr in chain.attrs:
            value = chain.attrs[attr]
            out[f"chain.selection.{key.replace('_', '')}"] = (
                str(int(value)) if float(value).is_integer() else cl.fmt(float(value)))
    for key, value in vars(criteria).items():
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[f"crit.{key.replace('_', '')}"] = cl.g(value)
    for key, value in vars(criteria.tolerance).items():
        out[f"tol.{key.replace('_', '')}"] = cl.g(value)
    out["tol.timefactor"] = cl.g(criteria.tolerance.time_factor)
    for name, end in criteria.plateau_end.items():
        out[f"crit.plateauend.{name}"] = cl.g(float(end))
    return out


def evaluate_claims(inputs, outputs, params, wildcards) -> None:
    """Measure the paper's claims on the results: claims.csv, claims_table.tex, claims_notes.tex,
    scenes_table.tex, search_table.tex and macros.tex (every number the manuscript prints, as \\cc{key})."""
    inputs = dict(inputs)
    inputs.pop("code", None)
    chain = xr.load_dataset(inputs.pop("chain"))
    ensemble = xr.load_dataset(inputs.pop("ensemble"))
    energy_scan = xr.load_dataset(inputs.pop("energy_scan"))
    disorder = xr.load_dataset(inputs.pop("disorder"))
    search = xr.load_dataset(inputs.pop("search"))
    verdicts = {name[len("verdict_"):]: xr.load_dataset(inputs.pop(name))
                for name in sorted(inputs) if name.startswith("verdict_")}
    scenes = {name: xr.load_dataset(path) for name, path in inputs.items()}
    criteria = cl.Criteria.from_config(params.get("claims"))
    site = int(params.get("simulation", {}).get("excited_site", 21))
    claims = cl.evaluate_claims(scenes, chain, ensemble, criteria, excited_site=site, energy_scan=energy_scan,
                                verdicts=verdicts, search=search, disorder=disorder)

    macros = run_macros(scenes, chain, ensemble, params.get("simulation", {}), criteria)
    macros.update(cl.scan_macros(energy_scan, disorder))
    for name, ds in scenes.items():
        macros.update(cl.scene_macros(name, ds, criteria))
    macros.update(cl.claim_macros(claims))
    macros.update(search_report.search_macros(search, verdicts, energy_scan, disorder, criteria.agreement))
    paper_scale = macros["run.scale"] == "paper"

    with atomic_output(outputs["csv"]) as tmp:
        cl.write_csv(claims, tmp)
    write_text(cl.claims_table_tex(claims), outputs["table"])
    write_text(cl.claims_notes_tex(claims), outputs["notes"])
    write_text(cl.scenes_table_tex(scenes), outputs["scenes"])
    write_text(search_report.search_table_tex(search, verdicts), outputs["search"])
    write_text(cl.macros_tex(macros)
               + "\\newif\\ifpaperscale\n" + ("\\paperscaletrue\n" if paper_scale else "\\paperscalefalse\n")
               + "\\newif\\ifsearchpinned\n"
               + ("\\searchpinnedtrue\n" if int(search.attrs["pinned"]) else "\\searchpinnedfalse\n"),
               outputs["macros"])
    for claim in claims:
        print(f"{claim.id:28s} {claim.verdict:28s} {claim.measured}", file=sys.stderr)


def build_manuscript(inputs, outputs, params, wildcards) -> None:
    """latexmk in the build directory on a copy of manuscript/ms.tex and of its inputs; a
    :class:`~chainchaos.manuscript.BuildError` (TeX missing, a LaTeX error) names what to do."""
    figures = {k: v for k, v in inputs.items() if k.startswith("fig")}
    numerics = {k[len("numerics_"):]: v for k, v in inputs.items() if k.startswith("numerics_")}
    manuscript.build(inputs["tex"], {k: inputs[k] for k in manuscript.GENERATED}, figures, numerics, outputs["pdf"],
                     params["build_dir"])


TASKS = (evaluate_claims, build_manuscript)
