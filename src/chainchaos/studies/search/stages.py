"""The realization chosen by the paper's published dynamics, not only by its linear modes.

The paper's alpha = 5 chain is unpublished. Its linear properties (mode 34 localized at bead 21,
overlaps near 1.06) leave many chains, and they differ in what the paper's scenes do. The search:

0. **Linear rule** (``selection.qualifying``, in chunks of ``seeds_per_job`` seeds): the chains
   of seeds 0..n_seeds-1 that pass the linear rule, ordered by their overlap score; the first
   ``candidates`` of them (all of them when ``candidates`` is empty) are searched.
1. **Filter**: every candidate's scenes (``statements.statement_scenes``), one orbit each, to
   ``filter_t_final``, ``candidates_per_job`` candidates per job. A statement marked ``early`` that such a run already breaks (a packet
   already spread, an orbit already chaotic) cannot hold at t = 1e5. The ``survivors`` candidates
   with the fewest broken statements go on (ties: linear-rule order).
2. **Score**: each survivor's scenes with ``lanes`` perturbed orbits to ``t_final``; per statement
   the fraction of the lanes that satisfy it (``verdicts``). A chain's score is the sum of these
   fractions over the statements: the expected number of the paper's statements one of its orbits
   satisfies. The highest score wins (ties: more statements that hold on the ensemble, then
   linear-rule order).

With ``pinned_seed`` the search is skipped: stage 2 re-scores that one chain, and the chain file
says it was pinned. The orbits of stages 1 and 2 are studies of the stage's chains, one per model
(:func:`stage_studies`, study ``<search>-<stage>-<model>``), integrated, cut into jobs and resumed
as every study is (workflow rule ``study_group``); what is the search's own is the step after each,
which judges the statements on a study's groups (:func:`judge`, :func:`filter_dataset`,
:func:`score_datasets`) and chooses. A coarser step than the scenes' is used (``settings.dt``),
which the pipeline checks by comparing the chosen chain's fractions with the ensemble verdicts at
the verdicts' step.
"""

from dataclasses import dataclass

import numpy as np
import xarray as xr

from chainchaos.errors import require
from chainchaos.paper import statements
from chainchaos.paper.criteria import Criteria
from chainchaos.paper.verdicts import (
    HOLDS,
    LANE,
    STATEMENT,
    evaluate,
    scene_verdicts,
    verdict_variables,
)
from chainchaos.paper.ensembles import scenes_study, study_runs
from chainchaos.run.orbits import OrbitSettings
from chainchaos.studies.search.selection import (
    SelectionCriteria,
    candidate_row,
    qualifying,
    ranked,
)
from chainchaos.studies.study.runs import run_group
from chainchaos.studies.study.spec import load_study

#: Version of the numbers a search computes (the kept full search records it, chainchaos.records.kept):
#: bump only when a change of code changes its numbers (a bit-identity test tells).
SEARCH_RESULT_VERSION = 2  # 2: spread-level-H1.8-hertz and eta-H4-fput follow their sentences


@dataclass(frozen=True, kw_only=True)
class SearchPlan:
    """The sizes of a search (config blocks ``search:`` and ``search_full:``). ``candidates``:
    how many chains that pass the linear rule are searched, None for all of them."""

    candidates: int | None = 32
    candidates_per_job: int = 8
    survivors: int = 4
    lanes: int = 4
    filter_t_final: float = 1e4
    seeds_per_job: int = 10000
    pinned_seed: int | None = None

    def __post_init__(self):
        for key in ("candidates_per_job", "survivors", "lanes", "seeds_per_job"):
            value = getattr(self, key)
            require(isinstance(value, int) and value >= 1, key, value, "an integer >= 1")
        require(self.candidates is None or (isinstance(self.candidates, int) and self.candidates >= 1),
                "candidates", self.candidates, "empty (every chain that passes the linear rule) or an integer >= 1")
        require(self.filter_t_final > 0, "filter_t_final", self.filter_t_final, "> 0")
        require(self.pinned_seed is None or (isinstance(self.pinned_seed, int) and self.pinned_seed >= 0),
                "pinned_seed", self.pinned_seed, "empty (search) or an integer seed >= 0")

    @classmethod
    def from_config(cls, block: dict) -> "SearchPlan":
        keys = ("candidates", "candidates_per_job", "survivors", "lanes", "filter_t_final", "seeds_per_job",
                "pinned_seed")
        return cls(**{k: block[k] for k in keys if k in block})

    @property
    def pinned(self) -> bool:
        return self.pinned_seed is not None

    def n_seed_jobs(self, selection: SelectionCriteria) -> int:
        """Stage-0 jobs: chunks of ``seeds_per_job`` of the ``selection.n_seeds`` seeds."""
        return -(-int(selection.n_seeds) // self.seeds_per_job)

    def n_filter_jobs(self, n_candidates: int) -> int:
        """Stage-1 jobs for ``n_candidates`` candidates (stage 0's count)."""
        return 0 if self.pinned else -(-int(n_candidates) // self.candidates_per_job)

    def n_score_jobs(self, n_candidates: int) -> int:
        """Stage-2 jobs for ``n_candidates`` candidates."""
        return 1 if self.pinned else min(self.survivors, int(n_candidates))


def _scene_names(scenes=None) -> list[str]:
    """The statement scenes run, in table order: all, or those named in ``scenes``."""
    return [name for name in statements.statement_scenes() if scenes is None or name in scenes]


#: The stages whose orbits are studies: ``filter`` (one short orbit per scene of every candidate)
#: and ``score`` (``lanes`` orbits per scene of each survivor).
STUDY_STAGES = ("filter", "score")


def study_name(search: str, stage: str, model: str) -> str:
    """The name of the study of a search's stage for one model: ``<search>-<stage>-<model>``."""
    return f"{search}-{stage}-{model}"


def search_models(scenes=None) -> list[str]:
    """The models of the statement scenes run (:func:`_scene_names`), in table order."""
    of = statements.statement_scenes()
    return list(dict.fromkeys(of[name].model for name in _scene_names(scenes)))


def stage_studies(search: str, stage: str, selection: SelectionCriteria, plan: SearchPlan, settings: OrbitSettings,
                  criteria: Criteria, site: int, seeds, scenes=None) -> dict[str, dict]:
    """The studies of a stage's orbits on the chains of ``seeds``, one per model (``model ->`` the
    study's keys, ``paper.ensembles.scenes_study``).

    ``filter``: one orbit per scene to ``plan.filter_t_final``, judged by Λ alone (GALI_k's verdicts
    are taken on the scored ensembles), ``candidates_per_job`` chains per job; ``score``:
    ``plan.lanes`` orbits per scene to ``settings.t_final``, one chain per job. ``scenes``: only
    these statement scenes."""
    require(stage in STUDY_STAGES, "stage", stage, f"one of {STUDY_STAGES}")
    filtering = stage == "filter"
    run = OrbitSettings(**{**vars(settings), "t_final": float(plan.filter_t_final), "alignment": False}) \
        if filtering else settings
    return _scene_studies(lambda model: study_name(search, stage, model), selection, seeds, run,
                          1 if filtering else plan.lanes, site, criteria,
                          f"Realization search ({search}), stage {stage}", plan.candidates_per_job if filtering else 1,
                          scenes)


def _scene_studies(name, selection: SelectionCriteria, seeds, settings: OrbitSettings, lanes: int, site: int,
                   criteria: Criteria, title: str, per_job: int | None, scenes=None) -> dict[str, dict]:
    """``model ->`` the study (``paper.ensembles.scenes_study``) of its statement scenes on the
    chains of ``seeds``, named ``name(model)``; ``per_job`` chains per job (None: all)."""
    of = statements.statement_scenes()
    names = _scene_names(scenes)
    lattice = {"seeds": [int(seed) for seed in seeds], "N": int(selection.N), "alpha": float(selection.alpha)}
    return {model: scenes_study(name(model), model, [of[n].energy for n in names if of[n].model == model], lattice,
                                settings, lanes, site, criteria, f"{title}: the {model} scenes of its chains", per_job)
            for model in search_models(scenes)}


def judge(groups: dict[str, list[xr.Dataset]], n_chains: int, lanes: int, criteria: Criteria, scenes=None):
    """The statements judged on the studies of a stage (:func:`stage_studies`).

    Parameters
    ----------
    groups : dict
        ``model ->`` the group files of that model's study.
    n_chains : int
        The study's realizations (the chains of the stage, in its order).
    lanes : int
        Orbits per scene and chain.
    criteria : Criteria
        The claims' criteria.
    scenes : list of str, optional
        The statement scenes run (default all); the other statements stay NaN.

    Returns
    -------
    result : dict
        ``verdicts.evaluate``'s keys as arrays (chain, statement, lane), ``read_gali`` (chain, statement).
    energy_error : numpy.ndarray
        Each chain's largest relative energy error over its orbits.
    """
    names = _scene_names(scenes)
    of = statements.statement_scenes()
    ids = [st.id for st in statements.STATEMENTS]
    keys = ("value", "outcome", "value_gali", "outcome_gali")
    result = {key: np.full((n_chains, len(ids), lanes), np.nan) for key in keys}
    result["read_gali"] = np.zeros((n_chains, len(ids)), dtype=bool)
    energy_error = [[] for _ in range(n_chains)]
    for model, model_groups in groups.items():
        t, runs = study_runs(model_groups)
        for k, name in enumerate(n for n in names if of[n].model == model):
            of_scene = statements.statements_of_scene(name)
            for c in range(n_chains):
                ev = evaluate(of_scene, t, runs[k, c], criteria)
                for i, st in enumerate(of_scene):
                    for key in (*keys, "read_gali"):
                        result[key][c, ids.index(st.id)] = ev[key][i]
                energy_error[c] += [np.nanmax(r["energy_error"]) for r in runs[k, c]]
    return result, np.array([max(e) for e in energy_error]) if n_chains else np.zeros(0)


def _outcomes(seeds: list[int], selection: SelectionCriteria, site: int, lanes: int, settings: OrbitSettings,
              criteria: Criteria, progress=None, scenes=None):
    """:func:`judge` on the chains of ``seeds`` integrated in this process, each model's orbits one
    study (``paper.ensembles.scenes_study``, ``studies.study.runs.run_group``): the re-judging of
    a kept search (``rejudge``) runs them so. ``scenes``: run only these statement scenes; an
    orbit's numbers do not depend on which others run beside it."""
    studies = _scene_studies(lambda model: f"search-{model}", selection, seeds, settings, lanes, site, criteria,
                             "Realization search", None, scenes) if len(seeds) else {}
    groups = {model: [run_group(load_study(keys), 0, progress)] for model, keys in studies.items()}
    return judge(groups, len(seeds), lanes, criteria, scenes)


def seed_chunk(selection: SelectionCriteria, plan: SearchPlan, chunk: int) -> xr.Dataset:
    """Stage 0 for one chunk of seeds, ``chunk * seeds_per_job`` up to the next chunk or
    ``selection.n_seeds``: the chains that pass the linear rule, with their linear-rule data."""
    n = plan.n_seed_jobs(selection)
    require(0 <= chunk < n, "chunk", chunk, f"0..{n - 1} (n_seeds / seeds_per_job)")
    seeds = range(chunk * plan.seeds_per_job, min((chunk + 1) * plan.seeds_per_job, int(selection.n_seeds)))
    rows = qualifying(selection, seeds)
    ds = xr.Dataset(_seed_dataset(rows), coords={"candidate": _candidates(np.arange(len(rows)))})
    ds.attrs.update(title="Realization search, stage 0: the chains of a chunk of seeds that pass the linear rule",
                    first_seed=int(seeds.start), seeds_scanned=len(seeds))
    return ds


def candidates(selection: SelectionCriteria, plan: SearchPlan, chunks: list[xr.Dataset] | None = None) -> xr.Dataset:
    """Stage 0, once per search: the candidates (the first ``plan.candidates`` chains passing the
    linear rule, all of them when it is None, or the pinned seed) with their linear-rule data, and
    in the attribute ``n_qualifying`` how many of the scanned seeds pass the rule. ``chunks``: the
    :func:`seed_chunk` results of every chunk (computed here when None). Later stages read this."""
    if chunks is None:
        chunks = [seed_chunk(selection, plan, k) for k in range(plan.n_seed_jobs(selection))]
    scanned = sum(int(c.attrs["seeds_scanned"]) for c in chunks)
    require(scanned == int(selection.n_seeds), "seed chunks", f"{scanned} seeds",
            f"the {selection.n_seeds} seeds of chain.selection.n_seeds")
    found = ranked([row for c in chunks for row in candidate_rows(c)])
    rows = [candidate_row(plan.pinned_seed, selection)] if plan.pinned else found[:plan.candidates]
    ds = xr.Dataset(_seed_dataset(rows), coords={"candidate": _candidates(np.arange(len(rows)))})
    ds.attrs.update(title="Realization search, stage 0: the candidate chains of the linear rule",
                    n_qualifying=len(found), seeds_scanned=scanned, pinned=int(plan.pinned))
    return ds


def candidate_rows(ds: xr.Dataset) -> list[dict]:
    """The rows of :func:`candidates`' Dataset as dicts (seed, score, mode_participation, ...)."""
    return [{"seed": int(ds["seed"].values[i]), "score": float(ds["linear_score"].values[i]),
             "mode_participation": float(ds["mode_participation"].values[i]),
             "overlap_left": float(ds["overlap_left"].values[i]), "overlap_right": float(ds["overlap_right"].values[i])}
            for i in range(ds.sizes["candidate"])]


def _candidates(index: np.ndarray) -> tuple:
    return ("candidate", index, {"units": "1", "long_name": "candidate index, in the linear rule's order"})


def _statements(of) -> tuple:
    return ("statement", [st.id for st in of], STATEMENT)


def _seed_dataset(rows: list[dict]) -> dict:
    one = {"units": "1"}
    return {
        "seed": ("candidate", np.array([r["seed"] for r in rows], dtype=np.int64),
                 {**one, "long_name": "seed of numpy.random.default_rng drawing the radii"}),
        "linear_score": ("candidate", np.array([r["score"] for r in rows]),
                         {**one, "long_name": "|delta_site - target| + |delta_site+1 - target| (linear rule)"}),
        "mode_participation": ("candidate", np.array([r["mode_participation"] for r in rows]),
                               {**one, "long_name": "participation number of the selection mode"}),
        "overlap_left": ("candidate", np.array([r["overlap_left"] for r in rows]),
                         {**one, "long_name": "static overlap delta of the excited bead's left bond"}),
        "overlap_right": ("candidate", np.array([r["overlap_right"] for r in rows]),
                          {**one, "long_name": "static overlap delta of the excited bead's right bond"}),
    }


def filter_dataset(plan: SearchPlan, settings: OrbitSettings, criteria: Criteria, found: xr.Dataset,
                   groups: dict[str, list[xr.Dataset]]) -> xr.Dataset:
    """Stage 1 judged: every candidate's filter outcomes (candidate, statement) on the groups of the
    filter studies (``model ->`` groups, :func:`stage_studies`), and the ``survivor`` candidates
    (by rank) that go on to stage 2 (:func:`survivors`)."""
    rows = candidate_rows(found)
    ev, err = judge(groups, len(rows), 1, criteria)
    data = _seed_dataset(rows)
    data.update({
        "outcome": (("candidate", "statement"), ev["outcome"][:, :, 0],
                    {"units": "1", "long_name": "1 satisfied, 0 already violated, NaN not decided by the short run"}),
        "measured": (("candidate", "statement"), ev["value"][:, :, 0],
                     {"long_name": "measured value of the statement (one orbit, short run)"}),
        "energy_error_max": ("candidate", err, {"units": "1", "long_name": "largest relative energy error"}),
    })
    ds = xr.Dataset(data, coords={"candidate": _candidates(np.arange(len(rows))),
                                  "statement": _statements(statements.STATEMENTS)})
    ds["survivor"] = ("rank", survivors([ds], plan).astype(np.int64),
                      {"units": "1", "long_name": "candidate of each rank that goes on to stage 2"})
    ds.attrs.update(title="Realization search, stage 1: one orbit per scene of every candidate", stage="filter",
                    t_final=float(plan.filter_t_final), dt=float(settings.dt))
    return ds


def survivors(filter_groups: list[xr.Dataset], plan: SearchPlan) -> np.ndarray:
    """Candidate indices that go on to stage 2: the fewest statements broken by the short run,
    then linear-rule order."""
    if plan.pinned:
        return np.array([0])
    ds = xr.concat(filter_groups, dim="candidate") if len(filter_groups) > 1 else filter_groups[0]
    broken = (ds["outcome"].values == 0).sum(axis=1)
    order = np.lexsort((ds["candidate"].values, broken))
    return ds["candidate"].values[order][:plan.n_score_jobs(ds.sizes["candidate"])]


def _score_dataset(plan: SearchPlan, settings: OrbitSettings, criteria: Criteria, row: dict, candidate: int,
                   ev: dict, err: float) -> xr.Dataset:
    """Stage 2 of one candidate from its judged lanes (``ev``: :func:`judge`'s arrays of its chain)."""
    data = _seed_dataset([row])
    data = {k: ((), v[1][0], v[2]) for k, v in data.items()}
    data.update({
        **verdict_variables(ev, scene_verdicts(ev, criteria.agreement)),
        "energy_error_max": ((), float(err), {"units": "1", "long_name": "largest relative energy error"}),
    })
    ds = xr.Dataset(data, coords={"statement": _statements(statements.STATEMENTS),
                                  "lane": ("lane", np.arange(plan.lanes), LANE)})
    ds.attrs.update(title=f"Realization search, stage 2: the ensemble of candidate {candidate}",
                    stage="score", candidate=int(candidate), t_final=float(settings.t_final), dt=float(settings.dt),
                    lanes=int(plan.lanes))
    return ds


def score_datasets(plan: SearchPlan, settings: OrbitSettings, criteria: Criteria, found: xr.Dataset,
                   ranked: np.ndarray, groups: dict[str, list[xr.Dataset]]) -> list[xr.Dataset]:
    """Stage 2 judged: per survivor (``ranked``: its candidate index, by rank, the realizations of
    the score studies) the lanes' outcomes, fractions and verdicts, from the score studies'
    groups (``model ->`` groups, :func:`stage_studies`)."""
    rows = candidate_rows(found)
    ev, err = judge(groups, len(ranked), plan.lanes, criteria)
    return [_score_dataset(plan, settings, criteria, rows[int(c)], int(c), {key: v[r] for key, v in ev.items()},
                           err[r]) for r, c in enumerate(ranked)]


def score_candidate(selection: SelectionCriteria, plan: SearchPlan, settings: OrbitSettings, criteria: Criteria,
                    rows: list[dict], candidate: int, site: int, progress=None) -> xr.Dataset:
    """Stage 2 for one candidate (index into ``rows``) in this process (``rejudge`` scores a
    candidate the kept search did not so): ``plan.lanes`` perturbed orbits per scene to
    ``settings.t_final``; per statement the lanes' outcomes, fraction and verdict."""
    row = rows[candidate]
    ev, err = _outcomes([row["seed"]], selection, site, plan.lanes, settings, criteria, progress)
    return _score_dataset(plan, settings, criteria, row, candidate, {key: v[0] for key, v in ev.items()}, err[0])


def chain_score(fraction: np.ndarray) -> float:
    """Expected number of statements satisfied by one orbit: the sum of the fractions (an
    undecidable statement counts 0)."""
    return float(np.nansum(fraction))


_FLAGS = np.array([-3, -2, -1, 0, 1], dtype=np.int8)
#: Attributes of the merged search's per-indicator fractions and verdicts (candidate, statement).
INDICATOR_ATTRS = {
    "fraction_lambda": {"units": "1", "long_name": "stage 2: fraction of the lanes that satisfy the statement by Lambda"},
    "fraction_gali": {"units": "1", "long_name": "stage 2: fraction of the lanes that satisfy the statement by GALI_k",
                      "comment": "NaN: not scored, or a statement GALI_k does not decide"},
    "verdict_lambda": {"long_name": "stage 2 ensemble verdict by Lambda", "flag_values": _FLAGS,
                       "flag_meanings": "not_scored not_testable undecided fails holds"},
    "verdict_gali": {"long_name": "stage 2 ensemble verdict by GALI_k", "flag_values": _FLAGS,
                     "flag_meanings": "not_scored_or_not_read not_testable undecided fails holds"},
}


def merge(selection: SelectionCriteria, plan: SearchPlan, settings: OrbitSettings, criteria: Criteria,
          found: xr.Dataset, filter_groups: list[xr.Dataset], scores: list[xr.Dataset]) -> xr.Dataset:
    """The search as one Dataset: the candidates (``found``, from :func:`candidates`), every
    candidate's stage-1 outcomes, the survivors' stage-2 fractions and verdicts, scores, and the
    chosen seed (attribute ``chosen_seed``)."""
    rows = candidate_rows(found)
    C, S = len(rows), len(statements.STATEMENTS)
    data = _seed_dataset(rows)
    filt = np.full((C, S), np.nan)
    for g in filter_groups:
        filt[g["candidate"].values] = g["outcome"].values
    frac = np.full((C, S), np.nan)
    verdict = np.full((C, S), -3, dtype=np.int8)
    # per indicator (a score written before GALI_k joined: its fraction and verdict are Λ's, GALI_k not read)
    by_indicator = {"fraction_lambda": np.full((C, S), np.nan), "fraction_gali": np.full((C, S), np.nan),
                    "verdict_lambda": np.full((C, S), -3, dtype=np.int8),
                    "verdict_gali": np.full((C, S), -3, dtype=np.int8)}
    median = np.full((C, S), np.nan)
    score = np.full(C, np.nan)
    holds = np.zeros(C, dtype=np.int32)
    err = np.full(C, np.nan)
    for s in scores:
        c = int(s.attrs["candidate"])
        frac[c], verdict[c] = s["fraction"].values, s["verdict"].values
        for key, array in by_indicator.items():
            if key in s:
                array[c] = s[key].values
            elif key.endswith("_lambda"):
                array[c] = s[key.removesuffix("_lambda")].values
        values = s["measured"].values
        finite = np.isfinite(values)
        median[c] = [np.median(v[f]) if f.any() else np.nan for v, f in zip(values, finite)]
        score[c] = chain_score(s["fraction"].values)
        holds[c] = int((s["verdict"].values == HOLDS).sum())
        err[c] = float(s["energy_error_max"].values)
    scored = np.flatnonzero(np.isfinite(score))
    require(scored.size > 0, "search", "no scored candidate", "at least one stage-2 result")
    best = scored[np.lexsort((scored, -holds[scored], -score[scored]))][0]
    listed = statements.STATEMENTS
    data.update({
        "filter_outcome": (("candidate", "statement"), filt, {
            "units": "1", "long_name": "stage 1: 1 satisfied, 0 already violated, NaN not decided by the short run"}),
        "filter_broken": ("candidate", (filt == 0).sum(axis=1).astype(np.int32),
                          {"units": "1", "long_name": "stage 1: statements already violated"}),
        "scored": ("candidate", np.isfinite(score).astype(np.int8), {"units": "1", "long_name": "1 if scored in stage 2"}),
        "fraction": (("candidate", "statement"), frac, {
            "units": "1", "long_name": "stage 2: fraction of the lanes that satisfy the statement"}),
        "verdict": (("candidate", "statement"), verdict, {
            "long_name": "stage 2 ensemble verdict (undecided where the indicators disagree)", "flag_values": _FLAGS,
            "flag_meanings": "not_scored not_testable undecided fails holds"}),
        **{key: (("candidate", "statement"), array, INDICATOR_ATTRS[key]) for key, array in by_indicator.items()},
        "measured_median": (("candidate", "statement"), median, {
            "long_name": "stage 2: median over the lanes of the statement's measured value"}),
        "score": ("candidate", score, {"units": "1", "long_name": "sum over statements of the fraction satisfied"}),
        "statements_held": ("candidate", holds, {"units": "1", "long_name": "statements that hold on the ensemble"}),
        "energy_error_max": ("candidate", err, {"units": "1", "long_name": "largest relative energy error (stage 2)"}),
        "scene": ("statement", np.array([st.scene.name for st in listed], dtype=object)),
        "kind": ("statement", np.array([st.kind for st in listed], dtype=object)),
        "text": ("statement", np.array([st.text for st in listed], dtype=object)),
    })
    ds = xr.Dataset(data, coords={"candidate": _candidates(np.arange(C)), "statement": _statements(listed)})
    ds.attrs.update(
        title="Realization search: the paper's statements on candidate chains",
        pinned=int(plan.pinned), chosen_candidate=int(best), chosen_seed=int(rows[best]["seed"]),
        chosen_score=float(score[best]), n_candidates=int(C), n_scored=int(scored.size),
        n_statements=int(S), filter_t_final=float(plan.filter_t_final), t_final=float(settings.t_final),
        dt=float(settings.dt), integrator=settings.integrator, lanes=int(plan.lanes),
        perturbation=float(settings.perturbation), agreement=float(criteria.agreement),
        gali_order=settings.judged_gali_order,
        seeds_scanned=int(selection.n_seeds), alpha=float(selection.alpha),
        n_qualifying=int(found.attrs["n_qualifying"]),
    )
    return ds
