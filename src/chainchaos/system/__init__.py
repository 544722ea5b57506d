"""The physical system: disordered chains and their linear modes, the bond models (a registry),
initial states, and the :class:`~chainchaos.system.problem.Problem` every algorithm starts from.
"""
