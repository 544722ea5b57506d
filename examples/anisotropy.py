"""The anisotropy of a packet on a square lattice, as an observable of your own.

    A = (m2_x - m2_y) / (m2_x + m2_y),   m2_x = sum_n (i_n - X)^2 z_n,  m2_y = sum_n (j_n - Y)^2 z_n,

the second moments of the packet's density z (the energy density, the norm density of a DNLS
lattice) along each axis about its centre (X, Y): 0 for a round packet, +1 for one stretched
along the lines, -1 across them; 1 on a chain. Name it in a study file as
``observables: [participation, second_moment, anisotropy.py:ANISOTROPY]`` (the file beside the
study file, or a path from the working directory): the study keeps it per orbit beside the
package's series (docs/tutorials/your-own-study.md).
"""

import numpy as np

from chainchaos.observe.formulas import site_positions
from chainchaos.observe.registry import Observable


def anisotropy(run) -> np.ndarray:
    """A at every sample of ``run`` (a SampledRun: its density (S, N) and its lattice)."""
    z = run.density
    moments = []
    for r in site_positions(run.chain.geometry).T:  # positions along each axis
        centre = z @ r
        moments.append(np.sum(z * (r[None, :] - centre[:, None]) ** 2, axis=1))
    along, across = moments[0], moments[1] if len(moments) > 1 else np.zeros_like(moments[0])
    return (along - across) / (along + across)


ANISOTROPY = Observable(name="anisotropy", dims=("time",), label=r"$A$", compute=anisotropy,
                        long_name="anisotropy (m2_x - m2_y) / (m2_x + m2_y) of the packet's density")
