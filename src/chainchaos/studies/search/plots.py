"""The realization-search figure, drawn from results/search/search.nc only.

Left: per statement of the paper, how many candidates the short run leaves (not broken), and how
many scored candidates satisfy it on their ensemble (verdict ``holds``). Right: every scored
candidate's fraction of lanes satisfying each statement, the chosen chain marked.
"""

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from chainchaos.output.plotting.style import PAGE_WIDTH, context, save_figure
from chainchaos.paper.verdicts import HOLDS


def search_figure(ds):
    statements = [str(s) for s in ds.statement.values]
    S = len(statements)
    scored = np.flatnonzero(ds["scored"].values == 1)
    chosen = int(ds.attrs["chosen_candidate"])
    with context():
        fig = Figure(figsize=(PAGE_WIDTH, 0.16 * S + 1.2))
        ax, bx = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.0, 1.3]}, sharey=True)
        y = np.arange(S)
        not_broken = (ds["filter_outcome"].values != 0).sum(axis=0)
        holds = (ds["verdict"].values[scored] == HOLDS).sum(axis=0)
        ax.barh(y + 0.2, not_broken, height=0.4, color="#90a4ae",
                label=f"not broken by $t = {ds.attrs['filter_t_final']:g}$ ({ds.sizes['candidate']} candidates)")
        ax.barh(y - 0.2, holds, height=0.4, color="#2e7d32",
                label=f"holds on the ensemble ({scored.size} scored)")
        ax.set_yticks(y, statements)
        ax.invert_yaxis()
        ax.set_xlabel("candidates")
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=5.5, borderaxespad=0.2)
        frac = ds["fraction"].values[scored]
        im = bx.imshow(frac.T, aspect="auto", cmap="RdYlGn", vmin=0, vmax=1, interpolation="nearest",
                       extent=(-0.5, scored.size - 0.5, S - 0.5, -0.5))
        bx.set_xticks(np.arange(scored.size), [str(int(s)) for s in ds["seed"].values[scored]], rotation=90)
        bx.set_xlabel("seed of the scored candidate (chosen: boxed)")
        if chosen in scored:
            k = int(np.flatnonzero(scored == chosen)[0])
            bx.add_patch(Rectangle((k - 0.5, -0.5), 1, S, fill=False, lw=1.2, ec="black"))
        cb = fig.colorbar(im, ax=bx, fraction=0.05, pad=0.02)
        cb.set_label("fraction of lanes satisfying it")
        bx.set_title(f"chosen seed {ds.attrs['chosen_seed']}, score {ds.attrs['chosen_score']:.2f} of {S}",
                     fontsize=7)
        fig.tight_layout()
    return fig


def plot_search(ds, pdf_path, png_path, dpi: int = 200) -> None:
    """Write the search figure as PDF and PNG (byte-stable, atomic)."""
    from pathlib import Path

    stem = Path(pdf_path).with_suffix("")
    if Path(png_path).with_suffix("") != stem:
        raise ValueError(f"PDF {pdf_path} and PNG {png_path} must share a stem")
    save_figure(search_figure(ds), stem, dpi=dpi)
