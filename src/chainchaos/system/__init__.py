"""The physical system: disordered chains and their linear modes, the bond models (a registry)
and initial states. The :class:`~chainchaos.engine.problem.Problem` that integrates them is in
``chainchaos.engine``.
"""
