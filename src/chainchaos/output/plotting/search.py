"""The realization-search figures, drawn from a merged search (``stages.merge``) only.

``search``: per statement of the paper, the fraction of the candidates that the short run leaves
(not broken) and of the scored candidates that satisfy it on their ensemble (verdict ``holds``);
every scored candidate's fraction of lanes satisfying each statement, the chosen chain marked.
``search_joint`` (``joint``): which statements hold together, the scores, and Hertz H = 1.8's chaos
onset against its level.
"""

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle
from matplotlib.ticker import MaxNLocator

from chainchaos.output.plotting.style import PAGE_WIDTH, context, save_figure
from chainchaos.paper.criteria import Tolerances
from chainchaos.studies.search.joint import (
    held_counts,
    joint_statements,
    onset_and_level,
    paper_onset_and_level,
    unbroken_counts,
)

#: up to this many scored candidates, each column of the search figure is labelled with its seed
LABELLED_COLUMNS = 16


def search_figure(ds):
    statements = [str(s) for s in ds.statement.values]
    S = len(statements)
    scored = np.flatnonzero(ds["scored"].values == 1)
    chosen = int(ds.attrs["chosen_candidate"])
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 0.16 * S + 1.2))
        ax, bx = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.3]}, sharey=True)
        y = np.arange(S)
        # fractions, so that stage 1 (every candidate) and stage 2 (the scored few) share one axis
        not_broken = unbroken_counts(ds) / ds.sizes["candidate"]
        holds = held_counts(ds) / scored.size if scored.size else np.zeros(S)
        ax.barh(y + 0.2, not_broken, height=0.4, color="#90a4ae",
                label=f"not broken by $t = {ds.attrs['filter_t_final']:g}$ (of {ds.sizes['candidate']} candidates)")
        ax.barh(y - 0.2, holds, height=0.4, color="#2e7d32",
                label=f"holds on the ensemble (of {scored.size} scored)")
        ax.set_yticks(y, statements)
        ax.invert_yaxis()
        ax.set_xlim(0, 1)
        ax.set_xlabel("fraction of candidates")
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=5.5, borderaxespad=0.2)
        frac = ds["fraction"].values[scored]
        im = bx.imshow(frac.T, aspect="auto", cmap="RdYlGn", vmin=0, vmax=1, interpolation="nearest",
                       extent=(-0.5, scored.size - 0.5, S - 0.5, -0.5))
        seeds = [str(int(s)) for s in ds["seed"].values[scored]]
        k = int(np.flatnonzero(scored == chosen)[0]) if chosen in scored else None
        if scored.size <= LABELLED_COLUMNS:
            bx.set_xticks(np.arange(scored.size), seeds, rotation=90)
            bx.set_xlabel("seed of the scored candidate (chosen: boxed)")
        else:  # too many to read: only the chosen one's seed
            bx.set_xticks([] if k is None else [k], [] if k is None else [seeds[k]], rotation=90)
            bx.set_xlabel(f"{scored.size} scored candidates (chosen: boxed)")
        if k is not None:
            bx.add_patch(Rectangle((k - 0.5, -0.5), 1, S, fill=False, lw=1.2, ec="black"))
        cb = fig.colorbar(im, ax=bx, fraction=0.05, pad=0.02)
        cb.set_label("fraction of lanes satisfying it")
        bx.set_title(f"chosen seed {ds.attrs['chosen_seed']}, score {ds.attrs['chosen_score']:.2f} of {S}",
                     fontsize=7)
        fig.tight_layout()
    return fig


def _cooccurrence_panel(ax, fig, joint):
    n = max(joint.n_scored, 1)
    S = len(joint.statements)
    im = ax.imshow(joint.both / n, cmap="Greens", vmin=0, vmax=1, interpolation="nearest")
    for a, b in joint.exclusive_pairs():
        i, j = joint.statements.index(a), joint.statements.index(b)
        ax.plot([i, j], [j, i], ls="none", marker="x", ms=3, mew=0.8, color="#c62828")
    ax.set_xticks(np.arange(S), joint.statements, rotation=90, fontsize=4.5)
    ax.set_yticks(np.arange(S), joint.statements, fontsize=4.5)
    ax.set_title(f"(a) both hold, fraction of {joint.n_scored} scored; x: never together", fontsize=6.5)
    cb = fig.colorbar(im, ax=ax, fraction=0.046, pad=0.02)
    cb.set_label("fraction of scored candidates")


def _score_panel(ax, joint, n_statements: int):
    bins = np.arange(0.0, n_statements + 1.0, 1.0)
    ax.hist(joint.score, bins=bins, color="#90a4ae", edgecolor="white")
    ax.axvline(joint.chosen_score, color="black", lw=1.0,
               label=f"chosen ({joint.at_least_as_good()} of {joint.n_scored} score as high)")
    ax.set_xlabel("score (expected statements satisfied by one orbit)")
    ax.set_ylabel("scored candidates")
    ax.yaxis.set_major_locator(MaxNLocator(integer=True))  # counts of candidates
    ax.set_xlim(0, n_statements)
    ax.legend(fontsize=5.5, loc="upper left")
    ax.set_title("(b) scores", fontsize=6.5)


def _onset_panel(ax, ds, time_factor: float, level_factor: float):
    onset, level = paper_onset_and_level()
    t, lam = onset_and_level(ds)
    ok = np.isfinite(t) & np.isfinite(lam)
    chosen = np.flatnonzero(ds["scored"].values == 1) == int(ds.attrs["chosen_candidate"])
    ax.loglog(t[ok & ~chosen], lam[ok & ~chosen], "o", ms=3, color="#455a64", label="scored candidate (median)")
    ax.loglog(t[ok & chosen], lam[ok & chosen], "s", ms=4, mfc="none", color="black", label="chosen chain")
    box = Rectangle((onset / time_factor, level / level_factor), onset * (time_factor - 1 / time_factor),
                    level * (level_factor - 1 / level_factor), fill=False, ls="--", ec="#c62828")
    ax.add_patch(box)
    ax.plot([onset], [level], "*", ms=7, color="#c62828", label="the paper's (with tolerances)")
    ax.set_xlabel(r"Hertz $H = 1.8$: onset of chaos $t$")
    ax.set_ylabel(r"final $\Lambda$")
    ax.legend(fontsize=5, loc="upper left", bbox_to_anchor=(1.0, 1.0), borderaxespad=0.2)
    ax.set_title(f"(c) {int(ok.sum())} candidates with an onset and a level", fontsize=6.5)


def joint_figure(ds, time_factor: float = Tolerances.time_factor, level_factor: float = Tolerances.mlce_factor):
    """Co-occurrence of the statements over the scored candidates, the scores, and Hertz H = 1.8's
    onset of chaos against its final Lambda with the paper's values (``joint.paper_onset_and_level``)
    and the claims' tolerances on them."""
    joint = joint_statements(ds)
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 0.55 * PAGE_WIDTH + 2.2))
        grid = fig.add_gridspec(2, 2, height_ratios=[1.6, 1.0])
        _cooccurrence_panel(fig.add_subplot(grid[0, :]), fig, joint)
        _score_panel(fig.add_subplot(grid[1, 0]), joint, len(joint.statements))
        _onset_panel(fig.add_subplot(grid[1, 1]), ds, time_factor, level_factor)
        fig.tight_layout()
    return fig


def _save(fig, pdf_path, png_path, dpi: int) -> None:
    from pathlib import Path

    stem = Path(pdf_path).with_suffix("")
    if Path(png_path).with_suffix("") != stem:
        raise ValueError(f"PDF {pdf_path} and PNG {png_path} must share a stem")
    save_figure(fig, stem, dpi=dpi)


def plot_search(ds, pdf_path, png_path, dpi: int = 200) -> None:
    """Write the search figure as PDF and PNG (byte-stable, atomic)."""
    _save(search_figure(ds), pdf_path, png_path, dpi)


def plot_search_joint(ds, pdf_path, png_path, dpi: int = 200, **tolerances) -> None:
    """Write the joint-analysis figure (:func:`joint_figure`) as PDF and PNG (byte-stable, atomic)."""
    _save(joint_figure(ds, **tolerances), pdf_path, png_path, dpi)
