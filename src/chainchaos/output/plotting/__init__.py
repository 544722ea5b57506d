"""Figures: every panel of the paper (``plot_panel``), every composite (``plot_figure``), the one
figure style (``style``: sizes, fonts, colours, labels) and byte-stable, atomic saving to PDF and
PNG (``save_figure``). Every figure of the package, the studies' included, is drawn in that style."""

from chainchaos.output.plotting.composite import plot_figure
from chainchaos.output.plotting.panels import plot_panel
from chainchaos.output.plotting.style import save_figure

__all__ = ["plot_panel", "plot_figure", "save_figure"]
