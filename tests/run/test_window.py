"""The growing window (chainchaos.run.window): a long chain integrated where its packet is.

Exact: a problem restricted to the whole chain is the problem (bit for bit). Against the
whole chain: a windowed run, started with the same deviation vector (on the excited site),
equals the whole chain's run to less than the integrator's own error at that step (the
difference between the runs at dt and dt/2), on the Klein-Gordon chain (a site law), on the
Hertz chain (bonds that open, gap counts too) and on the DNLS chain (a split model, its window
following the norm). Cost: on a long KG chain the window stays the
packet's width, not N."""

import numpy as np
import pytest

from chainchaos.engine.problem import Problem
from chainchaos.errors import ParameterError, StudyError
from chainchaos.run.driver import sample, sample_steps
from chainchaos.run.window import Window, WindowedEngine, restricted_deviation
from chainchaos.studies.study.spec import load_study
from chainchaos.system.chain import dnls_chain, kg_chain, random_chain
from chainchaos.system.initial import Excitation, initial_deviation

CASES = {  # model: chains, excited site, energy, variable, scheme, dt, t_final
    "kg": ([kg_chain(s, 4.0, 256) for s in range(4)], 128, 0.4, "momentum", "ABA864", 0.2, 1e3),
    "hertz": ([random_chain(s, 5.0, 300) for s in range(4)], 150, 1.8, "displacement", "SRKN6b", 0.01, 1e2),
    "dnls": ([dnls_chain(s, 4.0, 256, beta=1.0) for s in range(4)], 128, 1.0, "displacement", "ABC4", 0.1, 1e3),
}


def _start(model, chains, site, energy, variable):
    N, B = chains[0].N, len(chains)
    q, p, dq, dp = (np.zeros((N, B)) for _ in range(4))
    for j, c in enumerate(chains):
        q[:, j], p[:, j], _ = Excitation(site=site, variable=variable).state(Problem(model, [c]).model, c, energy)
        dq[:, j], dp[:, j] = initial_deviation(N, j)
    return q, p, *restricted_deviation(dq, dp, *Window.excited(q, p))


def _run(model, chains, scheme, dt, t_final, start, window=None):
    problem = Problem(model, chains, integrator=scheme, dt=dt, tangent=True, track_gaps=model == "hertz",
                      check_every=100)
    return sample(problem, *start, sample_steps(t_final, dt, 5, 1.0), window=window)


def test_a_problem_restricted_to_the_whole_chain_is_the_problem():
    chains, site, energy, variable, scheme, dt, _ = CASES["kg"]
    start = _start("kg", chains, site, energy, variable)
    whole = Problem("kg", chains, integrator=scheme, dt=dt, check_every=7)
    a, b = whole.engine(*start), whole.restricted(0, whole.N).engine(*start)
    a.advance(500)
    b.advance(500)
    for key in ("q", "p", "dq", "dp", "log_growth"):
        assert np.array_equal(getattr(a, key), getattr(b, key)), key


@pytest.mark.parametrize("model", sorted(CASES))
def test_a_windowed_run_equals_the_whole_chain_to_the_integrators_error(model):
    chains, site, energy, variable, scheme, dt, t_final = CASES[model]
    start = _start(model, chains, site, energy, variable)
    whole = _run(model, chains, scheme, dt, t_final, start)
    halved = _run(model, chains, scheme, dt / 2, t_final, start)
    windowed = _run(model, chains, scheme, dt, t_final, start, Window())
    for key in ("Q", "P", "DQ", "DP"):
        integrator = np.abs(getattr(whole, key) - getattr(halved, key)).max()
        assert 0 < np.abs(getattr(whole, key) - getattr(windowed, key)).max() < integrator, key
    assert np.abs(whole.log_growth - windowed.log_growth).max() < np.abs(whole.log_growth - halved.log_growth).max()
    assert np.array_equal(whole.max_gaps, windowed.max_gaps)


def test_the_window_follows_the_packet_not_the_chain():
    N = 4096
    chains = [kg_chain(s, 4.0, N) for s in range(2)]
    start = _start("kg", chains, N // 2, 0.4, "momentum")
    engine = WindowedEngine(Problem("kg", chains, integrator="ABA864", dt=0.4, check_every=100), Window(), *start)
    engine.advance(2500)  # t = 1e3
    lo, hi = engine.span
    assert len(engine.spans) > 1 and lo < N // 2 - 64 and hi > N // 2 + 64  # it grew with the packet ...
    assert hi - lo < N // 8  # ... and stayed far from the walls
    full = engine.q
    assert full.shape == (N, 2) and not full[:lo].any() and not full[hi:].any()


def test_bad_windows_are_named():
    with pytest.raises(ParameterError, match="window.threshold"):
        Window(threshold=2.0)
    with pytest.raises(ParameterError, match="window.margin"):
        Window(margin=0)
    chains = CASES["kg"][0]
    rest = np.zeros((256, 4))
    with pytest.raises(ParameterError, match="a state at rest"):
        WindowedEngine(Problem("kg", chains), Window(), rest, rest, rest, rest)
    with pytest.raises(ParameterError, match="GALI"):
        WindowedEngine(Problem("kg", chains, gali=2), Window(), *_start("kg", chains, 128, 0.4, "momentum"))
    with pytest.raises(ParameterError, match="sites"):
        Problem("kg", chains, sites=(10, 300))


def test_a_study_with_a_window_and_gali_is_refused():
    spec = {"lattice": {"model": "kg", "N": 64}, "excitation": {"kind": "site", "site": "centre", "energies": [0.4]},
            "integration": {"dt": 0.1, "t_final": 10.0, "window": {}}, "observables": ["mlce", "log_gali"]}
    with pytest.raises(StudyError, match="integration.window"):
        load_study(spec).check()
