"""The paper's quantitative statements, measured on the pipeline's results, each with a verdict.

* :mod:`~chainchaos.paper.claims.catalogue`: the claims as data, one :class:`ClaimRow` each (statement,
  the paper's value, measure, checks, time required, place in the paper);
* :mod:`~chainchaos.paper.claims.measures`: the named measures a row calls, which read the stored results
  (scene files, chain file, ensemble, energy scan, ensemble verdicts) with the criteria of the
  config block ``claims:``; the arithmetic is in :mod:`~chainchaos.paper.claims.quantities`;
* :mod:`~chainchaos.paper.claims.framework`: rows, checks, measurements, verdicts and the templates of
  the texts; :mod:`~chainchaos.paper.claims.evidence`: verdicts and reasons from the ensemble verdicts,
  the realization search and the disorder statistics;
* :mod:`~chainchaos.paper.claims.evaluation`: :func:`evaluate_claims`, the table of claims;
* :mod:`~chainchaos.paper.claims.writers`: claims.csv, the LaTeX tables and macros.tex (the rule evaluate_claims, ``chainchaos.workflow.tasks.manuscript``, writes them).

Verdicts (:data:`VERDICTS`):

``reproduced``
    the measured value satisfies the criterion;
``differs``
    it does not; the row carries the reason (a known one, e.g. a convention, when there is one);
``undecided``
    the perturbed orbits of the scene's ensemble disagree;
``not testable at this scale``
    the run ends before the time the claim needs (quick scale stops at t = 1e3 while most of the
    paper's statements concern t = 1e4..1e5). A claim that holds "for the whole run" (an orbit
    stays regular, a packet stays localized, at most one gap is open) is refuted by a short run
    that already violates it, so such a claim can still be ``differs`` at a small scale.

No number of the pipeline is typed here: the only literals are the paper's values and the
criteria, and the paper's values are the ones printed in its text.
"""

from chainchaos.paper.claims.evaluation import evaluate_claims
from chainchaos.paper.claims.framework import (
                                               DIFFERS,
                                               ENERGY_SCAN,
                                               REPRODUCED,
                                               UNDECIDED,
                                               UNTESTABLE,
                                               VERDICTS,
                                               Claim,
                                               ClaimRow,
                                               decide,
)

__all__ = ["evaluate_claims", "Claim", "ClaimRow", "decide", "VERDICTS", "REPRODUCED", "DIFFERS",
           "UNDECIDED", "UNTESTABLE", "ENERGY_SCAN"]
