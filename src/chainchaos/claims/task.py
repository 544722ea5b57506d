"""What the rule ``evaluate_claims`` runs: the claims measured on the results, and every number the
manuscript prints (claims.csv, claims_table.tex, claims_notes.tex, scenes_table.tex,
search_table.tex, macros.tex)."""

import sys

import numpy as np
import xarray as xr

from chainchaos import search_report
from chainchaos.claims.evaluation import evaluate_claims
from chainchaos.claims.quantities import taylor_sign_barrier
from chainchaos.claims.writers import (claim_macros, claims_notes_tex, claims_table_tex, macros_tex, scan_macros,
                                       scene_macros, scenes_table_tex, write_csv)
from chainchaos.criteria import Criteria
from chainchaos.formatting import tex_escape, tex_number, tex_parameter
from chainchaos.io import atomic_output, read_chain, write_text

#: The inputs of the rule that are not scene files (and the prefix of the ensemble verdicts).
PRODUCTS = ("chain", "ensemble", "energy_scan", "disorder", "search")
VERDICT_PREFIX = "verdict_"


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


def evaluate(inputs: dict, outputs: dict, params: dict) -> None:
    """Measure the claims on the rule's inputs (the products named in :data:`PRODUCTS`, the
    ensemble verdicts ``verdict_<scene>`` and the scene files by scene name; any ``code`` input
    only triggers reruns) and write the outputs ``csv``, ``table``, ``notes``, ``scenes``,
    ``search`` and ``macros``. ``params``: the config blocks ``claims`` and ``simulation``."""
    files = {k: v for k, v in inputs.items() if k != "code"}
    products = {name: xr.load_dataset(files.pop(name)) for name in PRODUCTS}
    chain, ensemble, energy_scan, disorder, search = (products[name] for name in PRODUCTS)
    verdicts = {name[len(VERDICT_PREFIX):]: xr.load_dataset(files.pop(name))
                for name in sorted(files) if name.startswith(VERDICT_PREFIX)}
    scenes = {name: xr.load_dataset(path) for name, path in files.items()}
    criteria = Criteria.from_config(params.get("claims"))
    simulation = params.get("simulation", {})
    site = int(simulation.get("excited_site", 21))
    claims = evaluate_claims(scenes, chain, ensemble, criteria, excited_site=site, energy_scan=energy_scan,
                             verdicts=verdicts, search=search, disorder=disorder)

    barrier = taylor_sign_barrier(read_chain(inputs["chain"], k4_sign=-1.0), site)
    macros = run_macros(scenes, chain, ensemble, simulation, criteria, barrier)
    macros.update(scan_macros(energy_scan, disorder))
    for name, ds in scenes.items():
        macros.update(scene_macros(name, ds, criteria))
    macros.update(claim_macros(claims))
    macros.update(search_report.search_macros(search, verdicts, energy_scan, disorder, criteria.agreement))
    paper_scale = macros["run.scale"] == "paper"

    with atomic_output(outputs["csv"]) as tmp:
        write_csv(claims, tmp)
    write_text(claims_table_tex(claims), outputs["table"])
    write_text(claims_notes_tex(claims), outputs["notes"])
    write_text(scenes_table_tex(scenes), outputs["scenes"])
    write_text(search_report.search_table_tex(search, verdicts), outputs["search"])
    write_text(macros_tex(macros)
               + "\\newif\\ifpaperscale\n" + ("\\paperscaletrue\n" if paper_scale else "\\paperscalefalse\n")
               + "\\newif\\ifsearchpinned\n"
               + ("\\searchpinnedtrue\n" if int(search.attrs["pinned"]) else "\\searchpinnedfalse\n"),
               outputs["macros"])
    for claim in claims:
        print(f"{claim.id:28s} {claim.verdict:28s} {claim.measured}", file=sys.stderr)
