"""The paper's quantitative statements as data: one :class:`ClaimRow` per claim, in table order.

Each row quotes the paper's words it encodes (``quote``: passages of the paper's LaTeX source, from
the section its ``where`` names; tests/paper/test_claims_catalogue.py finds them in the paper) and names
the statement and value, the measure that reads the stored results
(:data:`chainchaos.paper.claims.measures.MEASURES`), the checks of the verdict, the time the statement
needs and the texts of the claims table (templates, see :mod:`chainchaos.paper.claims.framework`). The
only numbers here are the paper's values, printed in its text, and the times its statements are
about; every threshold comes from the config block ``claims:``.

A criterion says what the quoted sentence says, no more and no less:

* a bound stays a bound: "for energies $H > 1.8$ [...] always [...] a delocalized chaotic state" is
  checked at every scanned energy above 1.8 and says nothing below it (the paper's own Hertz orbit
  at $H = 0.5$ is chaotic); "$P < 3$" is an upper bound;
* a range stays a range: "$0.5 \\lesssim H \\lesssim 1.8$" is an interval whose ends are bracketed by
  the paper's own runs (the next one below 0.5 is 0.25, where the packet stays localized);
* a value gets the tolerance of how the paper gives it (:class:`chainchaos.paper.criteria.Tolerances`
  says why each is what it is): an exact quantity printed to a digit (u_21(0) = 1.01,
  delta ~ 1.06, P ~ 2.5 of mode 34) one unit of that digit; a participation number read off a curve
  (P ~ 1.8, 26, <P> ~ 2, P_D ~ 20) ``participation_relative``; a time read off a logarithmic time axis
  (t ~ 2e2, 3e2, 4e3) ``time_factor``; a bare power of ten (Lambda ~ 1e-3) ``mlce_factor``; an entropy
  level read off an eta(t) plot ``eta_plateau``; "around H = 2.9" among the paper's few energies
  ``threshold_factor``; a statement without a number ("almost overlap", "close to <eta>") the
  tolerance its row names;
* a statement about the whole run ("a constant value", "the curves almost overlap", "remains
  regular") needs the paper's $t = 10^5$ and is refuted by a shorter run that already breaks it.

Families of rows that differ only by scene (a packet stays localized, an orbit is chaotic) are
built by the functions below, as ``statements._pair`` builds the statements; :func:`statement_rows`
adds a row for every statement of ``statements.STATEMENTS`` that no row here rests on, quoting
:data:`STATEMENT_QUOTES`.
"""

from chainchaos.paper import panels, statements
from chainchaos.paper import verdicts as _verdicts
from chainchaos.paper.claims.framework import (
    CHAOS_CRITERION_TEXT,
    ENERGY_SCAN,
    Check,
    ClaimRow,
    literal,
)
from chainchaos.records.formatting import tex_parameter
from chainchaos.system.models import model_label

T_PAPER = 1e5  # the paper's integration time: a statement about "the end" needs it

CHAOS = literal(CHAOS_CRITERION_TEXT)
CHAOS_TEXT = "slope {slope:math2}, growth excess {growth:math2}, $\\Lambda(t_\\mathrm{{end}}) = {mlce:tex}$"
RELATIVE_P = "tolerance.participation_relative"

HZ25, FP25 = panels.HZ[0.25].name, panels.FP[0.25].name
HZ05, FP05 = panels.HZ[0.5].name, panels.FP[0.5].name
HZ18, FP18 = panels.HZ[1.8].name, panels.FP[1.8].name
HZ3 = panels.HZ[3.0].name
FP29, FP4, FP87 = panels.FP[2.9].name, panels.FP[4.0].name, panels.FP[8.7381].name

# ---- the paper's words, passages of its LaTeX source (section in the row's `where`) --------------

#: Sec. III B 2: the Hertz threshold, a bound (nothing is said below 1.8).
HERTZ_ALWAYS = (r"For energies  $ H >1.8 $ we have found that the dynamics of the Hertzian model always lead to a "
                r"delocalized chaotic state.")
#: Sec. III B 3: the FPUT chaos threshold, a bound.
FPUT_ALWAYS_CHAOTIC = (r"regarding the chaoticity of the FPUT system, we found that for high energies, $H>2.8$, the "
                       r"system is always chaotic irrespectively of the localized or delocalized nature of the "
                       r"wave-packet")
#: Sec. III B 3: the first FPUT energy that delocalizes.
FPUT_FIRST = (r"The first energy at which the FPUT model's wave-packet is delocalized, exhibiting also a chaotic "
              r"behavior, is around $H = 2.9$")
#: Sec. III B 1: the Hertz packet at H = 1.8.
HERTZ_18_LOCALIZED = r"although up to $t\approx 2\times 10^2$ the wave-packet is localized"
HERTZ_18_SPREADS = r"it then rapidly spreads until $t\approx 4\times 10^{3}$"
#: Sec. III C: the Hertz entropy at H >= 1.8.
HERTZ_ETA = r"The entropy $\eta(t)$ features a plateau at a value around $\eta\approx 0.5$"
HERTZ_ETA_FINAL = (r"The asymptotic value of $\eta(t)$ approaches the theoretically predicted value of "
                   r"$\langle\eta\rangle$ with $H \geq 1.8$")
BOTH_LOCALIZED_05 = r"The energy distribution for both models is still found to be localized for $H = 0.5$."
#: Sec. III A: both models at H = 0.25 (said once of both).
BOTH_LOCALIZED_025 = (r"the energy density for both models is completely localized around the initially excited "
                      r"site $ n =21 $")
BOTH_REGULAR_025 = r"confirms that the dynamics is regular as $ \Lambda (t) $ follows"
#: Sec. III B 3: FPUT up to H = 1.8, localized and regular in one sentence.
FPUT_LOCALIZED_REGULAR_TO_18 = r"the dynamics of the FPUT model appears to remain localized and regular up to $H=1.8$"
#: Sec. III B 3: FPUT at H = 8.7381, delocalized and chaotic in one sentence.
FPUT_87_FINAL = r"which exhibits a delocalized and chaotic final energy profile"


def _label(scene: str) -> str:
    return model_label(panels.scenes()[scene].model)


def _energy(scene: str) -> str:
    return tex_parameter(panels.scenes()[scene].energy)


def _statement_id(kind: str, scene: str) -> str:
    """The id of a statement of statements.STATEMENTS about ``scene``, e.g. deloc-H1.8-hertz."""
    s = panels.scenes()[scene]
    return f"{kind}-H{tex_parameter(s.energy)}-{s.model}"


def _final_p_of_h025(scene: str) -> ClaimRow:
    """"A constant value of P ~ 1.8" is about the whole run: it needs the paper's t = 1e5, and a
    shorter run whose final P already differs refutes it."""
    return ClaimRow(
        id=f"P-H0.25-{panels.scenes()[scene].model}", where="Fig. 2(c), Sec. III A",
        statement=f"At $H = 0.25$ the {_label(scene)} packet keeps a constant $P \\approx 1.8$", paper="$1.8$",
        measure="final_value", unit="1",
        criterion="final $P$ within ${tol.participation_relative:param%}\\,\\%$ of 1.8", measured="{value:math}",
        checks=(Check("value", "near_relative", 1.8, RELATIVE_P),), scenes=(scene,),
        args={"variable": "participation"},
        variables=("participation",), t_required=T_PAPER, refutable_early=True,
        reason=("the paper plots a LOWESS-smoothed $P$ under an unstated energy density; the mean of the raw "
                "$P$, which oscillates with the mode between about 1.2 and 2.8, is larger"),
        quote=(r"the time evolution of the participation number which gives a constant value of $ P \approx 1.8 $ "
               r"for both models",))


def _chaos(id: str, where: str, scene: str, chaotic: bool, extra: str, quote: tuple,
           statements=None) -> ClaimRow:
    """The orbit of ``scene`` is chaotic (or regular) at the end of the paper's run."""
    state = "chaotic" if chaotic else "regular"
    return ClaimRow(
        id=id, where=where, statement=f"At $H = {_energy(scene)}$ the {_label(scene)} orbit is {state}{extra}",
        paper=state,
        measure="chaos", unit="1", criterion=CHAOS if chaotic else f"not: {CHAOS}", measured=CHAOS_TEXT,
        checks=(Check("chaotic", "==", chaotic),), scenes=(scene,), variables=("mlce",), t_required=T_PAPER,
        refutable_early=not chaotic, statements=statements or (id,), quote=quote)


def _dvd_participation_of_h025(scene: str) -> ClaimRow:
    return ClaimRow(
        id=f"PD-H0.25-{panels.scenes()[scene].model}", where="Fig. 3(e,f), Sec. III A",
        statement=f"At $H = 0.25$ the {_label(scene)} DVD has $P_D \\approx 20$ up to $t \\approx 10^3$",
        paper="$20$",
        measure="window_average", unit="1", criterion="within ${tol.participation_relative:param%}\\,\\%$ of 20",
        measured="mean $P_D$ over $10^2 \\le t \\le 10^3$: {value:math}",
        checks=(Check("value", "near_relative", 20, RELATIVE_P),), scenes=(scene,),
        args={"variable": "dvd_participation", "start": 1e2, "end": 1e3}, variables=("dvd_participation",),
        t_required=1e3, reason="$P_D$ fluctuates strongly from sample to sample; its mean over the decade is lower",
        quote=(r"although up to $t\approx 10^3$ both DVDs exhibit approximately  $P_{\rm D}\approx 20$",))


def _eta_of_h025(scene: str, quote: str) -> ClaimRow:
    return ClaimRow(
        id=f"eta-H0.25-{panels.scenes()[scene].model}", where="Fig. 8(a)/9(a), Sec. III C",
        statement=f"At $H = 0.25$ the {_label(scene)} $\\eta$ stays close to 1", paper="close to 1",
        measure="final_value", unit="1", criterion="final $\\eta \\ge {c.eta_near_one:param}$",
        measured="{value:math}",
        checks=(Check("value", ">=", "eta_near_one"),), scenes=(scene,), args={"variable": "eta"}, variables=("eta",),
        t_required=T_PAPER, refutable_early=True, quote=(quote,))


def _localized(id: str, where: str, scene: str, quote: str) -> ClaimRow:
    """The packet of ``scene`` stays localized to the end of the paper's run."""
    return ClaimRow(
        id=id, where=where, statement=f"At $H = {_energy(scene)}$ the {_label(scene)} packet stays localized",
        paper="localized",
        measure="final_value", unit="1", criterion="final $P \\le {c.localized_p_max:param}$",
        measured="final $P = {value:tex}$",
        checks=(Check("value", "<=", "localized_p_max"),), scenes=(scene,), args={"variable": "participation"},
        variables=("participation",), t_required=T_PAPER, refutable_early=True, statements=(id,), quote=(quote,))


def _delocalized_and_chaotic(id: str, where: str, scene: str, extra: str, quote: str) -> ClaimRow:
    """The packet of ``scene`` spreads and its orbit is chaotic at the end of the paper's run."""
    return ClaimRow(
        id=id, where=where,
        statement=f"At $H = {_energy(scene)}$ the {_label(scene)} packet is delocalized and chaotic{extra}",
        paper="delocalized, chaotic", measure="participation_and_chaos", unit="1",
        criterion=f"final $P \\ge {{c.delocalized_p_min:param}}$ and {CHAOS}",
        measured=f"final $P = {{value:tex}}$, {CHAOS_TEXT}",
        checks=(Check("value", ">=", "delocalized_p_min"), Check("chaotic", "==", True)), scenes=(scene,),
        variables=("participation", "mlce"), t_required=T_PAPER,
        statements=(_statement_id("deloc", scene), _statement_id("chaos", scene)), quote=(quote,))


def _chaos_onset(id: str, where: str, scene: str, statement: str, paper_t: float, paper_tex: str,
                 t_required: float, statement_id: str, quote: str) -> ClaimRow:
    """The orbit of ``scene`` turns chaotic at about ``paper_t``, a time read off a log axis."""
    return ClaimRow(
        id=id, where=where, statement=statement, paper=f"${paper_tex}$", measure="chaos_onset", unit="time",
        criterion="onset of chaos within a factor {tol.time_factor:param} of " + literal(f"${paper_tex}$"),
        measured={"": "chaotic from $t = {value:tex}$ on", "never": "not chaotic at the end"},
        checks=(Check("value", "within_factor", paper_t, "tolerance.time_factor"),), scenes=(scene,),
        variables=("mlce",),
        t_required=t_required, statements=(statement_id,), quote=(quote,))


def _eta_plateau(scene: str, level: float, where: str, quote: str) -> ClaimRow:
    """The eta of ``scene`` has a plateau near ``level``, read off an eta(t) plot."""
    return ClaimRow(
        id=f"eta-plateau-{scene}", where=f"{where}, Sec. III C",
        statement=f"At $H = {_energy(scene)}$ the {_label(scene)} $\\eta$ has a plateau near {tex_parameter(level)}",
        paper=f"${tex_parameter(level)}$", measure="plateau_median", unit="1",
        criterion="$|\\eta_\\mathrm{{plateau}} - {target:param}| \\le {tol.eta_plateau:param}$",
        measured="median $\\eta$ over ${start:param} \\le t \\le {end:param}$: {value:math}",
        checks=(Check("value", "near", level, "tolerance.eta_plateau"),), scenes=(scene,), args={"variable": "eta"},
        target=level,
        variables=("eta",), t_required=f"plateau_end[{scene}]",
        reason=("follows", _statement_id("deloc", scene), "the entropy follows the packet, which stays localized"),
        quote=(quote,))


def _eta_equipartition(scene: str, where: str, quote: str) -> ClaimRow:
    """The eta of ``scene`` ends close to its equipartition value."""
    return ClaimRow(
        id=f"eta-final-{scene}", where=f"{where}, Sec. III C",
        statement=f"At $H = {_energy(scene)}$ the {_label(scene)} $\\eta$ ends close to the equipartition value "
        f"$\\langle\\eta\\rangle$", paper=r"$\approx\langle\eta\rangle$", measure="eta_final", unit="1",
        criterion="$|\\eta_\\mathrm{{final}} - \\langle\\eta\\rangle| \\le {tol.eta_equipartition:param}$",
        measured="final $\\eta = {value:tex}$, $\\langle\\eta\\rangle = {equipartition:tex}$",
        checks=(Check("excess", "near", 0.0, "tolerance.eta_equipartition"),), scenes=(scene,), variables=("eta",),
        t_required=T_PAPER, reason=("follows", _statement_id("deloc", scene),
                                    "a packet that stays localized does not reach equipartition"),
        quote=(quote,))


def _scan_always(id: str, model: str, key: str, H: float, quote: str) -> ClaimRow:
    """"For H > H_paper the packet of ``model`` is always ``key``", a bound, on the energy scan: it
    holds at every scanned energy above H. Below H the sentence says nothing, so the lowest scanned
    energy H* from which it always holds is shown, not compared with H: the threshold lies between
    the highest scanned energy where it fails and H*, and it can lie at or below H exactly when the
    check passes."""
    return ClaimRow(
        id=id, where="Sec. III B, IV",
        statement=f"For $H > {tex_parameter(H)}$ the {model_label(model)} packet is always {key}",
        paper=f"$H > {tex_parameter(H)}$", measure="scan_always", unit="energy",
        criterion="{scan_criterion[" + key + "]} at every scanned $H > {H:param}$ (a bound: the sentence says nothing "
        "below it)",
        measured={"": "{key} at {count} of the {above} scanned $H > {H:param}$; at every scanned $H \\ge H^* = {star:tex}$",
         "nowhere": "{key} at {count} of the {above} scanned $H > {H:param}$; not at the highest"},
        checks=(Check("holds_above", "==", True),),
        scenes=(ENERGY_SCAN,), args={"model": model, "key": key, "H": H},
        variables=("delocalized", "chaotic", "valid"),
        t_required=T_PAPER, reason=("scan_always_reason", model, key, H), quote=(quote,))


CATALOGUE: tuple[ClaimRow, ...] = (
    # ---------------- Fig. 1 and the chosen realization ----------------
    ClaimRow(id="fig1-count", where="Fig. 1(a), Sec. II A",
             statement=r"For $\alpha \ge 4$ about 10 modes are strongly localized",
             paper="about 10", measure="localized_mode_counts", unit="modes",
             criterion="every $\\alpha \\ge 4$ has $10 \\pm {tol.count}$ ranks with "
             "$\\langle P\\rangle \\le {c.localized_mode_p_max:param}$",
             measured="{lowest}--{highest} modes with $\\langle P\\rangle \\le {c.localized_mode_p_max:param}$ "
             "($\\alpha = {alpha_low:param}$--${alpha_high:param}$)",
             checks=(Check("counts", "near", 10, "tolerance.count"),), args={"alpha_min": 4.0},
             quote=(r"for values of $\alpha \geq 4$ the averaged participation number reaches a limiting curve "
                    r"with about $10$ strongly localized modes",)),
    # <P> ~ 2 is read off the curves of Fig. 1(a), as P ~ 26 of rank 1 is, and printed as an integer
    ClaimRow(id="fig1-level", where="Fig. 1(a), Sec. II A",
             statement=r"Those modes have $\langle P\rangle \approx 2$", paper="$2$",
             measure="localized_levels", unit="1",
             criterion="within ${tol.participation_relative:param%}\\,\\%$ of 2 for every "
             "$\\alpha \\ge 4$",
             measured="${lowest:tex}$--${highest:tex}$ (mean of the {c.n_localized_modes} most localized ranks); chosen "
             "chain, period-averaged: {period_averaged:math}",
             checks=(Check("levels", "near_relative", 2.0, RELATIVE_P),), args={"alpha_min": 4.0},
             reason=("convention: with the potential energy density of a mode (docs/conventions.md, Mode energy "
                     "density) no bead holds more than half of an interior mode's energy, so $P \\ge 2$, and a "
                     "mode on one bead has $2 \\le P \\le 8/3$, with $P$ near 2 only when one of its two bonds "
                     "carries almost all of its energy. The paper does not define its energy density of a mode."),
             quote=(r"with about $10$ strongly localized modes with  $\langle P \rangle \approx 2$",)),
    ClaimRow(id="fig1-limit", where="Fig. 1(a), Sec. II A",
             statement=r"For $\alpha \ge 4$ the curve $\langle P\rangle(k)$ reaches a limiting curve",
             paper="limiting curve",
             measure="limiting_curve", unit="1", criterion="spread $\\le {tol.limiting_curve_relative:param%}\\,\\%$",
             measured="largest rank-wise spread of the $\\alpha \\ge 4$ curves: {value:math%2}\\,\\%",
             checks=(Check("value", "<=", "tolerance.limiting_curve_relative"),), args={"alpha_min": 4.0},
             quote=(r"for values of $\alpha \geq 4$ the averaged participation number reaches a limiting curve",)),
    ClaimRow(id="fig1-extended", where="Sec. III B, Fig. 1(a)",
             statement=r"The most extended mode of a disordered chain has $P \approx 26$", paper="$26$",
             measure="most_extended_mode", unit="1",
             criterion="within ${tol.participation_relative:param%}\\,\\%$ of 26",
             measured="rank-1 $\\langle P\\rangle = {value:tex}$ ($\\alpha = {alpha:param}$); chosen chain's most extended "
             "mode {chain_largest:math}",
             checks=(Check("value", "near_relative", 26.0, RELATIVE_P),),
             quote=(r"saturates to a value  $ P \approx 26 $.",
                    r"it also corresponds to the participation number of the most extended mode of a disordered "
                    r"lattice")),
    ClaimRow(id="mode34-P", where="Fig. 1(b), Sec. II A",
             statement=r"Mode 34 of the chosen chain is strongly localized, $P \approx 2.5$",
             paper="$2.5$", measure="mode_participation", unit="1",
             criterion="$|P - 2.5| \\le {tol.mode_participation:param}$ (potential convention)",
             measured="{value:math} (potential); {period_averaged:math} (period-averaged)",
             checks=(Check("value", "near", 2.5, "tolerance.mode_participation"),), args={"mode": 34},
             reason=("convention: the paper's realization and its energy density of a mode are unpublished; under "
                     "the potential convention (docs/conventions.md, Mode energy density) a mode whose neighbours "
                     "move has $P \\gtrsim 8/3$, and the selection window is $2.2 \\le P \\le 2.8$; the "
                     "period-averaged convention gives the other value shown"),
             quote=(r"we identify the $ 34^{th} $ mode of this chain as a strongly localized  mode "
                    r"($P \approx 2.5$)",)),
    ClaimRow(id="mode34-site", where="Fig. 1(b), Sec. II A", statement=r"Mode 34 is centred on site $n = 21$",
             paper="$21$", measure="mode_peak", unit="site",
             criterion="the mode's energy maximum is on site 21 (a selection requirement, docs/conventions.md, Realization)",
             measured="energy maximum at site ${value}$", checks=(Check("value", "==", 21),), args={"mode": 34},
             quote=(r"around the middle of the chain and in particular at site $n=21$",)),
    ClaimRow(id="overlaps", where="Sec. III A",
             statement=r"The static overlaps next to site 21 are $\delta_{21,22} \approx 1.06$",
             paper="$1.06$", measure="excited_overlaps", unit="length unit",
             criterion="both within ${tol.displacement:param}$ of 1.06 (the selection prefers them near 1.06)",
             measured="$\\delta_{{21}} = {left:tex}$, $\\delta_{{22}} = {right:tex}$",
             checks=(Check("overlaps", "near", 1.06, "tolerance.displacement"),), args={"around": 1.06},
             quote=(r"with the neighboring static overlaps being $\delta_{21,22}\approx 1.06$",)),
    ClaimRow(id="u0", where="Sec. III A",
             statement=r"At $H = 0.25$ the Hertz initial displacement is $u_{21}(0) = 1.01$",
             paper="$1.01$", measure="initial_displacement", unit="length unit",
             criterion="$|u_{{21}}(0) - 1.01| \\le {tol.displacement:param}$", measured="{value:math4}",
             checks=(Check("value", "near", 1.01, "tolerance.displacement"),), scenes=(HZ25,),
             reason=("units: in these units $u_{21}(0)$ depends only on the two overlaps next to bead 21, and "
                     "overlaps of 1.06 give $u_{21}(0) \\approx 1.04$; 1.01 would need overlaps near 1.0 "
                     "(docs/conventions.md, Units). The units are not tuned to hide this"),
             quote=(r"this energy corresponds for the Hertzian model to a initial displacement of $u_{21}(0)=1.01$",
                    )),

    # ---------------- H = 0.25 ----------------
    *(_final_p_of_h025(scene) for scene in (HZ25, FP25)),
    # about the whole run, as "a constant value" above
    ClaimRow(id="P-H0.25-overlap", where="Fig. 2(c), Sec. III A",
             statement=r"At $H = 0.25$ the $P(t)$ curves of the two models almost overlap", paper="overlap",
             measure="relative_difference", unit="1",
             criterion="relative difference $\\le {tol.participation_relative:param%}\\,\\%$",
             measured="final $P$: Hertz {first:math}, FPUT {second:math}",
             checks=(Check("value", "<=", RELATIVE_P),), scenes=(HZ25, FP25), args={"variable": "participation"},
             variables=("participation",), t_required=T_PAPER, refutable_early=True,
             quote=(r"The curves of the Hertzian (red curve) and the FPUT (blue curve) models almost overlap.",)),
    *(_chaos(f"regular-H0.25-{panels.scenes()[scene].model}", "Fig. 2(d), Sec. III A", scene, False,
             ", $\\Lambda \\propto t^{-1}$",
             (r"confirms that the dynamics is regular as $ \Lambda (t) $ follows the power law "
              r"$\Lambda(t)\propto t^{-1}$",)) for scene in (HZ25, FP25)),
    *(_dvd_participation_of_h025(scene) for scene in (HZ25, FP25)),
    ClaimRow(id="PD-H0.25-drop", where="Fig. 3(e,f), Sec. III A",
             statement=r"After $t \approx 10^3$ the Hertz $P_D$ drops, the FPUT one does not",
             paper="drop (Hertz only)",
             measure="early_and_late", unit="1",
             criterion="Hertz ratio $< 1 - {tol.participation_relative:param}$ and FPUT ratio $\\ge$ that",
             measured="final/early $P_D$: Hertz {first:math2}, FPUT {second:math2}",
             checks=(Check("first", "<", f"1 - {RELATIVE_P}"), Check("second", ">=", f"1 - {RELATIVE_P}")),
             scenes=(HZ25, FP25), args={"variable": "dvd_participation", "start": 1e2, "end": 1e3},
             variables=("dvd_participation",), t_required=T_PAPER,
             quote=(r"although up to $t\approx 10^3$ both DVDs exhibit approximately  $P_{\rm D}\approx 20$, for "
                    r"the case of the Hertzian chain [panel  (e)] it starts to drop to a smaller value",)),
    _eta_of_h025(HZ25, r"the normalized entropy initially has a value of $\eta=1$ and only slightly decreases from "
                       r"that value"),
    _eta_of_h025(FP25, r"$\eta(t)$ saturates to a finite value close to 1"),

    # ---------------- H = 0.5 ----------------
    _localized("loc-H0.5-hertz", "Fig. 4(a,c), Sec. III B", HZ05, BOTH_LOCALIZED_05),
    _chaos("chaos-H0.5-hertz", "Fig. 4(d), Sec. III B", HZ05, True, " (localized chaos, in the last decade)",
           (r"deviates from the $ \Lambda (t) \propto t^{-1}$ curve, at the last decade, and attains an almost "
            r"constant value. This signals that the system is chaotic.",),
           statements=("chaos-H0.5-hertz", "chaos-late-H0.5-hertz")),
    _localized("loc-H0.5-fput", "Fig. 4(c), Sec. III B", FP05, BOTH_LOCALIZED_05),
    _chaos("regular-H0.5-fput", "Fig. 4(d), Sec. III B", FP05, False, "",
           (r"In contrast, for the same energy the FPUT model's orbit remains regular",)),
    ClaimRow(id="dvd-H0.5-site21", where="Fig. 5(a,b), Sec. III B",
             statement=r"At $H = 0.5$ the Hertz DVD stays attached to site 21 in the last decade", paper="site 21",
             measure="dvd_at_site", unit="1",
             criterion="fraction $\\ge {c.dvd_site_fraction:param%}\\,\\%$",
             measured="DVD maximum within {c.dvd_site_halfwidth} site of 21 in {value:math%2}\\,\\% of the final samples",
             checks=(Check("value", ">=", "dvd_site_fraction"),), scenes=(HZ05,), variables=("dvd",),
             t_required=T_PAPER,
             quote=(r"Finally for the rest of the simulation the profile of the DVD is strongly localized around "
                    r"site $n=21$ as also confirmed by two different profiles during the last decade",)),
    ClaimRow(id="gaps-H0.5-one", where="Fig. 7(a,c), Sec. III C",
             statement=r"At $H = 0.5$ at most one gap is open at any instant",
             paper=r"$\le 1$", measure="max_gaps", unit="gaps",
             criterion="largest number of simultaneously open gaps $\\le 1$",
             measured="at most {value} open at once (checked every step)", checks=(Check("value", "<=", 1),),
             scenes=(HZ05,),
             variables=("n_gaps",), t_required=T_PAPER, refutable_early=True,
             reason=("follows", "loc-H0.5-hertz", "the gaps follow the packet, which spreads on this chain"),
             quote=(r"At this energy no more than one gap is open at any instant",)),
    # "on the left and right side": both bonds of bead 21 open, bond 21 (beads 20, 21) and bond 22
    # (beads 21, 22); "only": at H = 1.8, by contrast, gaps start "moving" away from site 21 (the same
    # section). "Often" gives no number: the fraction of the run each was open is shown, not checked.
    ClaimRow(id="gaps-H0.5-site21", where="Fig. 7(a), Sec. III C",
             statement=r"At $H = 0.5$ gaps open on the left and on the right of site 21, and nowhere else",
             paper="bonds 21, 22", measure="gaps_beside_site", unit="bonds",
             criterion="both bonds of bead 21 open at some time, bond 21 (beads 20, 21) and bond 22 (beads 21, 22), "
             "and no other bond opens",
             measured="bonds ever open: {bonds:bonds}; bond {left_bond} open {left_time:math%2}\\,\\% of the run, "
             "bond {right_bond} {right_time:math%2}\\,\\%",
             checks=(Check("left", "==", True), Check("right", "==", True), Check("distances", "==", 0)),
             scenes=(HZ05,),
             variables=("gap_fraction",), t_required=T_PAPER, refutable_early=True,
             reason=("follows", "loc-H0.5-hertz", "the gaps follow the packet, which spreads on this chain"),
             quote=(r"on the left and right side of site $n=21$ a gap often opens during the system's evolution",
                    r"For  the energy $H=1.8$ shown in  Fig.~\ref{gaps}(b), we find that more gaps start to "
                    r"open``moving'' away from site $n=21$")),

    # ---------------- H = 1.8 ----------------
    # the window ends at plateau_end = 2e2 / time_factor: before the earliest onset spread-H1.8-onset accepts
    ClaimRow(id="spread-H1.8-level", where="Fig. 4(b,c), Sec. III B",
             statement=r"At $H = 1.8$ the Hertz packet is first localized with $P < 3$", paper=r"$< 3$",
             measure="plateau_largest", unit="1",
             criterion="smoothed $P < {c.spreading_p_threshold:param}$ at every sample of that window (before the paper's onset)",
             measured="largest smoothed $P$ over ${start:param} \\le t \\le {end:param}$: {value:math}",
             checks=(Check("value", "<", "spreading_p_threshold"),), scenes=(HZ18,),
             args={"variable": "participation"},
             variables=("participation",), t_required=f"plateau_end[{HZ18}]",
             statements=("spread-level-H1.8-hertz",),
             reason=("the packet's early participation number is larger than the paper's; the paper's energy "
                     "density and smoothing are not stated (see the $H = 0.25$ claims)"),
             quote=(HERTZ_18_LOCALIZED, r"with a participation  number $P<3$")),
    # Sec. III C puts this onset at t ~ 3e2 (gaps-H1.8-spread): within the time factor of 2e2 too
    ClaimRow(id="spread-H1.8-onset", where="Fig. 4(b,c), Sec. III B",
             statement=r"At $H = 1.8$ the Hertz packet starts to spread at $t \approx 2\times 10^2$",
             paper=r"$2\times 10^{2}$",
             measure="spreading_onset", unit="time",
             criterion="onset within a factor {tol.time_factor:param} of $2\\times 10^2$",
             measured={"": "smoothed $P$ stays above {c.spreading_factor:param} times its value at "
                  "$t = {c.plateau_start:param}$ at $t = {value:tex}$",
              "never": "the smoothed $P$ never doubles"},
             checks=(Check("value", "within_factor", 2e2, "tolerance.time_factor"),), scenes=(HZ18,),
             variables=("participation",), t_required="2e2 * tolerance.time_factor", refutable_early=True,
             statements=("spread-onset-H1.8-hertz",), quote=(HERTZ_18_LOCALIZED, r"it then rapidly spreads")),
    ClaimRow(id="spread-H1.8-saturation", where="Fig. 4(c), Sec. III B",
             statement=r"At $H = 1.8$ the Hertz $P$ saturates near 26",
             paper="$26$", measure="final_value", unit="1",
             criterion="within ${tol.participation_relative:param%}\\,\\%$ of 26",
             measured="final $P = {value:tex}$", checks=(Check("value", "near_relative", 26, RELATIVE_P),),
             scenes=(HZ18,),
             args={"variable": "participation"}, variables=("participation",), t_required=4e4,
             reason=("spread_of_values", "deloc-H1.8-hertz", "the final $P$"),
             quote=(r"when eventually the participation number saturates to a value  $ P \approx 26 $",)),
    ClaimRow(id="spread-H1.8-until", where="Fig. 4(c), Sec. III B",
             statement=r"At $H = 1.8$ the spreading goes on until $t \approx 4\times 10^3$",
             paper=r"$4\times 10^{3}$",
             measure="saturation_time", unit="time",
             criterion="within a factor {tol.time_factor:param} of $4\\times 10^3$",
             measured="smoothed $P$ reaches {c.saturation_fraction:param%}\\,\\% of its final value at $t = {value:tex}$",
             checks=(Check("value", "within_factor", 4e3, "tolerance.time_factor"),), scenes=(HZ18,),
             variables=("participation",), t_required=4e4, statements=("spread-until-H1.8-hertz",),
             quote=(HERTZ_18_SPREADS,)),
    ClaimRow(id="mlce-H1.8", where="Fig. 4(d), Sec. III B",
             statement=r"At $H = 1.8$ the Hertz $\Lambda$ levels off at $\Lambda \approx 10^{-3}$",
             paper=r"$10^{-3}$",
             measure="final_mlce", unit="1/time", criterion="within a factor {tol.mlce_factor:param} of $10^{{-3}}$",
             measured="$\\Lambda(t_\\mathrm{{end}}) = {value:tex}$",
             checks=(Check("value", "within_factor", 1e-3, "tolerance.mlce_factor"),), scenes=(HZ18,),
             variables=("mlce",),
             t_required=1e4, statements=("mlce-H1.8-hertz",),
             quote=(r"acquiring an almost constant positive value of $ \Lambda (t) \approx 10^{-3} $",)),
    _chaos_onset("chaos-H1.8-onset", "Fig. 4(d), Sec. III B", HZ18,
                 r"At $H = 1.8$ the Hertz orbit is chaotic from $t \approx 2\times 10^2$ on",
                 2e2, r"2\times 10^{2}", 2e3, "chaos-onset-H1.8-hertz",
                 r"the system becomes  chaotic as early as $t\approx 2\times 10^2$"),
    ClaimRow(id="gaps-H1.8-spread", where="Fig. 7(b), Sec. III C",
             statement=r"At $H = 1.8$ gaps leave site 21 at $t \approx 3\times 10^2$, when $P$ starts to grow",
             paper=r"$3\times 10^{2}$", measure="gap_spread", unit="time",
             criterion="within a factor {tol.time_factor:param} of $3\\times 10^2$",
             measured={"": "first gap {c.gap_spread_distance} or more bonds from bead 21 by $t = {value:tex}$",
              "with_onset": "first gap {c.gap_spread_distance} or more bonds from bead 21 by $t = {value:tex}$; "
                            "spreading onset $t = {onset:tex}$",
              "never": "no gap leaves bead 21"},
             checks=(Check("value", "within_factor", 3e2, "tolerance.time_factor"),), scenes=(HZ18,),
             variables=("gap_fraction",), t_required="3e2 * tolerance.time_factor", refutable_early=True,
             quote=(r"the wave-packet starts to delocalize (as quantified by $ P $) at the same time that additional "
                    r"gaps start to move away from site  $n=21$",
                    r"this happens around $t\approx 3\times10^2$ which is the same time that $P$")),
    # "the whole lattice": every bond of the chain, 1 to N+1. The wall bonds 1 and N+1 count: with the
    # paper's fixed ends (dummy beads u_0 = u_{N+1} = 0) its gap condition u_n - u_{n-1} > delta_n
    # (the caption of Fig. 7) is defined at them as at any other bond, its Hamiltonian carries both, and
    # Fig. 7(b) as drawn here shows bonds 1 to N+1. No tolerance: a bond that never opens breaks "whole".
    ClaimRow(id="gaps-H1.8-cover", where="Fig. 7(b), Sec. III C",
             statement=r"At $H = 1.8$ gaps eventually cover the whole lattice",
             paper="whole lattice", measure="bond_coverage", unit="1",
             criterion="every bond, 1 to $N+1$ (the two wall bonds included), opens at some time",
             measured="{value:math%2}\\,\\% of the {bonds} bonds have opened; never open: {never_bonds:bonds}",
             checks=(Check("never", "==", 0),), scenes=(HZ18,),
             variables=("gap_fraction",), t_required=T_PAPER,
             quote=(r"more gaps start to open``moving'' away from site $n=21$, covering eventually the whole "
                    r"lattice",)),

    # ---------------- FPUT: regular up to 1.8, then alternation ----------------
    ClaimRow(id="fput-regular-to-1.8", where="Fig. 4(c,d), Sec. III B",
             statement=r"The FPUT packet stays localized and regular up to $H = 1.8$", paper="localized, regular",
             measure="localized_and_regular", unit="1",
             criterion="final $P \\le {c.localized_p_max:param}$ and regular at $H = 0.25, 0.5, 1.8$",
             measured="{states:states}",
             checks=(Check("P", "<=", "localized_p_max"), Check("chaotic", "==", False)), scenes=(FP25, FP05, FP18),
             variables=("participation", "mlce"), t_required=T_PAPER, refutable_early=True,
             statements=tuple(_statement_id(kind, scene) for scene in (FP25, FP05, FP18)
                              for kind in ("loc", "regular")),
             quote=(FPUT_LOCALIZED_REGULAR_TO_18,)),
    _delocalized_and_chaotic("fput-H2.9", "Fig. 6(a--d), Sec. III B", FP29, " (the first such energy)", FPUT_FIRST),
    # "t >~ 4e3" gives where Lambda leaves the t^-1 line (regular before it): an onset, not a bound
    _chaos_onset("chaos-H2.9-onset", "Fig. 6(d), Sec. III B", FP29,
                 r"At $H = 2.9$ the FPUT orbit is chaotic for $t \gtrsim 4\times 10^3$",
                 4e3, r"4\times 10^{3}", 4e4, "chaos-onset-H2.9-fput",
                 r"significantly deviates from the  $ \Lambda (t) \propto t^{-1}$ line, indicating chaotic dynamics "
                 r"for $t \gtrsim 4\times 10^3$"),
    _localized("loc-H4-fput", "Fig. 6(e,f), Sec. III B", FP4,
               r"In this case the wave-packet remains well localized and the participation number hardly changes"),
    _chaos("chaos-H4-fput", "Sec. III B", FP4, True, " (FPUT is chaotic for all $H > 2.8$)", (FPUT_ALWAYS_CHAOTIC,)),
    _delocalized_and_chaotic("fput-H8.7381", "Fig. 6(i--l), Sec. III B", FP87, "",
                             r"another example for $H=8.7381$ in the bottom row of Fig.~\ref{dynms29} which exhibits "
                             r"a delocalized and chaotic final energy profile"),

    # ---------------- entropy ----------------
    _eta_plateau(HZ18, 0.5, "Fig. 8(c)", HERTZ_ETA),
    _eta_plateau(HZ3, 0.5, "Fig. 8(d)", HERTZ_ETA),
    _eta_plateau(FP29, 0.7, "Fig. 9(b)", r"the entropy exhibits a plateau at  $\eta\approx 0.7$"),
    _eta_plateau(FP4, 0.82, "Fig. 9(c)", r"the entropy saturates for most of the evolution around a relatively large "
                                         r"value $\eta\approx 0.82$"),
    _eta_plateau(FP87, 0.8, "Fig. 9(d)", r"the entropy saturates for a long time interval at a value "
                                         r"$\eta\approx 0.8$"),
    _eta_equipartition(HZ18, "Fig. 8(c)", HERTZ_ETA_FINAL),
    _eta_equipartition(HZ3, "Fig. 8(d)", HERTZ_ETA_FINAL),
    _eta_equipartition(FP29, "Fig. 9(b)", r"finally reaches a minimum value which is found to be close to the "
                                          r"analytical result for equipartition"),
    _eta_equipartition(FP87, "Fig. 9(d)",
                       r"at the end of the simulation reaches a minimal value well captured by the "
                                          r"analytical prediction"),
    # not at equipartition: the complement of "close to <eta>" of the rows above, with their tolerance
    ClaimRow(id="eta-final-fput_H4", where="Fig. 9(c,g), Sec. III C",
             statement=r"At $H = 4$ the FPUT $\eta$ has not reached equipartition at the end",
             paper=r"$>\langle\eta\rangle$",
             measure="eta_final", unit="1",
             criterion="$\\eta_\\mathrm{{final}} - \\langle\\eta\\rangle > {tol.eta_equipartition:param}$",
             measured="final $\\eta = {value:tex}$, $\\langle\\eta\\rangle = {equipartition:tex}$",
             checks=(Check("excess", ">", "tolerance.eta_equipartition"),), scenes=(FP4,), variables=("eta",),
             t_required=T_PAPER,
             refutable_early=True,
             reason=("follows", "loc-H4-fput", "a packet that spreads approaches equipartition"),
             quote=(r"not all modes have been excited at the end of the simulation",
                    r"it is expected,  that for larger timescales the system will reach equipartition, and $\eta$ "
                    r"will eventually drop")),

    # ---------------- thresholds of Sec. III and IV, on the energy scan ----------------
    _scan_always("scan-hertz-deloc", "hertz", "delocalized", 1.8, HERTZ_ALWAYS),
    _scan_always("scan-hertz-chaos", "hertz", "chaotic", 1.8, HERTZ_ALWAYS),
    # a range whose ends are the paper's runs: the packet stays localized at 0.25 (Sec. III A) and
    # is delocalized at 1.8, so delocalization sets in within (0.25, 1.8]
    ClaimRow(id="scan-hertz-onset", where="Sec. III C",
             statement=r"The Hertz packet starts to delocalize in the energy region $0.5 \lesssim H \lesssim 1.8$",
             paper=r"$0.5 \lesssim H \lesssim 1.8$", measure="scan_onset", unit="energy",
             criterion="the lowest scanned $H$ with {scan_criterion[delocalized]} lies above 0.25 (the paper's energy "
             "below the region, where the packet stays localized) and the scanned $H$ below it is at most 1.8",
             measured={"": "first delocalized at $H = {first:tex}$, not at the scanned $H = {before:tex}$ below it",
              "lowest": "delocalized from the lowest scanned $H = {first:tex}$ on",
              "never": "never delocalized"},
             checks=(Check("first", ">", 0.25), Check("before", "<=", 1.8)), scenes=(ENERGY_SCAN,),
             args={"model": "hertz", "key": "delocalized", "high": 1.8},
             variables=("delocalized", "chaotic", "valid"),
             t_required=T_PAPER,
             reason="on this chain delocalization sets in outside the paper's region (the energies measured)",
             quote=(r"for the energy region $0.5\lesssim H \lesssim1.8$ the wave-packet starts to delocalize (as "
                    r"quantified by $ P $)",)),
    _scan_always("scan-fput-chaos", "fput", "chaotic", 2.8, FPUT_ALWAYS_CHAOTIC),
    ClaimRow(id="scan-fput-alternation", where="Sec. III B, IV",
             statement=r"The FPUT packet first delocalizes around $H = 2.9$; above it, it alternates between localized and "
             r"delocalized states",
             paper=r"first around $H = 2.9$", measure="scan_alternation", unit="energy",
             criterion="the lowest scanned $H$ with {scan_criterion[delocalized]} lies within a factor "
             "{tol.threshold_factor:param} of 2.9, and above it the state changes at least twice (delocalized, "
             "localized, delocalized)",
             measured={"": "first delocalized at $H = {first:tex}$; above it localized at $H = $ {localized:energies} "
                  "({switches} changes)",
              "never": "never delocalized"},
             checks=(Check("first", "within_factor", 2.9, "tolerance.threshold_factor"), Check("switches", ">=", 2)),
             scenes=(ENERGY_SCAN,), args={"model": "fput"}, variables=("delocalized", "chaotic", "valid"),
             t_required=T_PAPER,
             reason=("scan_alternation_reason", "fput", 2.9),
             quote=(FPUT_FIRST,
                    r"instead of an energy threshold above which all initial excitations lead to delocalization of "
                    r"the wave-packet, we observe alternations between localized and extended final states")),
)

#: The paper's words each statement of ``statements.STATEMENTS`` encodes (the statement rows quote
#: them; the rows of CATALOGUE that rest on a statement quote their own).
STATEMENT_QUOTES: dict[str, tuple[str, ...]] = {
    "loc-H0.25-hertz": (BOTH_LOCALIZED_025,),
    "regular-H0.25-hertz": (BOTH_REGULAR_025,),
    "loc-H0.5-hertz": (BOTH_LOCALIZED_05,),
    "chaos-H0.5-hertz": (r"This signals that the system is chaotic.",),
    "chaos-late-H0.5-hertz": (r"deviates from the $ \Lambda (t) \propto t^{-1}$ curve, at the last decade",),
    "spread-level-H1.8-hertz": (HERTZ_18_LOCALIZED, r"with a participation  number $P<3$"),
    "spread-onset-H1.8-hertz": (HERTZ_18_LOCALIZED, r"it then rapidly spreads"),
    "deloc-H1.8-hertz": (r"the initially localized wave-packet gradually spreads throughout the lattice",),
    "chaos-H1.8-hertz": (r"for this energy the chaoticity of the system is extended featuring strongly chaotic spots "
                         r"throughout the whole lattice",),
    "chaos-onset-H1.8-hertz": (r"the system becomes  chaotic as early as $t\approx 2\times 10^2$",),
    "spread-until-H1.8-hertz": (HERTZ_18_SPREADS,),
    "mlce-H1.8-hertz": (r"acquiring an almost constant positive value of $ \Lambda (t) \approx 10^{-3} $",),
    "deloc-H3-hertz": (HERTZ_ALWAYS,
                       r"at the last decade all modes appear to participate in the dynamics"),
    "chaos-H3-hertz": (HERTZ_ALWAYS,),
    "loc-H0.25-fput": (BOTH_LOCALIZED_025,),
    "regular-H0.25-fput": (BOTH_REGULAR_025,),
    "loc-H0.5-fput": (BOTH_LOCALIZED_05,),
    "regular-H0.5-fput": (r"In contrast, for the same energy the FPUT model's orbit remains regular",),
    "loc-H1.8-fput": (FPUT_LOCALIZED_REGULAR_TO_18,),
    "regular-H1.8-fput": (FPUT_LOCALIZED_REGULAR_TO_18,),
    "deloc-H2.9-fput": (FPUT_FIRST, r"appears to spread during the last decade of the simulation"),
    "chaos-H2.9-fput": (FPUT_FIRST,),
    "chaos-onset-H2.9-fput": (r"indicating chaotic dynamics for $t \gtrsim 4\times 10^3$",),
    "loc-H4-fput": (r"In this case the wave-packet remains well localized and the participation number hardly "
                    r"changes",),
    "chaos-H4-fput": (FPUT_ALWAYS_CHAOTIC,),
    "eta-H4-fput": (r"the entropy saturates for most of the evolution around a relatively large value "
                    r"$\eta\approx 0.82$",),
    "deloc-H8.7381-fput": (FPUT_87_FINAL,),
    "chaos-H8.7381-fput": (FPUT_87_FINAL,),
}


def statement_rows(catalogue=CATALOGUE) -> tuple[ClaimRow, ...]:
    """A row for every statement of ``statements.STATEMENTS`` that no row of ``catalogue`` rests on,
    decided on its scene's ensemble verdicts alone (measured: the ensemble's median value).

    Parameters
    ----------
    catalogue : sequence of ClaimRow, default CATALOGUE
        The claims' rows; a statement one of them rests on (``ClaimRow.statements``) gets no row.

    Returns
    -------
    tuple of ClaimRow
        One row per remaining statement, id ``stmt-<statement id>``, in table order.
    """
    used = {i for row in catalogue for i in row.statements}
    rows = []
    for st in statements.STATEMENTS:
        if st.id in used:
            continue
        _, _, required, unit, criterion = _verdicts.STATEMENT_KINDS[st.kind]
        yes_no = st.kind in ("chaotic", "regular", "regular_until")
        rows.append(ClaimRow(
            id=f"stmt-{st.id}", where="Sec. III", statement=st.text, paper=st.kind.replace("_", " "),
            measure="ensemble_statement", unit=unit,
            criterion=literal(criterion),
            measured="chaotic in {chaotic} of {orbits} orbits" if yes_no else "median over the ensemble: {median:math}",
            scenes=(st.scene.name,), args={"statement": st.id}, t_required=required(st), statements=(st.id,),
            quote=STATEMENT_QUOTES[st.id]))
    return tuple(rows)


STATEMENT_ROWS = statement_rows()
