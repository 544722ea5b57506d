"""The paper's figures as data: every panel, the scenes it draws from, the observables it needs.

This table is the single place that links panels to simulations (DESIGN section 6): the pipeline
derives from it which scenes to run and which observables each scene computes, and the plotting
code reads from it what to draw.
"""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Scene:
    model: str
    energy: float

    @property
    def name(self) -> str:
        """File stem of the scene, e.g. ``hertz_H0.25`` (results/scenes/<name>.nc)."""
        return f"{self.model}_H{self.energy:g}"


@dataclass(frozen=True)
class Panel:
    kind: str
    scenes: tuple[Scene, ...] = ()
    options: dict = field(default_factory=dict)


# What each kind of panel reads from a scene file.
KIND_OBSERVABLES = {
    "ensemble_participation": (),
    "chain_spectrum": (),
    "energy_map": ("energy_density", "energy_centre"),
    "participation": ("participation",),
    "participation_with_dvd": ("participation", "dvd_participation"),
    "mlce": ("mlce",),
    "dvd_map": ("dvd",),
    "dvd_profiles": ("dvd",),
    "dvd_participation": ("dvd_participation",),
    "gap_map": ("gap_fraction", "gap_open"),
    "gap_count": ("n_gaps",),
    "eta": ("eta",),
    "mode_energy_map": ("mode_energy",),
}

HZ = {e: Scene("hertz", e) for e in (0.25, 0.5, 1.8, 3.0)}
FP = {e: Scene("fput", e) for e in (0.25, 0.5, 1.8, 2.9, 4.0, 8.7381)}


def _fput_row(energy: float, first: str) -> dict[str, Panel]:
    letters = "abcdefghijkl"
    i = letters.index(first)
    s = (FP[energy],)
    return {
        f"6{letters[i]}": Panel("energy_map", s),
        f"6{letters[i + 1]}": Panel("participation_with_dvd", s),
        f"6{letters[i + 2]}": Panel("dvd_map", s),
        f"6{letters[i + 3]}": Panel("mlce", s),
    }


PANELS: dict[str, Panel] = {
    "1a": Panel("ensemble_participation"),
    "1b": Panel("chain_spectrum", options={"inset_mode": 34}),
    "2a": Panel("energy_map", (HZ[0.25],)),
    "2b": Panel("energy_map", (FP[0.25],)),
    "2c": Panel("participation", (HZ[0.25], FP[0.25])),
    "2d": Panel("mlce", (HZ[0.25], FP[0.25])),
    "3a": Panel("dvd_map", (HZ[0.25],)),
    "3b": Panel("dvd_map", (FP[0.25],)),
    "3c": Panel("dvd_profiles", (HZ[0.25],), {"times": (10.0, 1e3, 1e5)}),
    "3d": Panel("dvd_profiles", (FP[0.25],), {"times": (10.0, 1e3, 1e5)}),
    "3e": Panel("dvd_participation", (HZ[0.25],)),
    "3f": Panel("dvd_participation", (FP[0.25],)),
    "4a": Panel("energy_map", (HZ[0.5],)),
    "4b": Panel("energy_map", (HZ[1.8],)),
    "4c": Panel("participation", (HZ[0.5], HZ[1.8], FP[0.5], FP[1.8])),
    "4d": Panel("mlce", (HZ[0.5], HZ[1.8], FP[0.5], FP[1.8])),
    "5a": Panel("dvd_map", (HZ[0.5],)),
    "5b": Panel("dvd_profiles", (HZ[0.5],), {"times": (17.0, 1.7e4, 8.2e4)}),
    "5c": Panel("dvd_map", (HZ[1.8],)),
    "5d": Panel("dvd_profiles", (HZ[1.8],), {"times": (17.0, 4.9e3, 3.5e4, 4.8e4)}),
    **_fput_row(2.9, "a"),
    **_fput_row(4.0, "e"),
    **_fput_row(8.7381, "i"),
    "7a": Panel("gap_map", (HZ[0.5],)),
    "7b": Panel("gap_map", (HZ[1.8],)),
    "7c": Panel("gap_count", (HZ[0.5],)),
    "7d": Panel("gap_count", (HZ[1.8],)),
    "8a": Panel("eta", (HZ[0.25],)),
    "8b": Panel("eta", (HZ[0.5],)),
    "8c": Panel("eta", (HZ[1.8],), {"equipartition": True}),
    "8d": Panel("eta", (HZ[3.0],), {"equipartition": True}),
    "8e": Panel("mode_energy_map", (HZ[0.25],)),
    "8f": Panel("mode_energy_map", (HZ[0.5],)),
    "8g": Panel("mode_energy_map", (HZ[1.8],)),
    "8h": Panel("mode_energy_map", (HZ[3.0],)),
    "9a": Panel("eta", (FP[0.25],)),
    "9b": Panel("eta", (FP[2.9],), {"equipartition": True}),
    "9c": Panel("eta", (FP[4.0],)),
    "9d": Panel("eta", (FP[8.7381],), {"equipartition": True}),
    "9e": Panel("mode_energy_map", (FP[0.25],)),
    "9f": Panel("mode_energy_map", (FP[2.9],)),
    "9g": Panel("mode_energy_map", (FP[4.0],)),
    "9h": Panel("mode_energy_map", (FP[8.7381],)),
}

# Composite layouts (rows of panel letters), as in the paper.
LAYOUTS: dict[int, list[str]] = {
    1: ["a", "b"],
    2: ["ab", "cd"],
    3: ["ab", "cd", "ef"],
    4: ["ab", "cd"],
    5: ["ab", "cd"],
    6: ["abcd", "efgh", "ijkl"],
    7: ["ab", "cd"],
    8: ["abcd", "efgh"],
    9: ["abcd", "efgh"],
}


def panels_of_figure(figure: int) -> list[str]:
    return sorted(p for p in PANELS if int(p[:-1]) == figure)


def scenes() -> dict[str, Scene]:
    """Every scene any panel uses, by name."""
    return {s.name: s for panel in PANELS.values() for s in panel.scenes}


def scene_observables(scene_name: str) -> list[str]:
    """The observables a scene must compute: the union over the panels that use it."""
    wanted = {o for panel in PANELS.values() if scene_name in {s.name for s in panel.scenes}
              for o in KIND_OBSERVABLES[panel.kind]}
    if not wanted:
        raise KeyError(f"no panel uses scene {scene_name!r}; scenes are {sorted(scenes())}")
    return sorted(wanted)


def panels_of_scene(scene_name: str) -> list[str]:
    return sorted(p for p, panel in PANELS.items() if scene_name in {s.name for s in panel.scenes})


# The paper's qualitative statements about its scenes, as data: what a realization must show to
# tell the paper's story. Each is decided per orbit by ``verdicts.STATEMENT_KINDS[kind]`` with the
# thresholds of the config block ``verdicts:``; ``value`` is the paper's number where it gives one
# (a time, a level), ``until`` the end of the window a statement is about. ``early``: a run
# shorter than the paper's can already break it (a packet that has spread is not localized at the
# end; an orbit already chaotic is not regular), which the realization search uses to discard
# chains cheaply.


@dataclass(frozen=True)
class Statement:
    id: str
    scene: Scene
    kind: str
    text: str
    value: float | None = None
    until: float | None = None
    early: bool = False


def _pair(scene: Scene, localized: bool, chaotic: bool, where: str) -> tuple[Statement, ...]:
    label = "Hertz" if scene.model == "hertz" else "FPUT"
    tag = f"H{scene.energy:g}-{scene.model}"
    return (
        Statement(f"{'loc' if localized else 'deloc'}-{tag}", scene, "localized" if localized else "delocalized",
                  f"{label} $H = {scene.energy:g}$: {'localized' if localized else 'delocalized'} at the end "
                  f"({where})", early=localized),
        Statement(f"{'chaos' if chaotic else 'regular'}-{tag}", scene, "chaotic" if chaotic else "regular",
                  f"{label} $H = {scene.energy:g}$: {'chaotic' if chaotic else 'regular'} ({where})",
                  early=not chaotic),
    )


STATEMENTS: tuple[Statement, ...] = (
    *_pair(HZ[0.25], True, False, "Fig. 2"),
    *_pair(HZ[0.5], True, True, "Fig. 4"),
    Statement("chaos-late-H0.5-hertz", HZ[0.5], "regular_until",
              "Hertz $H = 0.5$: chaotic only in the last decade, regular up to $t = 10^4$ (Fig. 4d)",
              until=1e4, early=True),
    Statement("spread-level-H1.8-hertz", HZ[1.8], "participation_below_until",
              "Hertz $H = 1.8$: $P < 3$ up to $t \\approx 2\\times 10^2$ (Fig. 4c)", value=3.0, until=2e2,
              early=True),
    Statement("spread-onset-H1.8-hertz", HZ[1.8], "spreading_onset_near",
              "Hertz $H = 1.8$: $P$ starts to grow at $t \\approx 2\\times 10^2$ (Fig. 4c)", value=2e2),
    *_pair(HZ[1.8], False, True, "Fig. 4"),
    Statement("chaos-onset-H1.8-hertz", HZ[1.8], "chaos_onset_near",
              "Hertz $H = 1.8$: chaotic from $t \\approx 2\\times 10^2$ (Fig. 4d)", value=2e2),
    Statement("spread-until-H1.8-hertz", HZ[1.8], "saturation_near",
              "Hertz $H = 1.8$: $P$ grows until $t \\approx 4\\times 10^3$ (Fig. 4c)", value=4e3),
    Statement("mlce-H1.8-hertz", HZ[1.8], "mlce_near",
              "Hertz $H = 1.8$: $\\Lambda$ levels off near $10^{-3}$ (Fig. 4d)", value=1e-3),
    *_pair(HZ[3.0], False, True, "Fig. 8"),
    *_pair(FP[0.25], True, False, "Fig. 2"),
    *_pair(FP[0.5], True, False, "Fig. 4"),
    *_pair(FP[1.8], True, False, "Fig. 4"),
    *_pair(FP[2.9], False, True, "Fig. 6"),
    Statement("chaos-onset-H2.9-fput", FP[2.9], "chaos_onset_near",
              "FPUT $H = 2.9$: chaotic from $t \\approx 4\\times 10^3$ (Fig. 6d)", value=4e3),
    *_pair(FP[4.0], True, True, "Fig. 6"),
    Statement("eta-H4-fput", FP[4.0], "eta_near",
              "FPUT $H = 4$: $\\eta \\approx 0.82$ for most of the run (Fig. 9c)", value=0.82),
    *_pair(FP[8.7381], False, True, "Fig. 6"),
)


def statements_of_scene(scene_name: str) -> list[Statement]:
    return [s for s in STATEMENTS if s.scene.name == scene_name]


def statement_scenes() -> dict[str, Scene]:
    """The scenes the statements are about, by name, in table order."""
    return {s.scene.name: s.scene for s in STATEMENTS}
