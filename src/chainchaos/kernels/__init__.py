"""The arithmetic the Numba kernels are written in, and how they are compiled and cached.

``exactmath``: correctly rounded and CPU-independent scalar functions (log, exp10, roots, norms,
Gram-Schmidt) that ``system``, ``engine`` and ``observe`` share; ``simd``: the explicit SIMD
vectors of the batch engine; ``cache``: Numba's on-disk
cache and the environment that selects the compiled code. The lowest layer with Numba in it: it
imports nothing of the package above ``errors`` and ``project``.
"""
