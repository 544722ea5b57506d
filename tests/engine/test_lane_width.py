"""Results do not depend on the SIMD width (chainchaos.kernels.simd.LANES) or on which scenes share a batch.

The width is fitted to the CPU (8 with AVX-512, 4 otherwise) and ``CHAINCHAOS_SIMD_LANES`` selects
another; both engines are compiled for it. These are bit-for-bit reproducibility tests: the same
trajectories computed at two widths, or alone and together, must agree to the last bit.
"""

import os
import subprocess
import sys

import numpy as np
import pytest

from chainchaos import random_chain
from chainchaos.errors import ParameterError
from chainchaos.kernels import simd
from chainchaos.run.scenes import (
    SceneParameters,
    model_observables,
    simulate,
    simulate_scenes,
)
from chainchaos.system.models import BEAD_MODELS

OTHER_WIDTH = 4 if simd.LANES == 8 else 8

# Both engines on a mix of models, energies and chains, written as raw bytes of their results.
_PROBE = """
import sys
import numpy as np
from chainchaos import random_chain
from chainchaos.kernels import simd
from chainchaos.system.initial import initial_deviation, initial_state
from chainchaos.system.models import BEAD_MODELS
from chainchaos.engine.problem import Problem

chains = [random_chain(s, 5.0) for s in (879, 5346, 11, 12, 13)]
out = [np.array([simd.LANES], dtype=float)]
for name, model in BEAD_MODELS.items():
    states = [initial_state(model, c, E, 21)[:2] for c, E in zip(chains, (0.25, 0.5, 1.8, 4.0, 9.0))]
    q, p = np.stack([s[0] for s in states], 1), np.stack([s[1] for s in states], 1)
    dq, dp = initial_deviation(40, 1)
    dq, dp = np.tile(dq[:, None], (1, 5)), np.tile(dp[:, None], (1, 5))
    for kind in ("batch", "single", "auto"):
        problem = Problem(name, chains, dt=0.01, tangent=True, track_gaps=model.has_gaps, check_every=97)
        b = problem.engine(q, p, dq, dp, kind)
        b.advance(700)
        b.advance(300)
        out += [b.q, b.p, b.dq, b.dp, b.log_growth, b.gap_steps.astype(float), b.max_gaps.astype(float)]
sys.stdout.buffer.write(b"".join(np.ascontiguousarray(a, dtype=float).tobytes() for a in out))
"""


def _probe(width: int | None) -> np.ndarray:
    env = dict(os.environ)
    env.pop(simd.LANES_VARIABLE, None)
    env.pop("NUMBA_CACHE_DIR", None)  # the package keys its cache by the chosen width
    if width is not None:
        env[simd.LANES_VARIABLE] = str(width)
    done = subprocess.run([sys.executable, "-c", _PROBE], env=env, capture_output=True, check=True, timeout=900)
    return np.frombuffer(done.stdout, dtype=float)


@pytest.mark.slow
def test_both_engines_give_the_same_bits_at_the_other_width():
    fitted, other = _probe(None), _probe(OTHER_WIDTH)
    assert fitted[0] == simd.LANES and other[0] == OTHER_WIDTH
    assert fitted.size == other.size
    np.testing.assert_array_equal(fitted[1:].view(np.int64), other[1:].view(np.int64))


def test_a_width_outside_the_allowed_ones_is_refused(monkeypatch):
    monkeypatch.setenv(simd.LANES_VARIABLE, "3")
    with pytest.raises(ParameterError, match="CHAINCHAOS_SIMD_LANES.*'3'.*2, 4, 8"):
        simd.target_lanes()


def test_the_fitted_width_matches_the_cpu_numba_compiles_for(monkeypatch):
    monkeypatch.delenv(simd.LANES_VARIABLE, raising=False)
    assert simd.target_lanes() == (8 if simd.target_has_512_bit_vectors() else 4)


@pytest.mark.parametrize("model", sorted(BEAD_MODELS))
def test_scenes_integrated_together_equal_each_scene_alone(model):
    """Four scenes of a model with different energies, beads, deviation seeds and observables in
    one batch (the batch engine): every variable of every scene file is the one of the scene run
    alone (the single engine), to the bit."""
    chain = random_chain(879, 5.0)
    common = dict(t_final=50.0, dt=0.01, samples_per_decade=8, check_every=300)
    gaps = [o for o in ("n_gaps", "gap_fraction") if o in model_observables(model)]
    scenes = [SceneParameters(model=model, energy=1.8, **common, name="a"),
              SceneParameters(model=model, energy=0.25, **common, excited_site=15, observables=("participation",), name="b"),
              SceneParameters(model=model, energy=3.0, **common, deviation_seed=4, observables=("mlce", *gaps[:1]), name="c"),
              SceneParameters(model=model, energy=0.5, **common, observables=("eta", *gaps[1:]), name="d")]
    together = simulate_scenes(chain, scenes)
    for params, ds in zip(scenes, together):
        alone = simulate(chain, params)
        assert set(ds.data_vars) == set(alone.data_vars), params.name
        for name in alone.data_vars:
            np.testing.assert_array_equal(ds[name].values, alone[name].values, err_msg=f"{params.name}: {name}")


def test_scenes_that_cannot_share_a_batch_are_refused():
    chain = random_chain(879, 5.0)
    a = SceneParameters(model="hertz", energy=1.8, t_final=10.0, dt=0.01)
    b = SceneParameters(model="hertz", energy=0.5, t_final=10.0, dt=0.02)
    with pytest.raises(ParameterError, match="scenes"):
        simulate_scenes(chain, [a, b])
