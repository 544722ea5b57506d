"""The paper's figures as data: every panel, the scenes it draws from, the observables it needs.

This table is the single place that links panels to simulations (docs/conventions.md#scenes): the pipeline
derives from it which scenes to run and which observables each scene computes, and the plotting
code reads from it what to draw.
"""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Scene:
    """A scene of the paper: one model at one energy, integrated once and drawn by its panels.

    Parameters
    ----------
    model : str
        A model's name (``MODELS``).
    energy : float
        Total energy H of the excitation, in the model's energy unit.
    """

    model: str
    energy: float

    @property
    def name(self) -> str:
        """File stem of the scene, e.g. ``hertz_H0.25`` (results/scenes/<name>.nc)."""
        return f"{self.model}_H{self.energy:g}"


@dataclass(frozen=True)
class Panel:
    """A panel of the paper's figures: an entry of ``PANELS`` (``chainchaos.PANELS``).

    Parameters
    ----------
    kind : str
        What it draws, a key of ``KIND_OBSERVABLES`` (which says what it reads from its scenes).
    scenes : tuple of Scene, optional
        The scenes it draws from (default none: a panel of the chain or of the ensemble).
    options : dict, optional
        Options of its kind, e.g. ``{"times": (10.0, 1e3, 1e5)}`` for DVD profiles.
    """

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

# What a panel of each kind shows: a few words (the HTML report's label) and a sentence (its
# caption, chainchaos.output.report_captions); math in $...$ as in the statements below.
KIND_TEXT = {
    "ensemble_participation": (
        "mean P of the linear modes",
        r"mean participation number $\langle P \rangle$ of the linear modes over the disorder "
        r"realizations against rank $k$ (modes sorted by descending $P$ in each realization), one curve "
        r"per disorder strength $\alpha$, error bars one standard deviation"),
    "chain_spectrum": (
        "spectrum of the chain",
        r"linear frequencies $\omega_k$ of the chosen $\alpha = 5$ chain against mode number $k$; the "
        r"inset shows the profile of mode 34 against site"),
    "energy_map": (
        "energy density map",
        r"energy density $h_n(t)$ of each site against time (logarithmic colour scale), with the "
        r"mean position of the energy as a black line"),
    "participation": (
        "participation number P",
        r"participation number $P(t)$ of the energy distribution, smoothed (LOWESS in $\log t$) with "
        r"the raw values faint behind; Hertz red, FPUT blue, energies told apart by shade and dash"),
    "participation_with_dvd": (
        "P and P_D",
        r"participation numbers $P(t)$ of the energy and $P_{\mathrm{D}}(t)$ of the deviation vector "
        r"density, both smoothed (LOWESS in $\log t$)"),
    "mlce": (
        "finite-time mLCE",
        r"finite-time maximum Lyapunov exponent $\Lambda(t)$ on log-log axes, with the law "
        r"$\Lambda \propto t^{-1}$ of regular orbits dashed"),
    "dvd_map": (
        "DVD map",
        r"deviation vector density $w_n(t)$ of each site against time (logarithmic colour scale), with "
        r"the times of the profile panel marked"),
    "dvd_profiles": (
        "DVD profiles",
        r"deviation vector density $w_n$ against site (logarithmic scale) at the times the paper picks"),
    "dvd_participation": (
        "P_D of the DVD",
        r"participation number $P_{\mathrm{D}}(t)$ of the deviation vector density, smoothed (LOWESS in "
        r"$\log t$)"),
    "gap_map": (
        "gap map",
        r"open bonds (gaps, $u_n - u_{n-1} > \delta_n$) against time: the fraction of the time since "
        r"the previous sample each bond was open"),
    "gap_count": (
        "number of gaps",
        r"number of open gaps against time, at each sample and the largest since the previous one"),
    "eta": (
        "spectral entropy",
        r"normalized spectral entropy $\eta(t)$ of the linear-mode energies; where the paper draws it, "
        r"the mean $\langle \eta \rangle$ at equipartition as a dashed line"),
    "mode_energy_map": (
        "mode energy map",
        r"normalized harmonic energies $v_k(t)$ of the linear modes, numbered by increasing "
        r"frequency, against time (logarithmic colour scale)"),
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



@dataclass(frozen=True)
class Figure:
    """A figure of the paper: its subject and what the paper reports about its panels.

    Parameters
    ----------
    title : str
        Its subject, a few words.
    reports : dict of str to str
        By panel letters (``"ab"``: panels a and b), what the paper reports about them, math in
        ``$...$``.
    """

    title: str
    reports: dict[str, str]  # panel letters -> what the paper reports about those panels


# Each figure's subject and, by panel, what the paper reports (its captions and Sec. II-III).
FIGURES: dict[int, Figure] = {
    1: Figure("disorder statistics and the chosen chain", {
        "a": r"Already at $\alpha = 2$ the curve $\langle P \rangle(k)$ lies far from the homogeneous "
             r"chain's; for $\alpha \ge 4$ it reaches a limiting curve with about 10 strongly localized "
             r"modes, $\langle P \rangle \approx 2$. The most extended mode has $P \approx 26$.",
        "b": r"Low-frequency modes extend over many sites, high-frequency ones are localized; mode 34 is "
             r"strongly localized ($P \approx 2.5$) at site $n = 21$, the site every run excites.",
    }),
    2: Figure("H = 0.25: both chains localized and regular", {
        "ab": r"The energy stays localized around the excited site $n = 21$ in both chains.",
        "c": r"$P \approx 1.8$ throughout, the Hertz and FPUT curves almost overlap.",
        "d": r"$\Lambda(t) \propto t^{-1}$ for both chains (regular orbits); the curves practically "
             r"overlap.",
    }),
    3: Figure("H = 0.25: deviation vectors", {
        "ab": r"The DVD is extended and smooth, unlike the pointy DVD of chaotic orbits.",
        "cd": r"The profiles at $t \approx 10^1$, $10^3$, $10^5$ cover the excited part of the lattice "
              r"smoothly.",
        "ef": r"$P_{\mathrm{D}} \approx 20$ in both chains up to $t \approx 10^3$; afterwards the Hertz "
              r"$P_{\mathrm{D}}$ starts to drop, a precursor of a chaotic spot.",
    }),
    4: Figure("H = 0.5 and 1.8: chaos and spreading of the Hertz chain", {
        "a": r"Hertz $H = 0.5$: the energy stays localized.",
        "b": r"Hertz $H = 1.8$: localized up to $t \approx 2\times 10^2$, then the packet spreads over "
             r"the chain.",
        "c": r"Hertz $H = 0.5$: $P$ grows a little in the last decade. Hertz $H = 1.8$: $P < 3$ up to "
             r"$t \approx 2\times 10^2$, rapid spreading until $t \approx 4\times 10^3$, then "
             r"$P \approx 26$. FPUT stays localized at both energies.",
        "d": r"Hertz $H = 0.5$: $\Lambda$ leaves the $t^{-1}$ law in the last decade (localized chaos). "
             r"Hertz $H = 1.8$: chaotic from $t \approx 2\times 10^2$, $\Lambda \approx 10^{-3}$. FPUT "
             r"stays regular at both energies.",
    }),
    5: Figure("Hertz chain: localized and extended chaos in the DVD", {
        "ab": r"$H = 0.5$: the DVD is extended while the orbit is regular, converges on site 21 up to "
              r"$t \approx 4\times 10^3$ and then stays strongly localized there (localized chaos).",
        "cd": r"$H = 1.8$: after an extended start the DVD has one dominant peak that moves over the "
              r"whole lattice (extended chaos).",
    }),
    6: Figure("FPUT chain at H = 2.9, 4 and 8.7381", {
        "abcd": r"$H = 2.9$, the first energy at which FPUT delocalizes: the packet spreads in the last "
                r"decade, $\Lambda$ leaves the $t^{-1}$ law for $t \gtrsim 4\times 10^3$, the DVD "
                r"peaks in changing places (extended chaos).",
        "efgh": r"$H = 4$: the packet stays localized and $P$ hardly changes; the DVD stays at site 21 "
                r"up to $t \approx 2\times 10^4$, then wanders to the left part while $\Lambda$ "
                r"deviates only slightly from the regular law.",
        "ijkl": r"$H = 8.7381$: delocalized and chaotic, as at $H = 2.9$. Above $H \approx 2.8$ FPUT is "
                r"always chaotic, localized or not.",
    }),
    7: Figure("Hertz chain: gaps", {
        "ac": r"$H = 0.5$: gaps open next to site 21 only, never more than one at a time; the "
              r"non-smooth nonlinearity there is what makes the orbit chaotic.",
        "bd": r"$H = 1.8$: more gaps open and move away from site 21 from $t \approx 3\times 10^2$, "
              r"when $P$ starts to grow, and eventually cover the whole lattice.",
    }),
    8: Figure("Hertz chain: spectral entropy and mode energies", {
        "ae": r"$H = 0.25$: $\eta$ stays near 1; mode 34 dominates with a few weak low-frequency "
              r"modes, constant after $t \approx 10^2$.",
        "bf": r"$H = 0.5$: the same, but $\eta$ drops in steps as new modes come in near "
              r"$t \approx 8\times 10^3$ and $8\times 10^4$.",
        "cdgh": r"$H = 1.8$ and 3: a plateau near $\eta \approx 0.5$, then a fall to the equipartition "
                r"value $\langle \eta \rangle$; in the last decade all modes take part.",
    }),
    9: Figure("FPUT chain: spectral entropy and mode energies", {
        "ae": r"$H = 0.25$: as for Hertz, $\eta$ stays close to 1, one dominant mode and a few "
              r"low-frequency ones.",
        "bf": r"$H = 2.9$: a plateau at $\eta \approx 0.7$ (a metastable phase), an abrupt fall at "
              r"$t \approx 5\times 10^3$ to about $\langle \eta \rangle$; almost all modes excited.",
        "cg": r"$H = 4$: $\eta \approx 0.82$ for most of the run, falling only slowly in the last two "
              r"decades; the highest-frequency modes stay silent.",
        "dh": r"$H = 8.7381$: a plateau near $\eta \approx 0.8$, a drop from $t \approx 10^4$ to "
              r"about $\langle \eta \rangle$; at the end all modes take part.",
    }),
}


def panels_of_figure(figure: int) -> list[str]:
    """The keys of ``PANELS`` of one figure.

    Parameters
    ----------
    figure : int
        The figure's number.

    Returns
    -------
    list of str
        Its panels' keys (``"2a"``, ``"2b"``, ...), sorted.
    """
    return sorted(p for p in PANELS if int(p[:-1]) == figure)


def scenes() -> dict[str, Scene]:
    """Every scene any panel uses, by name.

    Returns
    -------
    dict of str to Scene
        The scenes by ``Scene.name``, in the order the panels first use them.
    """
    return {s.name: s for panel in PANELS.values() for s in panel.scenes}


def models() -> tuple[str, ...]:
    """The models of the paper's scenes, in the order the panels first use them.

    Returns
    -------
    tuple of str
        The models' names.
    """
    return tuple(dict.fromkeys(s.model for s in scenes().values()))


def scene_observables(scene_name: str) -> list[str]:
    """The observables a scene must compute: the union over the panels that use it.

    Parameters
    ----------
    scene_name : str
        A scene's name (``Scene.name``).

    Returns
    -------
    list of str
        The observables' names, sorted.

    Raises
    ------
    KeyError
        For a scene no panel uses.
    """
    wanted = {o for panel in PANELS.values() if scene_name in {s.name for s in panel.scenes}
              for o in KIND_OBSERVABLES[panel.kind]}
    if not wanted:
        raise KeyError(f"no panel uses scene {scene_name!r}; scenes are {sorted(scenes())}")
    return sorted(wanted)
