"""The Toda chain (chainchaos.system.models.toda) against its exact properties.

- Its bond law expands to the FPUT one: K2 and K3 by construction, and the chain's K4 (paper sign)
  too, since 2 K3^2 / (3 K2) = h / 96; the first difference is the D^4 term K2 beta^3 / 24.
- A chain of equal beads between walls is integrable: it is the odd-symmetric half of a periodic
  Toda lattice of 2(N+1) particles, so the traces of that lattice's Flaschka-Lax matrix are
  conserved. tr L^4 is not a function of the energy; both engines keep it to rounding, while the
  FPUT chain, with the same expansion to fourth order, does not.
"""

import numpy as np
import pytest

from chainchaos.engine.problem import Problem
from chainchaos.system.chain import chain_from_radii, random_chain
from chainchaos.system.initial import initial_state
from chainchaos.system.models import fput, get_model, toda

TODA = get_model("toda")


def test_toda_force_is_the_fput_force_to_third_order_with_the_papers_K4():
    chain = random_chain(879, 5.0, 40)
    P_toda, P_fput = TODA.bond_parameters(chain), get_model("fput").bond_parameters(chain)
    beta = P_toda[1]
    np.testing.assert_allclose(2 * chain.K3**2 / (3 * chain.K2), chain.K4, rtol=1e-14)
    for b in range(chain.N + 1):
        for D in (2e-3, -2e-3, 1e-3):
            difference = toda.force(tuple(P_toda[:, b]), D, 0.0) - fput.force(tuple(P_fput[:, b]), D, 0.0)
            assert difference / D**4 == pytest.approx(chain.K2[b] * beta[b] ** 3 / 24, rel=3e-2)


def flaschka_traces(chain, q, p) -> tuple[float, float]:
    """(tr L^2, tr L^4) of the periodic Toda lattice whose odd-symmetric half is the chain.

    Positions Q = (0, q_1..q_N, 0, -q_N..-q_1), momenta likewise; with the stretch y_n =
    Q_{n+1} - Q_n, V = K2/beta^2 e^(-beta y) + (linear terms, which cancel), time scale
    omega = sqrt(K2/m): a_n = exp(-beta y_n / 2) / 2 and b_n = -beta P_n / (2 m omega)."""
    K2, beta, m = chain.K2[0], -2.0 * chain.K3[0] / chain.K2[0], chain.mass[0]
    Q = np.concatenate([[0.0], q, [0.0], -q[::-1]])
    P = np.concatenate([[0.0], p, [0.0], -p[::-1]])
    a = 0.5 * np.exp(-beta * (np.roll(Q, -1) - Q) / 2)
    b = -beta * P / (2 * m * np.sqrt(K2 / m))
    L = np.diag(b) + np.diag(a[:-1], 1) + np.diag(a[:-1], -1)
    L[0, -1] = L[-1, 0] = a[-1]
    L2 = L @ L
    return float(np.trace(L2)), float(np.trace(L2 @ L2))


@pytest.mark.parametrize("engine", ["batch", "single"])
def test_the_equal_bead_toda_chain_keeps_its_lax_traces_and_fput_does_not(engine):
    chain = chain_from_radii(np.ones(8))
    drift = {}
    for name in ("toda", "fput"):
        q0, p0, _ = initial_state(name, chain, 1.0, 3)  # strongly nonlinear: beta u0 ~ 1
        problem = Problem(name, [chain, chain], dt=0.01, tangent=False)
        run = problem.engine(np.stack([q0, q0], 1), np.stack([p0, p0], 1), kind=engine)
        start = np.array(flaschka_traces(chain, q0, p0))
        worst = np.zeros(2)
        for _ in range(50):
            run.advance(200)
            now = np.array(flaschka_traces(chain, run.q[:, 0], run.p[:, 0]))
            worst = np.maximum(worst, np.abs(now / start - 1))
        drift[name] = worst
    assert drift["toda"].max() < 1e-11
    assert drift["fput"][1] > 1e-4  # not an integral of FPUT
