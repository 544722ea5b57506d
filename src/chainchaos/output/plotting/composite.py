"""The composite figures: the panels of figure N laid out as in the paper (panels.LAYOUTS)."""

import numpy as np
from matplotlib.figure import Figure

from chainchaos.output.plotting import style
from chainchaos.output.plotting.panels import draw_panel
from chainchaos.paper import panels


def plot_figure(number: int, data: dict) -> Figure:
    """Figure ``number`` of the paper: its rows of panels from ``panels.LAYOUTS``, each panel
    lettered (a), (b), ... at its top left. ``data`` is as for ``plot_panel``."""
    if number not in panels.LAYOUTS:
        raise KeyError(f"unknown figure {number!r}; figures are {sorted(panels.LAYOUTS)}")
    rows = panels.LAYOUTS[number]
    columns = max(len(row) for row in rows)
    with style.context():
        fig = Figure(figsize=style.composite_size(len(rows), columns), layout="constrained")
        # One subfigure per row: a row of line plots is not squeezed to the colour-bar margins
        # of a row of maps below it.
        for row, subfigure in zip(rows, np.atleast_1d(fig.subfigures(len(rows), 1))):
            grid = subfigure.add_gridspec(1, columns)
            for c, letter in enumerate(row):
                ax = subfigure.add_subplot(grid[0, c])
                draw_panel(ax, f"{number}{letter}", data)
                _letter(ax, letter)
    return fig


def _letter(ax, letter: str) -> None:
    """The panel letter in bold, followed by the panel's own title, at the top left (a centred
    title would collide with the letter in a narrow panel)."""
    title = ax.get_title()
    ax.set_title("")
    ax.set_title(rf"$\bf{{({letter})}}$ {title}".rstrip(), loc="left")
