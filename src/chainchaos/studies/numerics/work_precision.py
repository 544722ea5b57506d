"""Work-precision measurements: error against wall-clock time for every scheme and solve_ivp.

For each case (model, energy) on one chain, every splitting scheme runs at a ladder of steps and
scipy's RK45/DOP853 at a ladder of tolerances, all to t_final with the tangent dynamics (so that
Lambda is measured), and each run is scored by

- ``energy_error``: max over t <= t_final of |H(t) - H(0)| / H(0) (dimensionless),
- ``phase_space_error``: |x(t_probe) - x_ref(t_probe)| / |x_ref(t_probe)|, x = (u, p),
- ``lambda_error``: |Lambda(t_final) - Lambda_ref(t_final)| (units of omega_max),

against ``seconds``, its wall-clock time. The reference is a high-order scheme at a small step
(``reference``); its own uncertainty is measured against the same scheme at twice that step,
and a scheme's step ladder stops once its errors are within ``floor_factor`` times that
uncertainty (or the round-off floor): smaller steps would measure the reference, not the scheme.
"""

import json
import math

import numpy as np
import xarray as xr

from chainchaos.engine.integrators import SCHEMES, get_scheme
from chainchaos.errors import require
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.warmup import warm_up
from chainchaos.studies.numerics.runs import (
    IVP_METHODS,
    phase_space_error,
    run_scheme,
    run_solve_ivp,
)
from chainchaos.system.models import get_model

STATUS = {"ok": 0, "unstable": 1, "skipped": 2, "failed": 3}
IVP_ORDER = {"RK45": 5, "DOP853": 8}
ROUND_OFF = 1e-13


def case_name(model: str, energy: float) -> str:
    return f"{model}_H{energy:g}"


def reference_run(model, chain, energy: float, scheme: str, dt: float, t_final: float, t_probe: float,
                  **kw) -> dict:
    """The converged reference of one case: ``scheme`` at ``dt`` (with contact statistics for
    a model whose bonds open), and its uncertainty from the same scheme at 2 dt (phase space at t_probe, Lambda at
    t_final). Returns a dict of the reference RunResult and the uncertainties."""
    ref = run_scheme(model, chain, energy, scheme, dt, t_final, t_probe, repeats=1,
                     track_gaps=get_model(model).has_gaps, **kw)
    check = run_scheme(model, chain, energy, scheme, 2 * dt, t_final, t_probe, repeats=1, **kw)
    require(ref.stable and check.stable, "reference", f"{scheme} dt={dt:g}", "a stable reference run")
    return {"run": ref, "phase_uncertainty": phase_space_error(check.state_probe, ref.state_probe),
            "lambda_uncertainty": abs(check.lambda_final - ref.lambda_final),
            "check_energy_error": check.max_energy_error}


def _score(run, ref) -> tuple[float, float]:
    ps = phase_space_error(run.state_probe, ref["run"].state_probe) if run.stable else math.nan
    dl = abs(run.lambda_final - ref["run"].lambda_final) if run.stable else math.nan
    return ps, dl


#: What each run of the study records (one value per case and run).
RUN_QUANTITIES = ("seconds", "cpu_seconds", "energy_error", "phase_space_error", "lambda_error", "lambda_final",
                  "force_evaluations", "n_steps")
#: What each case's reference run records.
REFERENCE_QUANTITIES = ("reference_lambda", "reference_phase_uncertainty", "reference_lambda_uncertainty",
                        "reference_energy_error", "reference_seconds", "reference_max_open_gaps",
                        "reference_open_fraction", "reference_bonds_ever_open", "reference_dt")


def _reference_values(model, ref: dict, ref_dt: float) -> dict:
    """The :data:`REFERENCE_QUANTITIES` of one case's reference run (the contact statistics are
    zero for a model whose bonds never open)."""
    r = ref["run"]
    gaps = model.has_gaps
    return {"reference_lambda": r.lambda_final, "reference_phase_uncertainty": ref["phase_uncertainty"],
            "reference_lambda_uncertainty": ref["lambda_uncertainty"], "reference_energy_error": r.max_energy_error,
            "reference_seconds": r.seconds, "reference_max_open_gaps": r.max_open_gaps if gaps else 0,
            "reference_open_fraction": r.open_fraction if gaps else 0.0,
            "reference_bonds_ever_open": r.bonds_ever_open if gaps else 0, "reference_dt": ref_dt}


def _case_runs(model, chain, energy: float, runs: list, ref: dict, floor_factor: float, t_final: float,
               t_probe: float, repeats: int, repeat_below: float, common: dict, say) -> list:
    """Every run of one case, in order: (status, values of :data:`RUN_QUANTITIES`) per run, None
    for a splitting run skipped because its scheme reached the floor (floor_factor x the
    reference's uncertainty, or round-off) at a larger step."""
    ps_floor = max(floor_factor * ref["phase_uncertainty"], ROUND_OFF)
    dl_floor = max(floor_factor * ref["lambda_uncertainty"], ROUND_OFF)
    floored, out = set(), []
    name = case_name(model.name, energy)
    for kind, method, dt, tol in runs:
        if kind == "splitting" and method in floored:
            out.append(None)
            continue
        if kind == "splitting":
            run = run_scheme(model, chain, energy, method, dt, t_final, t_probe, repeats=repeats,
                             repeat_below=repeat_below, stop_error=1.0, **common)
        else:
            run = run_solve_ivp(model, chain, energy, method, tol, t_final, t_probe, repeats=repeats,
                                repeat_below=repeat_below, excited_site=common["excited_site"],
                                deviation_seed=common["deviation_seed"])
        ps, dl = _score(run, ref)
        values = dict(seconds=run.seconds, cpu_seconds=run.cpu_seconds, energy_error=run.max_energy_error,
                      phase_space_error=ps, lambda_error=dl, lambda_final=run.lambda_final,
                      force_evaluations=run.force_evaluations, n_steps=run.n_steps)
        out.append((STATUS["ok"] if run.stable else STATUS["unstable"], values))
        say(f"{name}: {method} {'dt' if kind == 'splitting' else 'rtol'}="
            f"{dt if kind == 'splitting' else tol:g}: {run.seconds:.3g} s, energy {run.max_energy_error:.2e}, "
            f"phase {ps:.2e}, Lambda {dl:.2e}{'' if run.stable else ' UNSTABLE'}")
        if kind == "splitting" and run.stable and ps <= ps_floor and dl <= dl_floor:
            floored.add(method)
    return out


def work_precision(chain, cases, schemes=None, dts=None, tolerances=None, t_final: float = 1e3,
                   t_probe: float = 100.0, reference: dict | None = None, floor_factor: float = 10.0,
                   check_interval: float = 1.0, repeats: int = 3, repeat_below: float = 0.5,
                   excited_site: int = 21, deviation_seed: int = 0, progress=None) -> xr.Dataset:
    """Measure error against run time (module docstring) and return it as a Dataset.

    ``cases``: iterable of (model name, energy). ``schemes``: names of
    chainchaos.engine.integrators.SCHEMES (default all). ``dts``: steps, in decreasing order (each a
    divisor of t_probe and t_final). ``tolerances``: {"RK45": [rtol...], "DOP853": [...]}, atol =
    rtol. ``reference``: {"scheme": name, "dt": {model: dt}}. ``progress(message)`` is called
    after every run. Dims: ``case`` and ``run`` (one per scheme and step, or method and tolerance).
    """
    schemes = list(SCHEMES) if schemes is None else list(schemes)
    dts = sorted([0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4] if dts is None else dts,
                 reverse=True)
    tolerances = {"DOP853": [1e-5, 1e-7, 1e-9, 1e-11], "RK45": [1e-4, 1e-6, 1e-8]} if tolerances is None else tolerances
    reference = {"scheme": "SRKN11b", "dt": {"hertz": 2.5e-4, "fput": 1e-3}} if reference is None else reference
    for s in schemes:
        get_scheme(s)
    for m in tolerances:
        require(m in IVP_METHODS, "tolerances", m, f"methods among {IVP_METHODS}")
    cases = [(str(m), float(e)) for m, e in cases]
    say = progress or (lambda message: None)

    runs = [("splitting", s, dt, math.nan) for s in schemes for dt in dts]
    runs += [("solve_ivp", m, math.nan, tol) for m in tolerances for tol in sorted(tolerances[m], reverse=True)]
    shape = (len(cases), len(runs))
    out = {k: np.full(shape, math.nan) for k in RUN_QUANTITIES}
    status = np.full(shape, STATUS["skipped"], dtype=np.int8)
    per_case = {k: np.full(len(cases), math.nan) for k in REFERENCE_QUANTITIES}
    common = dict(check_interval=check_interval, excited_site=excited_site, deviation_seed=deviation_seed)
    warm_up(sorted({m for m, _ in cases}))

    for ci, (model_name, energy) in enumerate(cases):
        model = get_model(model_name)
        ref_dt = float(reference["dt"][model_name] if isinstance(reference["dt"], dict) else reference["dt"])
        ref = reference_run(model, chain, energy, reference["scheme"], ref_dt, t_final, t_probe, **common)
        for k, v in _reference_values(model, ref, ref_dt).items():
            per_case[k][ci] = v
        r = ref["run"]
        say(f"{case_name(model_name, energy)}: reference {reference['scheme']} dt={ref_dt:g} in {r.seconds:.1f} s, "
            f"Lambda={r.lambda_final:.6g}, uncertainty phase {ref['phase_uncertainty']:.2e} "
            f"Lambda {ref['lambda_uncertainty']:.2e}")
        done = _case_runs(model, chain, energy, runs, ref, floor_factor, t_final, t_probe, repeats, repeat_below,
                          common, say)
        for ri, result in enumerate(done):
            if result is not None:
                status[ci, ri] = result[0]
                for k, v in result[1].items():
                    out[k][ci, ri] = v

    parameters = {"cases": [list(c) for c in cases], "schemes": schemes, "dts": list(dts),
                  "tolerances": {k: list(v) for k, v in tolerances.items()}, "t_final": t_final,
                  "t_probe": t_probe, "reference": reference, "floor_factor": floor_factor,
                  "check_interval": check_interval, "repeats": repeats, "repeat_below": repeat_below,
                  "excited_site": excited_site, "deviation_seed": deviation_seed, "chain_seed": chain.seed,
                  "alpha": chain.alpha}
    ds = _dataset(cases, runs, out, status, per_case)
    ds.attrs.update(provenance_attrs(parameters))
    ds.attrs.update(title="chainchaos work-precision measurements", t_final=float(t_final),
                    t_probe=float(t_probe), reference_scheme=reference["scheme"],
                    floor_factor=float(floor_factor), check_interval=float(check_interval),
                    seed=-1 if chain.seed is None else int(chain.seed), alpha=float(chain.alpha),
                    comment="status 'skipped': the scheme's errors had reached floor_factor x the reference "
                            "uncertainty (or round-off) at a larger step")
    return ds


def _dataset(cases: list, runs: list, out: dict, status: np.ndarray, per_case: dict) -> xr.Dataset:
    """The measurements on (case, run), with the reference runs per case, as a Dataset."""
    kinds, methods, dt_c, tol_c = zip(*runs)
    order = [float(get_scheme(m).order) if k == "splitting" else float(IVP_ORDER[m]) for k, m, _, _ in runs]
    one = {"units": "1"}
    per_time = {"units": "1", "comment": "units of omega_max (inverse nondimensional time)"}
    data = {
        "seconds": (("case", "run"), out["seconds"], {"units": "s", "long_name": "wall-clock time of the run",
                                                      "comment": "time.perf_counter, best of repeats for short runs"}),
        "cpu_seconds": (("case", "run"), out["cpu_seconds"], {"units": "s", "long_name": "process CPU time of the run",
                                                              "comment": "time.process_time of the timed (best) repeat"}),
        "energy_error": (("case", "run"), out["energy_error"], {**one, "long_name": "maximum relative energy error |H(t) - H(0)| / H(0) up to t_final"}),
        "phase_space_error": (("case", "run"), out["phase_space_error"], {**one, "long_name": "relative phase-space error |x - x_ref| / |x_ref| at t_probe, x = (u, p)"}),
        "lambda_error": (("case", "run"), out["lambda_error"], {**per_time, "long_name": "absolute error of Lambda(t_final) against the reference"}),
        "lambda_final": (("case", "run"), out["lambda_final"], {**per_time, "long_name": "finite-time mLCE Lambda(t_final)"}),
        "force_evaluations": (("case", "run"), out["force_evaluations"], {**one, "long_name": "force evaluations"}),
        "n_steps": (("case", "run"), out["n_steps"], {**one, "long_name": "steps taken (accepted steps for solve_ivp)"}),
        "status": (("case", "run"), status, {**one, "long_name": "run status",
                                            "flag_values": np.array(list(STATUS.values()), dtype=np.int8),
                                            "flag_meanings": " ".join(STATUS)}),
        "reference_lambda": ("case", per_case["reference_lambda"], {**per_time, "long_name": "reference Lambda(t_final)"}),
        "reference_phase_uncertainty": ("case", per_case["reference_phase_uncertainty"], {**one, "long_name": "relative phase-space difference of the reference at dt_ref and 2 dt_ref at t_probe"}),
        "reference_lambda_uncertainty": ("case", per_case["reference_lambda_uncertainty"], {**per_time, "long_name": "difference of reference Lambda(t_final) at dt_ref and 2 dt_ref"}),
        "reference_energy_error": ("case", per_case["reference_energy_error"], {**one, "long_name": "maximum relative energy error of the reference"}),
        "reference_seconds": ("case", per_case["reference_seconds"], {"units": "s", "long_name": "wall-clock time of the reference run"}),
        "reference_dt": ("case", per_case["reference_dt"], {**one, "long_name": "step of the reference run (time units 1/omega_max)"}),
        "reference_max_open_gaps": ("case", per_case["reference_max_open_gaps"], {**one, "long_name": "largest number of simultaneously open contacts in the reference run (Hertz)"}),
        "reference_open_fraction": ("case", per_case["reference_open_fraction"], {**one, "long_name": "fraction of bond-steps with an open contact in the reference run (Hertz)"}),
        "reference_bonds_ever_open": ("case", per_case["reference_bonds_ever_open"], {**one, "long_name": "number of bonds that opened at least once in the reference run (Hertz)"}),
    }
    coords = {
        "case": ("case", [case_name(m, e) for m, e in cases], {"long_name": "model and energy"}),
        "model": ("case", [m for m, _ in cases], {"long_name": "model"}),
        "energy": ("case", np.array([e for _, e in cases]), {**one, "long_name": "total energy H"}),
        "run": ("run", np.arange(len(runs)), {**one, "long_name": "run index"}),
        "method": ("run", list(methods), {"long_name": "splitting scheme or solve_ivp method"}),
        "kind": ("run", list(kinds), {"long_name": "splitting (fixed step) or solve_ivp (adaptive)"}),
        "dt": ("run", np.array(dt_c), {**one, "long_name": "time step (units 1/omega_max); NaN for solve_ivp"}),
        "rtol": ("run", np.array(tol_c), {**one, "long_name": "relative tolerance (atol = rtol); NaN for splitting"}),
        "nominal_order": ("run", np.array(order), {**one, "long_name": "nominal order of the method"}),
    }
    return xr.Dataset(data, coords=coords)


def merge_cases(parts: list[xr.Dataset]) -> xr.Dataset:
    """One Dataset of the cases measured in separate jobs (each a :func:`work_precision` Dataset),
    along ``case``, with the parameters of every case in its provenance."""
    ds = xr.concat(parts, dim="case", data_vars="minimal", coords="minimal", compat="override",
                   combine_attrs="override")
    parameters = json.loads(parts[0].attrs["parameters"])
    parameters["cases"] = [c for p in parts for c in json.loads(p.attrs["parameters"])["cases"]]
    ds.attrs.update(provenance_attrs(parameters))
    return ds


def observed_order(dt, error, lower: float = ROUND_OFF, upper: float = 1e-3, last: int | None = 3) -> tuple[float, int]:
    """Observed order p of error ~ C dt^p: the least-squares slope of log(error) against
    log(dt) over the points with lower < error < upper (finite), restricted to the ``last``
    smallest steps among them (the asymptotic regime; None = all). Returns (p, points used);
    p is NaN with fewer than two points."""
    dt, error = np.asarray(dt, float), np.asarray(error, float)
    ok = np.isfinite(dt) & np.isfinite(error) & (error > lower) & (error < upper)
    x, y = np.log(dt[ok]), np.log(error[ok])
    order = np.argsort(x)
    x, y = x[order], y[order]
    if last is not None:
        x, y = x[:last], y[:last]
    if x.size < 2:
        return math.nan, int(x.size)
    return float(np.polyfit(x, y, 1)[0]), int(x.size)


def order_table(ds: xr.Dataset, floor_factor: float | None = None, upper: float = 1e-2, last: int | None = 5,
                tolerance: float = 0.5) -> list[dict]:
    """One row per (case, scheme): nominal order, observed orders of the phase-space and energy
    errors (:func:`observed_order`: least-squares slope over the steps whose errors lie between
    floor_factor x the reference uncertainty (round-off for the energy) and ``upper``; ``last``
    restricts it to the smallest steps), the reference's contact statistics, and ``reduced``:
    observed phase-space order below nominal - ``tolerance``. Where Hertz contacts open, the
    error of a step that crosses a contact is set by the force's regularity there
    (f ~ x^(3/2), k ~ x^(1/2)), not by the scheme's order."""
    floor_factor = float(ds.attrs.get("floor_factor", 10.0)) if floor_factor is None else floor_factor
    rows = []
    split = ds.where(ds.kind == "splitting", drop=True)
    for case in ds.case.values:
        c = ds.sel(case=case)
        lower_ps = max(floor_factor * float(c.reference_phase_uncertainty), ROUND_OFF)
        for scheme in dict.fromkeys(split.method.values.tolist()):
            sel = (ds.method == scheme).values & (ds.kind == "splitting").values
            d = c.isel(run=np.flatnonzero(sel))
            ok = d.status.values == STATUS["ok"]
            p_ps, n_ps = observed_order(d.dt.values[ok], d.phase_space_error.values[ok], lower_ps, upper, last)
            p_e, n_e = observed_order(d.dt.values[ok], d.energy_error.values[ok], 1e3 * np.finfo(float).eps, upper, last)
            nominal = get_scheme(scheme).order
            gaps = int(c.reference_max_open_gaps) if get_model(str(c.model.values)).has_gaps else 0
            rows.append({
                "case": str(case), "model": str(c.model.values), "energy": float(c.energy), "scheme": scheme,
                "nominal_order": nominal, "order_phase_space": p_ps, "points_phase_space": n_ps,
                "order_energy": p_e, "points_energy": n_e,
                "contacts_open": gaps > 0, "max_open_contacts": gaps,
                "open_fraction": float(c.reference_open_fraction),
                "reduced": bool(np.isfinite(p_ps) and p_ps < nominal - tolerance),
            })
    return rows
