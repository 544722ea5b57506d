"""Tasks of workflow/rules/numerics.smk: the numerical accuracy and stability of the integrators on
the chosen chain (work precision, stable steps, energy drift, the Taylor sign of K4, step advice)."""

import sys
from pathlib import Path

import xarray as xr

from chainchaos.paper import panels
from chainchaos.records.io import read_chain, write_netcdf
from chainchaos.run.progress import ProgressReporter
from chainchaos.run.warmup import warm_up
from chainchaos.studies.numerics.advice import step_advice
from chainchaos.studies.numerics.stability import (
    drift_dataset,
    energy_drift,
    stability_scan,
    taylor_dataset,
    taylor_sign_probe,
)
from chainchaos.studies.numerics.tables import (
    advice_tables,
    stability_tables,
    work_precision_tables,
)
from chainchaos.studies.numerics.work_precision import merge_cases, work_precision


def _say(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def _load(path) -> xr.Dataset:
    return xr.load_dataset(path, engine="netcdf4")


def numerics_work_precision_model(inputs, outputs, params, wildcards) -> None:
    """Error against run time of every scheme and solve_ivp method for one model's cases (model,
    energy)."""
    chain = read_chain(inputs["chain"])
    s = dict(params["settings"])
    cases = [(model, float(energy)) for model, energy in params["cases"]]
    ds = work_precision(chain, cases, schemes=s["schemes"], dts=s["dts"],
                        tolerances=s["tolerances"], t_final=s["t_final"], t_probe=s["t_probe"],
                        reference=s["reference"], floor_factor=s.get("floor_factor", 10.0),
                        check_interval=s.get("check_interval", 1.0), repeats=s.get("repeats", 3),
                        repeat_below=s.get("repeat_below", 0.5), excited_site=s.get("excited_site", 21),
                        progress=_say)
    write_netcdf(ds, outputs["data"])


def numerics_work_precision(inputs, outputs, params, wildcards) -> None:
    """The cases in one file (results/numerics/work_precision.nc), the tables of observed orders
    (CSV, LaTeX) and the CSV of every run."""
    ds = merge_cases([_load(f) for f in inputs["models"]])
    write_netcdf(ds, outputs["data"])
    work_precision_tables(ds, outputs["orders_csv"], outputs["orders_tex"], outputs["runs_csv"])


def numerics_plot_work_precision(inputs, outputs, params, wildcards) -> None:
    """The work-precision figure (PDF and PNG)."""
    from chainchaos.output.plotting.numerics import (
        plot_work_precision,  # matplotlib: only in the plotting jobs
    )

    plot_work_precision(_load(inputs["data"]), Path(outputs["pdf"]).with_suffix(""))


def numerics_stability(inputs, outputs, params, wildcards) -> None:
    """Largest stable steps of every scheme over disorder strengths and energies, and on the
    near-sonic-vacuum chain."""
    chain = read_chain(inputs["chain"])
    warm_up(panels.models())
    s = params["settings"]
    ds = stability_scan(chain, s["alphas"], s["energies"], s["schemes"], s.get("models", ["hertz", "fput"]),
                        t_final=s["t_final"], bound=s["bound"], rel_tol=s.get("rel_tol", 1e-2),
                        sonic_factor=s.get("sonic_factor", 1e-6), sonic_energies=s.get("sonic_energies"),
                        excited_site=s.get("excited_site", 21), progress=_say)
    write_netcdf(ds, outputs["data"])


def numerics_energy_drift(inputs, outputs, params, wildcards) -> None:
    """Long-time energy drift of one scene at the production step; progress in the log."""
    chain = read_chain(inputs["chain"])
    warm_up(panels.models())
    s, integrator = params["settings"], params["integrator"]
    name = f"drift {s['model']} H={s['energy']:g}"
    r = energy_drift(s["model"], chain, float(s["energy"]), integrator, float(s["dt"]), float(s["t_final"]),
                     check_interval=s.get("check_interval", 1.0), samples_per_decade=s.get("samples_per_decade", 10),
                     excited_site=s.get("excited_site", 21), progress=ProgressReporter(name, float(s["t_final"]), 30.0))
    _say(f"{name}: {r['n_steps']} steps in {r['seconds']:.1f} s ({1e9 * r['seconds'] / r['n_steps']:.0f} ns/step), "
         f"max |dH/H| = {r['max_abs_error'].max():.3e}, growth exponent {r['growth_exponent']:.3f}")
    write_netcdf(drift_dataset(r, s["model"], float(s["energy"]), integrator, float(s["dt"]), chain), outputs["data"])


def numerics_taylor_sign(inputs, outputs, params, wildcards) -> None:
    """FPUT with the Taylor sign of K4: which energies stay bounded, which escape and are stopped by
    the guard, which cannot be reached."""
    chain = read_chain(inputs["chain"])
    s, integrator = params["settings"], params["integrator"]
    rows = taylor_sign_probe(chain, s["energies"], float(s["t_final"]), float(s["dt"]), integrator,
                             site=s.get("excited_site", 21))
    for r in rows:
        _say(f"H = {r['energy']:g}: {r['outcome']} {r['message']}")
    write_netcdf(taylor_dataset(rows, chain, float(s["t_final"]), float(s["dt"]), integrator), outputs["data"])


def numerics_step_advice(inputs, outputs, params, wildcards) -> None:
    """Energy error per scene at the production step and at larger ones (NetCDF, CSV and LaTeX)."""
    chain = read_chain(inputs["chain"])
    s = params["settings"]
    ds = step_advice(chain, params["scenes"], params["integrator"], s["dts"], float(s["t_final"]),
                     float(s["paper_dt"]), excited_site=s.get("excited_site", 21),
                     k4_sign=float(params["k4_sign"]), progress=_say)
    write_netcdf(ds, outputs["data"])
    advice_tables(ds, outputs["csv"], outputs["tex"])


def numerics_plot_stability(inputs, outputs, params, wildcards) -> None:
    """The stability figure (PDF and PNG) and its tables (CSV, LaTeX)."""
    from chainchaos.output.plotting.numerics import (
        plot_stability,  # matplotlib: only in the plotting jobs
    )

    stab, dr, ta, ad = (_load(inputs[k]) for k in ("stability", "drift", "taylor", "advice"))
    plot_stability(stab, dr, ta, ad, scheme=params["integrator"], path_stem=Path(outputs["pdf"]).with_suffix(""))
    stability_tables(stab, dr, ta, outputs["csv"], outputs["tex"])
