"""The paper's qualitative statements about its scenes, as data.

What a realization must show to tell the paper's story. Each is decided per orbit by
``verdicts.STATEMENT_KINDS[kind]`` with the thresholds of the config block ``verdicts:``;
``value`` is the paper's number where it gives one (a time, a level), ``until`` the end of the
window a statement is about. ``early``: a run shorter than the paper's can already break it (a
packet that has spread is not localized at the end; an orbit already chaotic is not regular),
which the realization search uses to discard chains cheaply.
"""

import re
from dataclasses import dataclass

from chainchaos.paper.panels import FP, HZ, PANELS, Scene, panels_of_figure
from chainchaos.system.models import model_label


@dataclass(frozen=True, kw_only=True)
class Statement:
    """A qualitative statement of the paper about one scene: an entry of ``STATEMENTS``.

    Parameters
    ----------
    id : str
        Its identifier, e.g. ``"chaos-H1.8-hertz"``.
    scene : Scene
        The scene it is about.
    kind : str
        How it is decided, a key of ``verdicts.STATEMENT_KINDS`` (``"localized"``, ``"chaotic"``,
        ``"mlce_near"``, ...).
    text : str
        What the paper says, ending with the figure it cites, "(Fig. 4)" or "(Fig. 4d)".
    value : float, optional
        The paper's number where it gives one: a time (the model's time unit), a level of P, an
        mLCE (units of 1 / the time unit) or eta.
    until : float, optional
        The end of the time window the statement is about (the model's time unit).
    early : bool, optional
        Whether a run shorter than the paper's can already break it (default False).
    """

    id: str
    scene: Scene
    kind: str
    text: str
    value: float | None = None
    until: float | None = None
    early: bool = False


def _pair(scene: Scene, localized: bool, chaotic: bool, where: str) -> tuple[Statement, ...]:
    label = model_label(scene.model)
    tag = f"H{scene.energy:g}-{scene.model}"
    return (
        Statement(id=f"{'loc' if localized else 'deloc'}-{tag}", scene=scene,
                  kind="localized" if localized else "delocalized",
                  text=f"{label} $H = {scene.energy:g}$: {'localized' if localized else 'delocalized'} at the end "
                       f"({where})",
                  early=localized),
        Statement(id=f"{'chaos' if chaotic else 'regular'}-{tag}", scene=scene,
                  kind="chaotic" if chaotic else "regular",
                  text=f"{label} $H = {scene.energy:g}$: {'chaotic' if chaotic else 'regular'} ({where})",
                  early=not chaotic),
    )


STATEMENTS: tuple[Statement, ...] = (
    *_pair(HZ[0.25], True, False, "Fig. 2"),
    *_pair(HZ[0.5], True, True, "Fig. 4"),
    Statement(id="chaos-late-H0.5-hertz", scene=HZ[0.5], kind="regular_until",
              text="Hertz $H = 0.5$: chaotic only in the last decade, regular up to $t = 10^4$ (Fig. 4d)",
              until=1e4, early=True),
    Statement(id="spread-level-H1.8-hertz", scene=HZ[1.8], kind="participation_below_until",
              text="Hertz $H = 1.8$: $P < 3$ up to $t \\approx 2\\times 10^2$ (Fig. 4c)", value=3.0, until=2e2,
              early=True),
    Statement(id="spread-onset-H1.8-hertz", scene=HZ[1.8], kind="spreading_onset_near",
              text="Hertz $H = 1.8$: $P$ starts to grow at $t \\approx 2\\times 10^2$ (Fig. 4c)", value=2e2),
    *_pair(HZ[1.8], False, True, "Fig. 4"),
    Statement(id="chaos-onset-H1.8-hertz", scene=HZ[1.8], kind="chaos_onset_near",
              text="Hertz $H = 1.8$: chaotic from $t \\approx 2\\times 10^2$ (Fig. 4d)", value=2e2),
    Statement(id="spread-until-H1.8-hertz", scene=HZ[1.8], kind="saturation_near",
              text="Hertz $H = 1.8$: $P$ grows until $t \\approx 4\\times 10^3$ (Fig. 4c)", value=4e3),
    Statement(id="mlce-H1.8-hertz", scene=HZ[1.8], kind="mlce_near",
              text="Hertz $H = 1.8$: $\\Lambda$ levels off near $10^{-3}$ (Fig. 4d)", value=1e-3),
    *_pair(HZ[3.0], False, True, "Fig. 8"),
    *_pair(FP[0.25], True, False, "Fig. 2"),
    *_pair(FP[0.5], True, False, "Fig. 4"),
    *_pair(FP[1.8], True, False, "Fig. 4"),
    *_pair(FP[2.9], False, True, "Fig. 6"),
    Statement(id="chaos-onset-H2.9-fput", scene=FP[2.9], kind="chaos_onset_near",
              text="FPUT $H = 2.9$: chaotic from $t \\approx 4\\times 10^3$ (Fig. 6d)", value=4e3),
    *_pair(FP[4.0], True, True, "Fig. 6"),
    Statement(id="eta-H4-fput", scene=FP[4.0], kind="eta_near",
              text="FPUT $H = 4$: $\\eta \\approx 0.82$ for most of the run (Fig. 9c)", value=0.82),
    *_pair(FP[8.7381], False, True, "Fig. 6"),
)


def statements_of_scene(scene_name: str) -> list[Statement]:
    """The statements about one scene.

    Parameters
    ----------
    scene_name : str
        A scene's name (``Scene.name``).

    Returns
    -------
    list of Statement
        Its statements, in table order (empty for a scene no statement is about).
    """
    return [s for s in STATEMENTS if s.scene.name == scene_name]


def statement_scenes() -> dict[str, Scene]:
    """The scenes the statements are about, by name, in table order.

    Returns
    -------
    dict of str to Scene
        The scenes by ``Scene.name``.
    """
    return {s.scene.name: s.scene for s in STATEMENTS}


def statement_scenes_by_model() -> dict[str, list[str]]:
    """The names of :func:`statement_scenes` by model, in table order: the scenes whose ensembles
    one verdict job integrates together (any mix of a model's orbits shares a batch).

    Returns
    -------
    dict of str to list of str
        By model name, its scenes' names.
    """
    groups: dict[str, list[str]] = {}
    for name, scene in statement_scenes().items():
        groups.setdefault(scene.model, []).append(name)
    return groups


# Which kinds of panel show what a statement of each kind is about.
STATEMENT_PANEL_KINDS = {
    "localized": ("energy_map", "participation", "participation_with_dvd"),
    "delocalized": ("energy_map", "participation", "participation_with_dvd"),
    "participation_below_until": ("participation", "participation_with_dvd"),
    "spreading_onset_near": ("participation", "participation_with_dvd"),
    "saturation_near": ("participation", "participation_with_dvd"),
    "chaotic": ("mlce",),
    "regular": ("mlce",),
    "regular_until": ("mlce",),
    "chaos_onset_near": ("mlce",),
    "mlce_near": ("mlce",),
    "eta_near": ("eta",),
}


def statement_panels(statement: Statement) -> list[str]:
    """The panels a statement is about: those of the figure its text cites, "(Fig. 4)" or
    "(Fig. 4d)", that show its scene, narrowed to the kinds that show its kind of statement when
    the figure has such a panel.

    Parameters
    ----------
    statement : Statement
        The statement.

    Returns
    -------
    list of str
        Keys of ``PANELS``.

    Raises
    ------
    ValueError
        For a statement whose text does not end with the figure it cites.
    """
    cited = re.search(r"\(Fig\. (\d+)([a-z]?)\)$", statement.text)
    if cited is None:
        raise ValueError(f"statement {statement.id!r} cites no figure as (Fig. N) or (Fig. Nx) at its end")
    figure, letter = int(cited.group(1)), cited.group(2)
    showing = [p for p in panels_of_figure(figure) if statement.scene in PANELS[p].scenes
               and (not letter or p == f"{figure}{letter}")]
    matching = [p for p in showing if PANELS[p].kind in STATEMENT_PANEL_KINDS[statement.kind]]
    return matching or showing


def statements_of_panel(panel_id: str) -> list[Statement]:
    """The statements about one panel (:func:`statement_panels`).

    Parameters
    ----------
    panel_id : str
        A key of ``PANELS``.

    Returns
    -------
    list of Statement
        Its statements, in table order.
    """
    return [s for s in STATEMENTS if panel_id in statement_panels(s)]
