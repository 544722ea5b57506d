"""Step advice: the energy error that a step gives per scene, so that defaults are backed by numbers.

For every scene (model, energy) of the paper and a ladder of steps around the paper's dt = 5e-4,
one run of the chosen scheme (no tangent dynamics: the energy error does not depend on it) to
t_final records the largest relative energy error |H(t) - H(0)| / H(0) and the run time. The
ratio of run times to that of the paper's step is what a larger step gains; the energy error
is what it costs.
"""

import math

import numpy as np
import xarray as xr

from chainchaos.engine.integrators import get_scheme
from chainchaos.errors import ParameterError
from chainchaos.records.provenance import provenance_attrs
from chainchaos.run.warmup import warm_up
from chainchaos.studies.numerics.runs import run_scheme


def step_advice(chain, scenes, scheme: str = "SRKN6b", dts=(5e-4, 1e-3, 2e-3, 5e-3, 1e-2, 2e-2),
                t_final: float = 1e3, paper_dt: float = 5e-4, stop_error: float = 1.0,
                check_interval: float = 0.1, excited_site: int = 21, k4_sign: float = 1.0,
                progress=None) -> xr.Dataset:
    """Energy error and run time of ``scheme`` at each step of ``dts`` for each scene
    (iterable of (model name, energy)); see the module docstring. Dims ``scene`` and ``dt``."""
    get_scheme(scheme)
    scenes = [(str(m), float(e)) for m, e in scenes]
    dts = sorted({float(d) for d in dts} | {float(paper_dt)})
    say = progress or (lambda message: None)
    c = chain.with_k4_sign(k4_sign)
    warm_up(sorted({m for m, _ in scenes}))
    shape = (len(scenes), len(dts))
    err, sec, cpu, t_stop = (np.full(shape, math.nan) for _ in range(4))
    stable = np.zeros(shape, dtype=np.int8)
    for si, (m, H) in enumerate(scenes):
        for di, dt in enumerate(dts):
            try:
                r = run_scheme(m, c, H, scheme, dt, t_final, tangent=False, check_interval=check_interval,
                               stop_error=stop_error, excited_site=excited_site)
            except ParameterError as exc:
                say(f"{m}_H{H:g}: {exc}")
                break
            err[si, di], sec[si, di], cpu[si, di] = r.max_energy_error, r.seconds, r.cpu_seconds
            stable[si, di], t_stop[si, di] = int(r.stable), r.t_stopped
            say(f"{m}_H{H:g} {scheme} dt={dt:g}: energy error {r.max_energy_error:.2e}, {r.seconds:.3g} s"
                + ("" if r.stable else f" (stopped at t = {r.t_stopped:.4g})"))
    ref = dts.index(float(paper_dt))
    one = {"units": "1"}
    ds = xr.Dataset({
        "energy_error": (("scene", "dt"), err, {**one, "long_name": f"maximum relative energy error up to t = {t_final:g}"}),
        "seconds": (("scene", "dt"), sec, {"units": "s", "long_name": "wall-clock time of the run (no tangent dynamics)"}),
        "cpu_seconds": (("scene", "dt"), cpu, {"units": "s", "long_name": "process CPU time of the run"}),
        "speedup": (("scene", "dt"), sec[:, ref:ref + 1] / sec, {**one, "long_name": f"run time at dt = {paper_dt:g} divided by run time at dt"}),
        "stable": (("scene", "dt"), stable, {**one, "long_name": f"run reached t_final with energy error <= {stop_error:g}",
                                             "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "stopped ok"}),
        "t_stopped": (("scene", "dt"), t_stop, {**one, "long_name": "time at which an unstable run stopped"}),
    }, coords={
        "scene": ("scene", [f"{m}_H{H:g}" for m, H in scenes], {"long_name": "scene (model and energy)"}),
        "model": ("scene", [m for m, _ in scenes], {"long_name": "model"}),
        "energy": ("scene", np.array([H for _, H in scenes]), {**one, "long_name": "total energy H"}),
        "dt": ("dt", np.array(dts), {**one, "long_name": "time step (units 1/omega_max)"}),
    })
    params = {"scenes": [list(s) for s in scenes], "integrator": scheme, "dts": dts, "t_final": t_final,
              "paper_dt": paper_dt, "stop_error": stop_error, "check_interval": check_interval,
              "excited_site": excited_site, "K4_sign": k4_sign, "chain_seed": chain.seed}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title="chainchaos step advice: energy error per scene and step", integrator=scheme,
                    integrator_order=get_scheme(scheme).order, t_final=float(t_final), paper_dt=float(paper_dt),
                    seed=-1 if chain.seed is None else int(chain.seed))
    return ds
