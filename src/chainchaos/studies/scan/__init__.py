"""The energy scan and the disorder statistics: groups of short trajectories (``runs``), their
merge onto the grid (``merge``), the thresholds (``thresholds``) and the figures (``plots``).
"""
