"""Figures of the paper: every panel (``plot_panel``), every composite (``plot_figure``), and
byte-stable, atomic saving to PDF and PNG (``save_figure``).

Importing this package selects matplotlib's Agg backend: the figures are only written to files.
"""

from chainchaos.plotting.style import save_figure  # noqa: I001  (first: selects Agg before any pyplot)
from chainchaos.plotting.composite import plot_figure
from chainchaos.plotting.panels import plot_panel

__all__ = ["plot_panel", "plot_figure", "save_figure"]
