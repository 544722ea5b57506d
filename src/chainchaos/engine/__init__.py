"""The Numba engines: splitting schemes and the single-trajectory engine, the SIMD batch engine,
explicit vectors, exactly rounded elementary functions, the energy-checked advance, the
right-hand side for general ODE solvers, and the on-disk kernel cache.

This ``__init__`` imports nothing: ``chainchaos.engine.cache`` must set up Numba's cache before
any module imports numba.
"""
