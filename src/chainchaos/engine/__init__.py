"""The Numba engines: the problem every algorithm starts from, splitting schemes and the
single-trajectory engine, the SIMD batch engine, the energy-checked advance, the right-hand side
for general ODE solvers, and the checks a model of one's own passes before they run it.

This ``__init__`` imports nothing: importing a module of the engines loads Numba, which
``chainchaos.kernels.cache`` must have configured first (``import chainchaos`` does).
"""
