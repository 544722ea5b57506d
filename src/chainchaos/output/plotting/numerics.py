"""Figures of the numerics study: work precision (error against run time) and stability.

Drawn with the Agg backend in the package's style and saved through
:func:`chainchaos.output.plotting.style.save_figure`: PDF and PNG, byte-stable (no dates in the PDF
metadata, frozen layout), written atomically.
"""

import math

import matplotlib.ticker as mticker
import numpy as np
from matplotlib.figure import Figure

from chainchaos.output.plotting.style import PAGE_WIDTH, context, model_label, save_figure
from chainchaos.studies.numerics.work_precision import STATUS

SCHEME_STYLE = {
    "verlet": ("#7f7f7f", "o"),
    "mclachlan_atela4": ("#2ca02c", "s"),
    "SRKN6b": ("#d62728", "D"),
    "ABA864": ("#ff7f0e", "^"),
    "SRKN11b": ("#1f77b4", "v"),
    "yoshida6": ("#9467bd", "P"),
}
IVP_STYLE = {"DOP853": ("black", "x", "--"), "RK45": ("#8c564b", "+", ":")}
ALPHA_COLOURS = ("#440154", "#3b528b", "#21918c", "#5ec962", "#c8a000")
ERROR_ROWS = (("energy_error", r"max $|\Delta H|/H$"), ("phase_space_error", r"phase-space error at $t_{\rm probe}$"),
              ("lambda_error", r"$|\Lambda - \Lambda_{\rm ref}|$ [$\omega_{\max}$]"))


def _tidy_log_axes(fig) -> None:
    """Readable log axes: no minor-tick labels; on an axis spanning less than two decades, major
    ticks also at 3 (or 2 and 5, below one decade) times the powers of ten, so that it still
    carries labels."""
    for ax in fig.axes:
        for axis, scale, lim in ((ax.xaxis, ax.get_xscale(), ax.get_xlim()), (ax.yaxis, ax.get_yscale(), ax.get_ylim())):
            if scale != "log":
                continue
            lo, hi = sorted(lim)
            decades = math.log10(hi / lo) if lo > 0 else math.inf
            if decades < 2:
                axis.set_major_locator(mticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0) if decades < 1 else (1.0, 3.0)))
                axis.set_major_formatter(mticker.FuncFormatter(lambda v, _: f"{v:g}"))
            else:
                axis.set_major_locator(mticker.LogLocator(base=10))
                axis.set_major_formatter(mticker.LogFormatterSciNotation())
            axis.set_minor_formatter(mticker.NullFormatter())


def _scheme_style(name):
    return SCHEME_STYLE.get(name, ("#17becf", "*"))


def _case_title(case: str, ds) -> str:
    model, energy = case.split("_H")
    title = f"{model_label(model)}, $H = {energy}$"
    if model == "hertz":
        gaps = int(ds.sel(case=case).reference_max_open_gaps)
        title += ", contacts open" if gaps > 0 else ", no contact opens"
    return title


def _work_precision_axis(ax, ds, c, var: str, methods) -> None:
    """One error measure of one case against wall-clock seconds: a line per splitting scheme (over
    its steps) and per solve_ivp method (over its tolerances), and the reference's uncertainty."""
    for m in methods:
        idx = np.flatnonzero(ds.method.values == m)
        d = c.isel(run=idx)
        ok = d.status.values == STATUS["ok"]
        x, y = d.seconds.values[ok], d[var].values[ok]
        keep = np.isfinite(x) & np.isfinite(y) & (y > 0)
        if not keep.any():
            continue
        kind = str(d.kind.values[0])
        # Connect the points in ladder order (decreasing step or tolerance), not by time.
        step = (d.dt.values if kind == "splitting" else d.rtol.values)[ok][keep]
        order = np.argsort(-step)
        if kind == "splitting":
            colour, marker = _scheme_style(m)
            ax.plot(x[keep][order], y[keep][order], marker=marker, color=colour, ms=2.8, lw=0.9, label=m)
        else:
            colour, marker, ls = IVP_STYLE.get(m, ("black", "x", "--"))
            ax.plot(x[keep][order], y[keep][order], marker=marker, color=colour, ms=3.5, lw=0.9, ls=ls,
                    label=f"solve_ivp {m}")
    floor = {"phase_space_error": float(c.reference_phase_uncertainty),
             "lambda_error": float(c.reference_lambda_uncertainty)}.get(var)
    if floor and floor > 0:
        ax.axhline(floor, color="0.5", lw=0.6, ls=(0, (1, 2)))
    ax.set_xscale("log")
    ax.set_yscale("log")


def _shared_legend(fig, axes) -> None:
    """One legend below the figure with every label of every axis, in order of appearance."""
    handles, labels = axes[0, 0].get_legend_handles_labels()
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    fig.legend(handles, labels, loc="outside lower center", ncol=min(len(labels), 8))


def plot_work_precision(ds, path_stem):
    """One column per case, one row per error measure (energy, phase space at t_probe,
    Lambda(t_final)), each against wall-clock seconds, log-log; a line per splitting scheme
    (over its steps) and per solve_ivp method (over its tolerances). The dotted line is the
    reference's own uncertainty (10x it is where a scheme's step ladder stops)."""
    cases = [str(c) for c in ds.case.values]
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 1.85 * len(ERROR_ROWS) + 0.5), layout="constrained")
        axes = fig.subplots(len(ERROR_ROWS), len(cases), squeeze=False, sharex="col")
        methods = list(dict.fromkeys(ds.method.values.tolist()))
        for ci, case in enumerate(cases):
            for ri, (var, label) in enumerate(ERROR_ROWS):
                ax = axes[ri, ci]
                _work_precision_axis(ax, ds, ds.sel(case=case), var, methods)
                if ri == 0:
                    ax.set_title(_case_title(case, ds))
                if ri == len(ERROR_ROWS) - 1:
                    ax.set_xlabel("wall-clock time [s]")
                if ci == 0:
                    ax.set_ylabel(label)
        _shared_legend(fig, axes)
        _tidy_log_axes(fig)
        return save_figure(fig, path_stem)


def _log_axes(ax, xlabel: str, ylabel: str) -> None:
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)


def _steps_by_energy(ax, stab, model: str, alpha0: float, letter: str) -> None:
    """(a, b) dt_max omega_max against H for every scheme, dashed: each scheme's linear bound."""
    for s in stab.scheme.values:
        colour, marker = _scheme_style(str(s))
        ax.plot(stab.energy.values, stab.dt_max_omega.sel(model=model, alpha=alpha0, scheme=s), color=colour,
                marker=marker, ms=2.8, label=str(s))
        ax.axhline(float(stab.linear_bound_wide.sel(scheme=s)), color=colour, lw=0.6, ls="--")
    _log_axes(ax, r"$H$", r"$\Delta t_{\max}\,\omega_{\max}$")
    ax.set_title(f"({letter}) {model_label(model)}, $\\alpha = {alpha0:g}$")


def _steps_against_estimate(ax, fig, stab, letter: str) -> None:
    """(c) dt_max against the linear estimate x_s/omega_max for every model, alpha, energy and
    scheme, coloured by log10 H."""
    H = stab.energy.values
    est = (stab.linear_bound_wide / stab.omega_max).transpose("alpha", "scheme")
    for model in stab.model.values:
        d = stab.dt_max.sel(model=model)
        x = np.broadcast_to(est.values[:, None, :], d.shape)
        cvals = np.broadcast_to(np.log10(H)[None, :, None], d.shape)
        sc = ax.scatter(x.ravel(), d.values.ravel(), c=cvals.ravel(), cmap="viridis", s=5,
                        marker="o" if model == "hertz" else "^", linewidths=0, label=model_label(model))
    lim = [np.nanmin(est.values) * 0.5, np.nanmax(est.values) * 1.5]
    ax.plot(lim, lim, color="0.3", lw=0.6, ls="--")
    _log_axes(ax, r"linear estimate $x_s/\omega_{\max}$", r"$\Delta t_{\max}$")
    ax.set_title(f"({letter}) all $\\alpha$, $H$, schemes")
    ax.legend(loc="upper left", fontsize=5.5)
    fig.colorbar(sc, ax=ax, label=r"$\log_{10} H$", shrink=0.8)


def _steps_by_alpha(ax, stab, model: str, scheme: str, letter: str) -> None:
    """(d, e) dt_max omega_max of ``scheme`` against H at every disorder strength."""
    for ai, a in enumerate(stab.alpha.values):
        ax.plot(stab.energy.values, stab.dt_max_omega.sel(model=model, alpha=a, scheme=scheme),
                color=ALPHA_COLOURS[ai % len(ALPHA_COLOURS)], marker="o", ms=2.5, label=f"$\\alpha = {a:g}$")
    ax.axhline(float(stab.linear_bound_wide.sel(scheme=scheme)), color="0.3", lw=0.6, ls="--")
    _log_axes(ax, r"$H$", r"$\Delta t_{\max}\,\omega_{\max}$")
    ax.set_title(f"({letter}) {model_label(model)}, {scheme}")


def _sonic_vacuum(ax, stab, scheme: str, letter: str) -> None:
    """(f) the near-sonic-vacuum chain, with the H^(-1/10) law of pure Hertz contacts."""
    Hs = stab.sonic_energy.values
    for s in stab.scheme.values:
        colour, marker = _scheme_style(str(s))
        ax.plot(Hs, stab.sonic_dt_max.sel(scheme=s), color=colour, marker=marker, ms=2.8)
    ref = float(stab.sonic_dt_max.sel(scheme=scheme if scheme in stab.scheme.values else stab.scheme.values[0]).values[0])
    ax.plot(Hs, ref * (Hs / Hs[0]) ** -0.1, color="0.3", lw=0.6, ls="--", label=r"$\propto H^{-1/10}$")
    _log_axes(ax, r"$H$", r"$\Delta t_{\max}$")
    ax.legend(loc="lower left", fontsize=5.5)
    ax.set_title(f"({letter}) Hertz, $F_0 \\times {stab.attrs['sonic_factor']:g}$ (near sonic vacuum)")


def _drift(ax, drift, letter: str) -> None:
    """(g) the energy error of the long run, per window."""
    ax.plot(drift.time, drift.max_abs_error, color=SCHEME_STYLE.get(drift.attrs["integrator"], ("k", "o"))[0], lw=0.9)
    _log_axes(ax, r"$t$ [$1/\omega_{\max}$]", r"max $|\Delta H|/H$ in window")
    ax.set_title(f"({letter}) drift: Hertz $H = {drift.attrs['energy']:g}$, $\\Delta t = {drift.attrs['dt']:g}$")
    ax.text(0.03, 0.95, f"growth exponent {drift.attrs['growth_exponent']:.3f}", transform=ax.transAxes,
            va="top", fontsize=6)


def _taylor_escape(ax, taylor, letter: str) -> None:
    """(h) FPUT with the Taylor sign of K4: time of escape against H."""
    E = taylor.energy.values
    out = taylor.outcome.values.astype(str)
    t_final = float(taylor.attrs["t_final"])
    esc = out == "SimulationError"
    ax.plot(E[esc], taylor.t_stopped.values[esc], "o", color="#d62728", ms=3.5, label="escape, stopped by guard")
    bnd = out == "bounded"
    ax.plot(E[bnd], np.full(bnd.sum(), t_final), "^", color="#2ca02c", ms=3.5, label=f"bounded to $t = {t_final:g}$")
    ax.axvline(float(taylor.attrs["lowest_bond_barrier"]), color="0.4", lw=0.6, ls=":")
    ax.axvline(float(taylor.attrs["excitation_barrier"]), color="0.2", lw=0.8, ls="--")
    ax.axvspan(float(taylor.attrs["excitation_barrier"]), max(E.max(), taylor.attrs["excitation_barrier"]) * 1.5,
               color="0.85", lw=0, label="ParameterError (unreachable)")
    ax.set_xlim(0, max(E.max(), taylor.attrs["excitation_barrier"]) * 1.05)
    ax.set_yscale("log")
    ax.set_xlabel(r"$H$")
    ax.set_ylabel(r"$t$ stopped [$1/\omega_{\max}$]")
    ax.set_title(f"({letter}) FPUT, $K_4 < 0$ (Taylor sign)")
    ax.legend(loc="upper right", fontsize=5.5)


def _step_advice(ax, advice, letter: str) -> None:
    """(i) the energy error of every scene against dt (step advice)."""
    for sc in advice.scene.values:
        d = advice.sel(scene=sc)
        model = str(d.model.values)
        ok = d.stable.values == 1
        ax.plot(advice.dt.values[ok], d.energy_error.values[ok], marker="o" if model == "hertz" else "^", ms=2.5,
                color="#c62828" if model == "hertz" else "#1565c0", lw=0.7,
                alpha=0.35 + 0.65 * float(d.energy) / float(advice.energy.max()))
    ax.axvline(float(advice.attrs["paper_dt"]), color="0.3", lw=0.6, ls="--")
    _log_axes(ax, r"$\Delta t$", r"max $|\Delta H|/H$")
    ax.set_title(f"({letter}) scenes, {advice.attrs['integrator']} (red Hertz, blue FPUT)")


def _panel(ax, available: bool, draw, *args) -> None:
    """``draw(ax, *args)``, or a blank axis where the panel's data is missing."""
    if available:
        draw(ax, *args)
    else:
        ax.set_axis_off()


def plot_stability(stab, drift=None, taylor=None, advice=None, scheme: str = "SRKN6b", path_stem="stability"):
    """Stability figure, 3 x 3 panels:
    (a, b) dt_max omega_max against H for every scheme, Hertz and FPUT, on the chosen chain,
    dashed: each scheme's linear bound x_s; (c) dt_max against the linear estimate x_s/omega_max
    for every model, alpha, energy and scheme; (d, e) ``scheme`` at every alpha; (f) the
    near-sonic-vacuum chain with the H^(-1/10) law of pure Hertz contacts; (g) energy drift of
    the long run; (h) FPUT with the Taylor sign of K4: time of escape against H; (i) energy
    error per scene against dt for ``scheme`` (step advice). A panel without its data is left
    blank."""
    alpha0 = float(stab.attrs["chain_alpha"])
    if alpha0 not in stab.alpha.values:
        alpha0 = float(stab.alpha.values[len(stab.alpha) // 2])
    models = set(stab.model.values)
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 7.2), layout="constrained")
        axes = fig.subplots(3, 3)
        for ax, (model, letter) in zip(axes[0, :2], (("hertz", "a"), ("fput", "b"))):
            _panel(ax, model in models, _steps_by_energy, stab, model, alpha0, letter)
        _steps_against_estimate(axes[0, 2], fig, stab, "c")
        for ax, (model, letter) in zip(axes[1, :2], (("hertz", "d"), ("fput", "e"))):
            _panel(ax, model in models and scheme in stab.scheme.values, _steps_by_alpha, stab, model, scheme, letter)
        _panel(axes[1, 2], "sonic_dt_max" in stab, _sonic_vacuum, stab, scheme, "f")
        _panel(axes[2, 0], drift is not None, _drift, drift, "g")
        _panel(axes[2, 1], taylor is not None, _taylor_escape, taylor, "h")
        _panel(axes[2, 2], advice is not None, _step_advice, advice, "i")
        axes[0, 0].legend(loc="lower left", ncol=2, fontsize=5.5)
        axes[1, 0].legend(loc="lower left", fontsize=5.5)
        _tidy_log_axes(fig)
        return save_figure(fig, path_stem)
