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
