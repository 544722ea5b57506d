"""Stability of the splitting schemes: linear bounds, largest stable steps, the near-sonic-vacuum
chain, long-time energy drift, and the escape of FPUT with the Taylor sign of K4.

Units are those of docs/conventions.md#units (time in 1/omega_max of the homogeneous linear chain,
energies in the derived unit); energy errors are relative, |H(t) - H(0)| / H(0).
"""

import functools
import math
import time

import numpy as np

from chainchaos.engine.checked import CheckedRun
from chainchaos.engine.integrators import get_scheme
from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError, SimulationError
from chainchaos.kernels import exactmath
from chainchaos.run.driver import sample_steps
from chainchaos.studies.numerics.runs import grid_steps, run_scheme
from chainchaos.system.chain import chain_at_alpha, sonic_vacuum_chain
from chainchaos.system.initial import excitation_energy, initial_state
from chainchaos.system.linear import normal_modes


def harmonic_half_trace(scheme: str, x) -> np.ndarray:
    """|trace| / 2 of one step of ``scheme`` on the harmonic oscillator q'' = -omega^2 q at
    x = omega dt (array): the step is linearly stable where it is <= 1 (its determinant is 1)."""
    s = get_scheme(scheme)
    x = np.asarray(x, dtype=float)
    # One step on (q, v/omega): drift(c) q += c x v, kick(d) v -= d x q.
    m11, m12, m21, m22 = np.ones_like(x), np.zeros_like(x), np.zeros_like(x), np.ones_like(x)
    for i, d in enumerate(s.kicks):
        if d != 0.0:
            m21, m22 = m21 - d * x * m11, m22 - d * x * m12
        if i < s.drifts.size:
            c = s.drifts[i]
            m11, m12 = m11 + c * x * m21, m12 + c * x * m22
    return np.abs(m11 + m22) / 2.0


@functools.cache  # a scheme's property, asked for by every run of the step search (2 million points)
def linear_instability_intervals(scheme: str, x_max: float = 20.0, resolution: float = 1e-5) -> tuple[tuple[float, float], ...]:
    """The intervals of x = omega dt in (0, x_max] where ``scheme`` is linearly unstable, found on
    a grid of spacing ``resolution`` (compositions have narrow resonance intervals, width ~1e-3,
    near x = pi); the last interval may end at x_max."""
    grid = np.arange(1, int(round(x_max / resolution)) + 1) * resolution
    unstable = harmonic_half_trace(scheme, grid) > 1.0 + 1e-12
    change = np.flatnonzero(np.diff(np.concatenate(([False], unstable, [False])).astype(np.int8)))
    return tuple((float(grid[i]), float(grid[j - 1])) for i, j in zip(change[::2], change[1::2]))


def linear_stability_bound(scheme: str, min_width: float = 0.0) -> float:
    """x_s = (omega dt) at which ``scheme`` first turns linearly unstable on the harmonic
    oscillator (dimensionless), counting only instability intervals at least ``min_width`` wide
    (the last, open-ended one always counts). A chain whose largest linear frequency is
    omega_max is linearly stable for dt < x_s / omega_max. Verlet has x_s = 2.
    """
    intervals = linear_instability_intervals(scheme)
    if not intervals:
        return math.inf
    for k, (a, b) in enumerate(intervals):
        if b - a >= min_width or k == len(intervals) - 1:
            break
    lo, hi = a - 1e-5, a
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if harmonic_half_trace(scheme, mid) > 1.0 + 1e-12 else (mid, hi)
    return float(lo)


#: Instability intervals narrower than this (in omega dt) are "narrow resonances" (see linear_bound_wide).
WIDE = 0.1


def linear_omega_max(chain) -> float:
    """The chain's largest linear frequency omega_max (units of the homogeneous chain's omega_max)."""
    return float(normal_modes(chain)[0][-1])


def is_stable(model, chain, energy: float, scheme: str, dt: float, t_final: float = 1e3,
              bound: float = 1e-2, excited_site: int = 21, check_interval: float = 0.1) -> tuple[bool, float]:
    """(stable, t_stopped): whether the relative energy error stays <= ``bound`` (and the state
    finite) up to t_final (rounded up to the step grid) at step ``dt``; no tangent dynamics."""
    t_end = math.ceil(t_final / dt - 1e-9) * dt
    r = run_scheme(model, chain, energy, scheme, dt, t_end, tangent=False, check_interval=check_interval,
                   repeats=1, stop_error=bound, excited_site=excited_site)
    return r.stable, r.t_stopped


def largest_stable_dt(model, chain, energy: float, scheme: str, t_final: float = 1e3,
                      bound: float = 1e-2, dt_start: float | None = None, growth: float = 2 ** 0.5,
                      rel_tol: float = 1e-2, excited_site: int = 21) -> dict:
    """The largest step dt_max (time units) at which ``scheme`` keeps the relative energy error
    below ``bound`` up to ``t_final``, and every step of a geometric ladder below it does too.

    The ladder climbs from ``dt_start`` (default 0.1 x_s / omega_max, divided by 4 until stable)
    by factors ``growth``
    until the first unstable step; the bracket (last stable, first unstable) is then bisected
    in log dt to relative width ``rel_tol``. Stable islands above the first instability are
    deliberately ignored: dt_max is the step below which the user is safe. Returns a dict with
    dt_max, dt_unstable (the upper end of the final bracket), runs (number of runs) and
    t_stopped (when the run at dt_unstable was stopped).
    """
    omega = linear_omega_max(chain)
    x_s = linear_stability_bound(scheme, WIDE)
    dt = 0.1 * x_s / omega if dt_start is None else float(dt_start)
    runs = 0
    ok, _ = is_stable(model, chain, energy, scheme, dt, t_final, bound, excited_site)
    runs += 1
    while not ok:
        dt /= 4.0
        ok, _ = is_stable(model, chain, energy, scheme, dt, t_final, bound, excited_site)
        runs += 1
        if runs > 12:
            return {"dt_max": math.nan, "dt_unstable": dt, "runs": runs, "t_stopped": math.nan}
    lo = dt
    while True:
        hi = lo * growth
        ok, t_stop = is_stable(model, chain, energy, scheme, hi, t_final, bound, excited_site)
        runs += 1
        if not ok:
            break
        lo = hi
        if hi > 1e3 * x_s / omega:
            return {"dt_max": lo, "dt_unstable": math.inf, "runs": runs, "t_stopped": math.nan}
    while hi / lo > 1.0 + rel_tol:
        mid = math.sqrt(lo * hi)
        ok, t = is_stable(model, chain, energy, scheme, mid, t_final, bound, excited_site)
        runs += 1
        if ok:
            lo = mid
        else:
            hi, t_stop = mid, t
    return {"dt_max": lo, "dt_unstable": hi, "runs": runs, "t_stopped": t_stop}


def energy_drift(model, chain, energy: float, scheme: str, dt: float, t_final: float,
                 check_interval: float = 1.0, samples_per_decade: int = 10, t_first: float = 1.0,
                 excited_site: int = 21, progress=None) -> dict:
    """Long run without tangent dynamics, recording the relative energy error e(t) = (H(t) -
    H(0)) / H(0) every ``check_interval`` time units, reduced to log-spaced windows.

    Returns a dict with the window ends ``time`` (the samples of ``driver.sample_steps`` from
    t_first to t_final, ``samples_per_decade`` per decade, on the grid of checks),
    ``max_abs_error`` (largest |e| in the window), ``mean_error`` (mean signed e in the window),
    ``error`` (e at the window end), the wall ``seconds``, ``n_steps``, and ``growth_exponent``:
    the least-squares slope of log(max |e| over [t/10, t]) against log t over the windows with
    t >= 100 (0 for a bounded error, 1/2 for a random walk, 1 for a linear drift).
    ``progress(t, fraction)`` is called after every window.
    """
    chunk = max(1, int(round(check_interval / dt)))
    problem = Problem(model, [chain], integrator=scheme, dt=dt, tangent=False, check_every=chunk)
    model = problem.model
    q, p, _ = initial_state(model, chain, energy, excited_site)
    run = CheckedRun(problem, q, p)
    grid_steps(t_final, chunk * dt, "t_final")
    ends = sample_steps(t_final, chunk * dt, samples_per_decade, t_first)[1:]  # in checks of chunk steps
    max_abs, mean, last = np.empty(ends.size), np.empty(ends.size), np.empty(ends.size)
    done = 0
    start = time.perf_counter()
    for i, end in enumerate(ends):
        err = np.empty(int(end - done))
        bad = run.advance(err.size, chunk, err)
        if bad >= 0:
            raise SimulationError(f"energy drift {model.name} H={energy:g}", (done + bad + 1) * chunk * dt,
                                  "non-finite state", math.nan)
        max_abs[i], mean[i], last[i] = np.max(np.abs(err)), np.mean(err), err[-1]
        done = int(end)
        if progress is not None:
            progress(done * chunk * dt, done / ends[-1])
    seconds = time.perf_counter() - start
    t = ends * chunk * dt
    decade_max = np.array([max_abs[(t > ti / 10.0 * (1 + 1e-12)) & (t <= ti)].max() for ti in t])
    use = t >= 100.0
    slope = (exactmath.line_slope(exactmath.log10(t[use]), exactmath.log10(decade_max[use])) if use.sum() >= 3
             else math.nan)
    return {"time": t, "max_abs_error": max_abs, "mean_error": mean, "error": last, "decade_max": decade_max,
            "seconds": seconds, "n_steps": int(ends[-1] * chunk), "growth_exponent": slope, "H0": run.H0}


def fput_bond_barrier(chain) -> float:
    """Lowest potential barrier of a single FPUT bond (energy units), or inf if every bond
    potential is bounded (K4 > 0). With K4 < 0 (Taylor sign) V(y) = K2 y^2/2 + K3 y^3/3 + K4 y^4/4
    has maxima where K2 + K3 y + K4 y^2 = 0; a bond stretched or compressed past them escapes."""
    best = math.inf
    for K2, K3, K4 in zip(chain.K2, chain.K3, chain.K4):
        if K4 >= 0:
            continue
        for y in np.roots([K4, K3, K2]).real:
            best = min(best, K2 * y**2 / 2 + K3 * y**3 / 3 + K4 * y**4 / 4)
    return float(best)


def excitation_barrier(model, chain, site: int = 21) -> float:
    """The largest energy the single-site excitation u_site = u0 can carry (energy units):
    the maximum of the potential along u0 > 0, or inf when it grows without bound."""
    u = np.linspace(0.0, 100.0, 20001)[1:]
    E = np.array([excitation_energy(model, chain, site, x) for x in u])
    i = int(np.argmax(E))
    if i == E.size - 1:
        return math.inf
    from scipy.optimize import minimize_scalar
    res = minimize_scalar(lambda x: -excitation_energy(model, chain, site, x),
                          bounds=(u[max(i - 1, 0)], u[min(i + 1, E.size - 1)]), method="bounded",
                          options={"xatol": 1e-12})
    return float(-res.fun)


def taylor_sign_probe(chain, energies, t_final: float, dt: float, scheme: str, site: int = 21,
                      max_energy_error: float = 1e-2) -> list[dict]:
    """Run FPUT with the Taylor sign of K4 (K4 < 0) through chainchaos.run.scenes.simulate at each
    energy and report what the guards do: ``outcome`` is "bounded" (reached t_final),
    "SimulationError" (stopped: non-finite state or energy error above ``max_energy_error``;
    ``t_stopped`` is the time named in the message) or "ParameterError" (the energy cannot be
    put into the single-site excitation: it exceeds the excitation barrier). ``message`` is the
    exception's text."""
    from chainchaos.run.scenes import SceneParameters, simulate

    rows = []
    for H in energies:
        params = SceneParameters(model="fput", energy=float(H), t_final=float(t_final), dt=float(dt),
                                 integrator=scheme, observables=("energy_error",), excited_site=site,
                                 k4_sign=-1, samples_per_decade=20, max_energy_error=max_energy_error,
                                 check_every=100, name=f"fput_H{H:g}_taylorK4")
        row = {"energy": float(H), "outcome": "bounded", "t_stopped": math.nan, "message": "",
               "max_energy_error": math.nan}
        start = time.perf_counter()
        try:
            ds = simulate(chain, params)
            row["max_energy_error"] = float(ds.attrs["max_energy_error"])
        except SimulationError as exc:
            row.update(outcome="SimulationError", t_stopped=float(exc.time), message=str(exc))
        except ParameterError as exc:
            row.update(outcome="ParameterError", message=str(exc))
        row["seconds"] = time.perf_counter() - start
        rows.append(row)
    return rows


def _steps_over_grid(chain, alphas, energies, schemes, models, t_final, bound, rel_tol, excited_site, say) -> dict:
    """Largest stable steps (and the bisection's bracket, runs and stop times) of every scheme for
    every model, disorder strength (:func:`chain_at_alpha`) and energy, on (model, alpha, energy,
    scheme), and each chain's linear omega_max."""
    shape = (len(models), len(alphas), len(energies), len(schemes))
    out = {k: np.full(shape, math.nan) for k in ("dt_max", "dt_unstable", "bisection_runs", "t_stopped")}
    omega = np.empty(len(alphas))
    for ai, alpha in enumerate(alphas):
        c = chain_at_alpha(chain, alpha)
        omega[ai] = linear_omega_max(c)
        for mi, m in enumerate(models):
            for ei, H in enumerate(energies):
                start = time.perf_counter()
                for si, s in enumerate(schemes):
                    r = largest_stable_dt(m, c, H, s, t_final, bound, rel_tol=rel_tol, excited_site=excited_site)
                    for key, value in (("dt_max", r["dt_max"]), ("dt_unstable", r["dt_unstable"]),
                                       ("bisection_runs", r["runs"]), ("t_stopped", r["t_stopped"])):
                        out[key][mi, ai, ei, si] = value
                say(f"{m} alpha={alpha:g} H={H:g}: dt_max*omega_max = "
                    + ", ".join(f"{s} {out['dt_max'][mi, ai, ei, si] * omega[ai]:.3g}" for si, s in enumerate(schemes))
                    + f" ({time.perf_counter() - start:.1f} s)")
    out["omega_max"] = omega
    return out


def _sonic_vacuum_steps(chain, factor: float, energies, schemes, t_final, bound, rel_tol, excited_site, say):
    """Largest stable steps of Hertz on the near-sonic-vacuum chain (:func:`sonic_vacuum_chain`
    of ``chain``), on (energy, scheme), and that chain."""
    sonic = sonic_vacuum_chain(chain, factor)
    sv = np.full((len(energies), len(schemes)), math.nan)
    for ei, H in enumerate(energies):
        for si, s in enumerate(schemes):
            sv[ei, si] = largest_stable_dt("hertz", sonic, H, s, t_final, bound, rel_tol=rel_tol,
                                           excited_site=excited_site)["dt_max"]
        say(f"sonic vacuum (F0 x {factor:g}) H={H:g}: dt_max = "
            + ", ".join(f"{s} {sv[ei, si]:.3g}" for si, s in enumerate(schemes)))
    return sv, sonic


def stability_scan(chain, alphas, energies, schemes, models=("hertz", "fput"), t_final: float = 1e3,
                   bound: float = 1e-2, rel_tol: float = 1e-2, sonic_factor: float | None = 1e-6,
                   sonic_energies=None, excited_site: int = 21, progress=None):
    """Largest stable steps (:func:`largest_stable_dt`) of every scheme for every model, disorder
    strength (:func:`chain_at_alpha`) and energy, and, with ``sonic_factor``, of Hertz on the
    near-sonic-vacuum chain (:func:`sonic_vacuum_chain` of ``chain``) at ``sonic_energies``.
    Returns an xarray Dataset (times in units of 1/omega_max of the homogeneous chain)."""
    import xarray as xr

    from chainchaos.records.provenance import provenance_attrs

    say = progress or (lambda message: None)
    alphas, energies = [float(a) for a in alphas], [float(e) for e in energies]
    schemes, models = list(schemes), list(models)
    grid = _steps_over_grid(chain, alphas, energies, schemes, models, t_final, bound, rel_tol, excited_site, say)
    one = {"units": "1"}
    dims = ("model", "alpha", "energy", "scheme")
    data = {
        "dt_max": (dims, grid["dt_max"], {**one, "long_name": "largest stable time step (units 1/omega_max of the homogeneous chain)",
                                  "comment": f"relative energy error <= {bound:g} up to t = {t_final:g}, and at every smaller step of the ladder"}),
        "dt_unstable": (dims, grid["dt_unstable"], {**one, "long_name": "smallest unstable step found (upper end of the bisection bracket)"}),
        "t_stopped": (dims, grid["t_stopped"], {**one, "long_name": "time at which the run at dt_unstable broke the bound"}),
        "bisection_runs": (dims, grid["bisection_runs"], {**one, "long_name": "runs used by the search"}),
        "omega_max": ("alpha", grid["omega_max"], {**one, "long_name": "largest linear frequency of the chain"}),
        "linear_bound": ("scheme", np.array([linear_stability_bound(s) for s in schemes]),
                         {**one, "long_name": "linear stability bound x_s: first omega dt with an unstable harmonic step"}),
        "linear_bound_wide": ("scheme", np.array([linear_stability_bound(s, WIDE) for s in schemes]), {
            **one, "long_name": f"first omega dt of an instability interval at least {WIDE:g} wide",
            "comment": "narrower resonance intervals below it are usually missed by a discrete spectrum"}),
    }
    data["dt_max_omega"] = (dims, grid["dt_max"] * grid["omega_max"][None, :, None, None],
                            {**one, "long_name": "dt_max * omega_max (the linear estimate is linear_bound)"})
    coords = {"model": models, "alpha": ("alpha", np.array(alphas), {**one, "long_name": "disorder strength"}),
              "energy": ("energy", np.array(energies), {**one, "long_name": "total energy H"}),
              "scheme": schemes}
    attrs = {}
    if sonic_factor is not None:
        sonic_energies = energies if sonic_energies is None else [float(e) for e in sonic_energies]
        sv, sonic = _sonic_vacuum_steps(chain, sonic_factor, sonic_energies, schemes, t_final, bound, rel_tol,
                                        excited_site, say)
        coords["sonic_energy"] = ("sonic_energy", np.array(sonic_energies), {**one, "long_name": "total energy H (near-sonic-vacuum chain)"})
        data["sonic_dt_max"] = (("sonic_energy", "scheme"), sv, {
            **one, "long_name": "largest stable time step of Hertz on the near-sonic-vacuum chain",
            "comment": f"precompression F0 x {sonic_factor:g}: delta_n x {sonic_factor ** (2 / 3):g}; time unit is "
                       "1/omega_max of the original (precompressed) homogeneous chain"})
        data["sonic_equivalent_energy"] = ("sonic_energy", np.array(sonic_energies) * sonic_factor ** (-5 / 3), {
            **one, "long_name": "energy of the original chain equivalent by Hertz scaling (H x factor^(-5/3))"})
        attrs.update(sonic_factor=float(sonic_factor), sonic_omega_max=linear_omega_max(sonic),
                     sonic_time_scale=float(sonic_factor ** (-1 / 6)))
    ds = xr.Dataset(data, coords=coords)
    params = {"alphas": alphas, "energies": energies, "schemes": schemes, "models": models, "t_final": t_final,
              "bound": bound, "rel_tol": rel_tol, "sonic_factor": sonic_factor,
              "sonic_energies": sonic_energies if sonic_factor is not None else None,
              "excited_site": excited_site, "chain_seed": chain.seed, "chain_alpha": chain.alpha}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title="chainchaos largest stable time steps", t_final=float(t_final), bound=float(bound),
                    seed=-1 if chain.seed is None else int(chain.seed), chain_alpha=float(chain.alpha), **attrs,
                    comment="chains at other alpha keep the chosen chain's uniform draws (chain_at_alpha)")
    return ds


def drift_dataset(result: dict, model: str, energy: float, scheme: str, dt: float, chain):
    """The output of :func:`energy_drift` as an xarray Dataset."""
    import xarray as xr

    from chainchaos.records.provenance import provenance_attrs

    one = {"units": "1"}
    ds = xr.Dataset({
        "max_abs_error": ("time", result["max_abs_error"], {**one, "long_name": "largest relative energy error |H - H0|/H0 in the window ending at time"}),
        "mean_error": ("time", result["mean_error"], {**one, "long_name": "mean signed relative energy error (H - H0)/H0 in the window"}),
        "energy_error": ("time", result["error"], {**one, "long_name": "signed relative energy error (H - H0)/H0 at the window end"}),
        "decade_max": ("time", result["decade_max"], {**one, "long_name": "largest |H - H0|/H0 over (t/10, t]"}),
    }, coords={"time": ("time", result["time"], {**one, "long_name": "time", "standard_name": "time",
                                                  "comment": "nondimensional time, unit 1/omega_max of the homogeneous linear chain"})})
    params = {"model": model, "energy": energy, "integrator": scheme, "dt": dt, "t_final": float(result["time"][-1]),
              "chain_seed": chain.seed}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title=f"chainchaos energy drift {model} H={energy:g}", model=model, energy=float(energy),
                    integrator=scheme, dt=float(dt), t_final=float(result["time"][-1]), n_steps=int(result["n_steps"]),
                    seconds=float(result["seconds"]), growth_exponent=float(result["growth_exponent"]),
                    total_energy=float(result["H0"]), seed=-1 if chain.seed is None else int(chain.seed),
                    comment="growth_exponent: slope of log decade_max against log t for t >= 100 "
                            "(0 bounded, 1/2 random walk, 1 linear drift)")
    return ds


def taylor_dataset(rows: list[dict], chain, t_final: float, dt: float, scheme: str):
    """The rows of :func:`taylor_sign_probe` as an xarray Dataset, with the barriers."""
    import xarray as xr

    from chainchaos.records.provenance import provenance_attrs

    one = {"units": "1"}
    taylor = chain.with_k4_sign(-1)
    ds = xr.Dataset({
        "outcome": ("energy", [r["outcome"] for r in rows], {"long_name": "bounded, SimulationError (escape stopped by the guard) or ParameterError (energy not reachable)"}),
        "t_stopped": ("energy", np.array([r["t_stopped"] for r in rows]), {**one, "long_name": "time named by the SimulationError"}),
        "message": ("energy", [r["message"] for r in rows], {"long_name": "text of the error"}),
        "max_energy_error": ("energy", np.array([r["max_energy_error"] for r in rows]), {**one, "long_name": "largest relative energy error of a bounded run"}),
    }, coords={"energy": ("energy", np.array([r["energy"] for r in rows]), {**one, "long_name": "total energy H"})})
    params = {"energies": [r["energy"] for r in rows], "t_final": t_final, "dt": dt, "integrator": scheme,
              "chain_seed": chain.seed, "K4_sign": -1}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title="FPUT with the Taylor sign of K4: what the guards do", t_final=float(t_final), dt=float(dt),
                    integrator=scheme, K4_sign=-1.0, excitation_barrier=excitation_barrier("fput", taylor),
                    lowest_bond_barrier=fput_bond_barrier(taylor), seed=-1 if chain.seed is None else int(chain.seed))
    return ds
