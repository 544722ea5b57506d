"""Studies beyond single scenes: the energy scan and disorder statistics (``scan``), the realization
search (``search``) and the numerical accuracy and stability of the integrators (``numerics``).
"""
