"""The composite figures: the panels of figure N laid out as in the paper (paper.LAYOUTS)."""

from matplotlib.figure import Figure

from chainchaos import paper
from chainchaos.plotting import style
from chainchaos.plotting.panels import draw_panel


def plot_figure(number: int, data: dict) -> Figure:
    """Figure ``number`` of the paper: its rows of panels from ``paper.LAYOUTS``, each panel
    lettered (a), (b), ... at its top left. ``data`` is as for ``plot_panel``."""
    if number not in paper.LAYOUTS:
        raise KeyError(f"unknown figure {number!r}; figures are {sorted(paper.LAYOUTS)}")
    rows = paper.LAYOUTS[number]
    columns = max(len(row) for row in rows)
    with style.context():
        fig = Figure(figsize=style.composite_size(len(rows), columns), layout="constrained")
        grid = fig.add_gridspec(len(rows), columns)
        for r, row in enumerate(rows):
            for c, letter in enumerate(row):
                ax = fig.add_subplot(grid[r, c])
                draw_panel(ax, f"{number}{letter}", data)
                ax.set_title(f"({letter})", loc="left", fontweight="bold")
    return fig
