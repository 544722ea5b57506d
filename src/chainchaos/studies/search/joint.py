"""The paper's statements analysed jointly over the candidates of a search (``stages.merge``, or the
archived full search): which statements hold together, which exclude each other, how the chosen
chain ranks, and whether the statements about Hertz H = 1.8's chaos agree with what chains do.

A statement "holds" on a scored candidate when its ensemble verdict is ``holds`` (at least the
``agreement`` fraction of its lanes satisfy it); a candidate's short run (stage 1) "leaves it
unbroken" when that run does not already violate it.
"""

from dataclasses import dataclass

import numpy as np
import xarray as xr

from chainchaos.paper.statements import STATEMENTS
from chainchaos.paper.verdicts import HOLDS, UNTESTABLE

#: Hertz H = 1.8's chaos: its onset "from t ~ 2e2" and its level "Lambda ~ 1e-3" (statements.STATEMENTS).
ONSET, LEVEL = "chaos-onset-H1.8-hertz", "mlce-H1.8-hertz"


@dataclass(frozen=True, kw_only=True)
class JointStatements:
    """Over the scored candidates: ``holds`` (candidate x statement, bool), ``testable`` (the
    statement was decided on some scored candidate), the co-occurrence counts ``both`` (statement
    x statement: candidates on which both hold), the statement ids, and the scores."""

    statements: list
    holds: np.ndarray
    testable: np.ndarray
    both: np.ndarray
    score: np.ndarray
    chosen_score: float

    @property
    def n_scored(self) -> int:
        return int(self.holds.shape[0])

    def exclusive_pairs(self) -> list[tuple[str, str]]:
        """Pairs of statements that each hold on some scored candidate but never on the same one."""
        alone = np.diag(self.both)
        S = len(self.statements)
        return [(self.statements[i], self.statements[j]) for i in range(S) for j in range(i + 1, S)
                if alone[i] > 0 and alone[j] > 0 and self.both[i, j] == 0]

    def all_held(self) -> int:
        """Scored candidates on which every testable statement holds."""
        return int(self.holds[:, self.testable].all(axis=1).sum())

    def at_least_as_good(self) -> int:
        """Scored candidates whose score is at least the chosen chain's."""
        return int((self.score >= self.chosen_score).sum())


def joint_statements(ds: xr.Dataset) -> JointStatements:
    """The joint analysis of the scored candidates of a merged search."""
    scored = np.flatnonzero(ds["scored"].values == 1)
    verdict = ds["verdict"].values[scored]
    holds = verdict == HOLDS
    testable = (verdict != UNTESTABLE).any(axis=0)
    both = holds.T.astype(np.int64) @ holds.astype(np.int64)
    return JointStatements(statements=[str(s) for s in ds.statement.values], holds=holds, testable=testable, both=both,
                           score=ds["score"].values[scored], chosen_score=float(ds.attrs["chosen_score"]))


def unbroken_counts(ds: xr.Dataset) -> np.ndarray:
    """Per statement: the candidates whose short run leaves it unbroken."""
    return (ds["filter_outcome"].values != 0).sum(axis=0)


def held_counts(ds: xr.Dataset) -> np.ndarray:
    """Per statement: the scored candidates on whose ensemble it holds."""
    return joint_statements(ds).holds.sum(axis=0)


def paper_onset_and_level() -> tuple[float, float]:
    """The paper's Hertz H = 1.8 pair: chaos from t ~ 2e2 and Lambda ~ 1e-3, the values of the
    statements ONSET and LEVEL."""
    value = {st.id: st.value for st in STATEMENTS}
    return value[ONSET], value[LEVEL]


def onset_and_level(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """Per scored candidate: the median over its lanes of Hertz H = 1.8's chaos onset time and of
    its final Lambda (NaN where no lane decided)."""
    scored = ds["scored"].values == 1
    median = ds["measured_median"]
    return median.sel(statement=ONSET).values[scored], median.sel(statement=LEVEL).values[scored]


def onset_level_consistency(ds: xr.Dataset, time_factor: float, level_factor: float) -> dict:
    """Whether the scored candidates show the paper's pair (:func:`paper_onset_and_level`: chaos
    from t ~ onset, Lambda levels off near level): how many have an onset within ``time_factor`` of
    it, how many a level within ``level_factor``, how many both, and the lowest level among those
    with such an onset."""
    onset, level = paper_onset_and_level()
    t, lam = onset_and_level(ds)
    near_t = np.isfinite(t) & (t >= onset / time_factor) & (t <= onset * time_factor)
    near_l = np.isfinite(lam) & (lam >= level / level_factor) & (lam <= level * level_factor)
    lowest = float(np.min(lam[near_t & np.isfinite(lam)])) if (near_t & np.isfinite(lam)).any() else float("nan")
    return {"onset_near": int(near_t.sum()), "level_near": int(near_l.sum()), "both": int((near_t & near_l).sum()),
            "lowest_level_with_onset": lowest, "decided": int((np.isfinite(t) & np.isfinite(lam)).sum())}
