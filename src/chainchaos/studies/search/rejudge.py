"""A kept full search re-judged where the code that judges some statements changed.

The full search (``stages``, kept in ``data/search/search_full.nc``) costs hours. When the code of
a few statements' judgement changes (not their scenes, nor the orbits' settings), the kept file
holds everything else: each statement's outcome is decided on the orbits of its own scene
alone, and an orbit's numbers do not depend on the orbits integrated beside it. So only the
scenes of the changed statements are integrated again:

1. **Filter** (:func:`filter_group`): every candidate's orbit of each such scene whose changed
   statements a short run can decide (``early``, or needing no more than ``filter_t_final``), one
   lane to ``filter_t_final``, in the search's groups of candidates.
2. **Score** (:func:`score_candidate`): the survivors of the re-judged filter (the same rule,
   ``stages.survivors``). A survivor scored before re-runs the changed statements' scenes with its
   lanes; one that was not is scored in full (``stages.score_candidate``).
3. **Merge** (:func:`rejudged_search`): the kept file's outcomes with the changed statements'
   columns replaced, merged by ``stages.merge`` as a full search would be.

Every recomputed orbit also decides its scene's unchanged statements, which must equal the kept
file's (filter outcomes; score fractions, verdicts and median measured values): a difference
stops the merge (:class:`RejudgeMismatch`), since then the kept file is not what this code
computes and only a full remake (``snakemake --cores 2 keep --config keep=search_full``) is
sound.

The stage files are kept too (the re-judging may take more than a session), so each records its
key (``records.kept``, :func:`stage_settings`): the kept search it re-judges and the statements
re-judged, with the search's result version. A stage file whose key is not the run's is not read.
"""

import numpy as np
import xarray as xr

from chainchaos.errors import require
from chainchaos.paper import statements
from chainchaos.paper.verdicts import STATEMENT_KINDS, scene_verdicts
from chainchaos.records import kept as kept_files
from chainchaos.studies.search import stages
from chainchaos.studies.search.stages import (
    SEARCH_RESULT_VERSION,
    _outcomes,
    candidate_rows,
)

#: The per-statement stage-2 columns of a score file that the merge reads.
SCORE_COLUMNS = ("fraction", "verdict", "fraction_lambda", "fraction_gali", "verdict_lambda", "verdict_gali")


class RejudgeMismatch(RuntimeError):
    """A recomputed orbit disagrees with the kept search on a statement whose judgement did not change."""


def _ids() -> list[str]:
    return [st.id for st in statements.STATEMENTS]


def check_ids(ids) -> list[str]:
    """The statement ids to re-judge, each one of ``statements.STATEMENTS``."""
    known = _ids()
    ids = list(ids or [])
    require(len(ids) > 0, "rejudge", ids, f"a list of statement ids, of {known}")
    for i in ids:
        require(i in known, "rejudge", i, f"a statement id, one of {known}")
    return ids


def scenes_of(ids) -> list[str]:
    """The scenes of the statements ``ids``, in table order."""
    of = {st.id: st.scene.name for st in statements.STATEMENTS}
    return [name for name in statements.statement_scenes() if name in {of[i] for i in ids}]


def filter_scenes(ids, filter_t_final: float) -> list[str]:
    """The scenes whose changed statements a short run can decide (the others' filter outcome is
    NaN whatever the code: ``verdicts._decide``)."""
    decidable = [st.id for st in statements.STATEMENTS if st.id in ids
                 and (st.early or STATEMENT_KINDS[st.kind][2](st) <= filter_t_final)]
    return scenes_of(decidable)


def filter_plan(plan, ids):
    """The search's plan with groups of as many orbits as its filter jobs: a group of the re-judged
    filter runs fewer scenes per candidate, so more candidates (numbers do not depend on it)."""
    from dataclasses import replace

    scenes = max(1, len(filter_scenes(ids, plan.filter_t_final)))
    return replace(plan, candidates_per_job=plan.candidates_per_job * max(1, len(statements.statement_scenes()) // scenes))


def stage_settings(kept: xr.Dataset, ids) -> dict:
    """What a stage file's numbers depend on besides the code (whose result version is the
    search's): the kept search re-judged, by its settings digest and result version, and the
    statements re-judged."""
    return {"kept_search_digest": str(kept.attrs[kept_files.DIGEST_ATTR]),
            "kept_search_result_version": int(kept.attrs[kept_files.VERSION_ATTR]),
            "rejudge": sorted(ids)}


def stage_key(kept: xr.Dataset, ids) -> dict:
    """The global attributes that key a stage file (``records.kept.kept_attrs``)."""
    return kept_files.kept_attrs(stage_settings(kept, ids), SEARCH_RESULT_VERSION)


def kept_rows(kept: xr.Dataset) -> list[dict]:
    """The candidates of the kept search, as ``stages.candidate_rows``."""
    return candidate_rows(kept)


def filter_group(kept: xr.Dataset, selection, plan, settings, criteria, ids, group: int, site: int,
                 progress=None) -> xr.Dataset:
    """Stage 1 again for one group of candidates, on the scenes of :func:`filter_scenes` only:
    ``outcome`` (candidate, statement), NaN for the statements of the other scenes."""
    rows = kept_rows(kept)
    plan = filter_plan(plan, ids)
    n_jobs = plan.n_filter_jobs(len(rows))
    require(0 <= group < max(n_jobs, 1), "group", group, f"0..{n_jobs - 1}")
    rows = rows[group * plan.candidates_per_job:(group + 1) * plan.candidates_per_job]
    scenes = filter_scenes(ids, plan.filter_t_final)
    first = group * plan.candidates_per_job
    outcome = np.full((len(rows), len(_ids())), np.nan)
    if scenes and rows:
        short = type(settings)(**{**vars(settings), "t_final": float(plan.filter_t_final), "alignment": False})
        outcome = _outcomes([r["seed"] for r in rows], selection, site, 1, short, criteria, progress,
                            scenes)[0]["outcome"][:, :, 0]
    ds = xr.Dataset({"outcome": (("candidate", "statement"), outcome, {
        "units": "1", "long_name": "1 satisfied, 0 already violated, NaN not decided by the short run (or not rerun)"})},
        coords={"candidate": ("candidate", np.arange(first, first + len(rows))), "statement": _ids()})
    ds.attrs.update(title="Re-judged search, stage 1: the changed statements' scenes of a job's candidates",
                    stage="rejudge_filter", scenes=" ".join(scenes), group=int(group), **stage_key(kept, ids))
    return ds


def _same(a, b) -> bool:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return bool(np.array_equal(a, b, equal_nan=True))


def rejudged_filter(kept: xr.Dataset, groups: list[xr.Dataset], ids, plan) -> xr.Dataset:
    """The kept filter outcomes with the changed statements' columns of the recomputed scenes
    replaced; the unchanged statements of those scenes must be the kept file's."""
    outcome = np.array(kept["filter_outcome"].values, dtype=float)
    scenes = filter_scenes(ids, plan.filter_t_final)
    # a changed statement that no short run decides has no filter outcome, whatever the code
    outcome[:, [k for k, st in enumerate(statements.STATEMENTS)
                if st.id in ids and st.scene.name not in scenes]] = np.nan
    cols = [k for k, st in enumerate(statements.STATEMENTS) if st.scene.name in scenes]
    for g in groups:
        at = g["candidate"].values
        for k in cols:
            new = g["outcome"].values[:, k]
            if statements.STATEMENTS[k].id in ids:
                outcome[at, k] = new
            elif not _same(new, outcome[at, k]):
                raise RejudgeMismatch(f"filter group {int(g.attrs['group'])}: statement {statements.STATEMENTS[k].id} "
                                      f"is not the kept search's on the recomputed orbits")
    return xr.Dataset({"outcome": (("candidate", "statement"), outcome)},
                      coords={"candidate": kept["candidate"].values, "statement": _ids()})


def survivor(kept: xr.Dataset, filtered: xr.Dataset, plan, rank: int) -> int:
    """The candidate of the given rank among the survivors of the re-judged filter."""
    ranks = stages.survivors([filtered], plan)
    require(0 <= rank < ranks.size, "rank", rank, f"0..{ranks.size - 1}")
    return int(ranks[rank])


def score_candidate(kept: xr.Dataset, selection, plan, settings, criteria, ids, candidate: int, site: int,
                    progress=None) -> xr.Dataset:
    """Stage 2 of one survivor: its changed statements' scenes again when the kept search scored
    it (the other statements' columns from the kept file, checked on the recomputed scenes), else
    in full (``stages.score_candidate``)."""
    rows = kept_rows(kept)
    if not int(kept["scored"].values[candidate]):
        ds = stages.score_candidate(selection, plan, settings, criteria, rows, candidate, site, progress)
        ds.attrs.update(rejudge="scored in full (not a survivor of the kept search)", **stage_key(kept, ids))
        return ds
    scenes = scenes_of(ids)
    ev, _ = _outcomes([rows[candidate]["seed"]], selection, site, plan.lanes, settings, criteria, progress, scenes)
    ev = {key: v[0] for key, v in ev.items()}
    sv = scene_verdicts(ev, criteria.agreement)
    columns = {key: np.array(kept[key].values[candidate]) for key in SCORE_COLUMNS}
    measured = np.repeat(np.asarray(kept["measured_median"].values[candidate], dtype=float)[:, None], plan.lanes, 1)
    for k, st in enumerate(statements.STATEMENTS):
        if st.scene.name not in scenes:
            continue
        new = {key: sv[key][k] for key in SCORE_COLUMNS}
        if st.id in ids:
            for key in SCORE_COLUMNS:
                columns[key][k] = new[key]
            measured[k] = ev["value"][k]
            continue
        finite = np.isfinite(ev["value"][k])
        median = np.median(ev["value"][k][finite]) if finite.any() else np.nan
        if not (all(_same(new[key], columns[key][k]) for key in SCORE_COLUMNS)
                and _same(median, kept["measured_median"].values[candidate, k])):
            raise RejudgeMismatch(f"candidate {candidate}: statement {st.id} is not the kept search's on the "
                                  "recomputed orbits")
    lanes = np.arange(plan.lanes)
    data = {key: ("statement", columns[key]) for key in SCORE_COLUMNS}
    data["measured"] = (("statement", "lane"), measured, {
        "long_name": "measured value per lane (the kept median, repeated, for statements not re-judged)"})
    data["energy_error_max"] = ((), float(kept["energy_error_max"].values[candidate]))
    ds = xr.Dataset(data, coords={"statement": _ids(), "lane": lanes})
    ds.attrs.update(title=f"Re-judged search, stage 2: candidate {candidate}", stage="rejudge_score",
                    candidate=int(candidate), rejudge=f"scenes {' '.join(scenes)} recomputed", **stage_key(kept, ids))
    return ds


def rejudged_search(kept: xr.Dataset, selection, plan, settings, criteria, filtered: xr.Dataset,
                    scores: list[xr.Dataset]) -> xr.Dataset:
    """The search merged as ``stages.merge`` merges a full one, from the re-judged filter and the
    survivors' scores."""
    found = kept[["seed", "linear_score", "mode_participation", "overlap_left", "overlap_right"]]
    found.attrs = {"n_qualifying": int(kept.attrs["n_qualifying"])}
    filt = filtered.assign_coords(candidate=kept["candidate"].values)
    return stages.merge(selection, plan, settings, criteria, found, [filt], scores)
