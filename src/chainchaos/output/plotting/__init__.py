"""Figures: every panel of the paper (``plot_panel``), every composite (``plot_figure``), the one
figure style (``style``: sizes, fonts, colours, labels) and byte-stable, atomic saving to PDF and
PNG (``save_figure``); and the figures of the studies: ``study`` (a study's spreading, chaos and
fractions, and studies side by side), ``scan``, ``search``, ``indicators``, ``numerics``. Every
figure of the package is drawn in that style."""

from chainchaos.output.plotting.composite import plot_figure
from chainchaos.output.plotting.panels import plot_panel
from chainchaos.output.plotting.style import save_figure

__all__ = ["plot_panel", "plot_figure", "save_figure"]
