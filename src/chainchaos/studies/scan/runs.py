"""Energy scans and disorder statistics of delocalization and chaos (issue 7): studies of the
config's ``scan`` block (:func:`scan_study`), their settings and their kept files.

Each trajectory is reduced to the numbers of ``studies.study.orbits`` (``participation_final``,
``mlce_final``, ``delocalization_onset``, ``chaos_onset``, ...) and judged by its criteria
(delocalized, chaotic, and with ``alignment`` GALI_k), stated in every output file; the
excitation of a realization is ``orbits.select_excitation``. A chaotic orbit with mLCE lambda is
seen once lambda t_final is of order 10, so a short scan (quick scale, t = 1e3) reports only strong
chaos, and a claim that reads "chaotic" from the scan is undecided where the two indicators lead
to different answers (``claims.measures``).

Their orbits run as every study's do (``studies.study.runs.run_group``). A trajectory whose state
turns non-finite or whose relative energy error exceeds ``max_energy_error`` is kept with
``valid = 0`` and left out of the statistics.
"""

from dataclasses import asdict

from chainchaos.paper import panels
from chainchaos.studies.study.orbits import StudySettings, settings_blocks
from chainchaos.system.chain import random_chain

#: Version of the numbers of the disorder statistics (the kept full statistics record it,
#: chainchaos.records.kept): bump only when a change of code changes their numbers (the bit-identity
#: test tests/records/test_kept.py tells).
DISORDER_RESULT_VERSION = 1


# ----------------------------------------------------------------------------------------------
# Configuration: grids, groups of trajectories per job
# ----------------------------------------------------------------------------------------------


#: Scan kinds whose block extends another's: the full disorder statistics, kept in the repository
#: (``scan.disorder.archive``, written by ``snakemake --cores 2 keep --config keep=disorder_full``),
#: are the disorder statistics with the keys of ``scan.disorder_full`` (more realizations and
#: energies) in place of its own.
EXTENDS = {"disorder_full": "disorder"}


def scan_config(kind: str, scan_cfg: dict) -> tuple[str, dict]:
    """(the kind the jobs run, the scan block as they see it): for a kind of :data:`EXTENDS`, its
    base with the base's block updated by the kind's own (without ``archive``)."""
    base = EXTENDS.get(kind)
    if base is None:
        return kind, scan_cfg
    block = {k: v for k, v in {**scan_cfg[base], **scan_cfg[kind]}.items() if k != "archive"}
    return base, {**scan_cfg, base: block}


#: The scan settings that decide what is delocalized and chaotic (``criteria_attrs``).
CRITERIA_KEYS = ("p_delocalized", "chaos_slope", "chaos_growth_margin", "onset_hold_decades", "gali_threshold")
#: Settings that say how the work is cut, not what it computes (the engines, batches and groups
#: give identical numbers): left out of the settings that key a kept result.
SCHEDULING_KEYS = ("engine", "batch_size", "trajectories_per_job")


def disorder_settings(scan_cfg: dict, N: int) -> dict:
    """The settings that determine the disorder statistics (their key as a kept result,
    ``chainchaos.records.kept``): ``scan_cfg`` is the scan block as the jobs see it (for the full
    statistics ``scan_config("disorder_full", ...)[1]``), ``N`` the chain's length.

    ``chain``: N, alpha, wall radius, first seed and realizations; ``excitation``: the rule that
    picks the excited bead (``selection_kwargs``); ``energies``: the models and the energy grid's
    keys; ``orbit``: integration and sampling (``settings_for``, without :data:`SCHEDULING_KEYS`);
    ``criteria``: :data:`CRITERIA_KEYS`."""
    block = scan_cfg["disorder"]
    settings = asdict(settings_for("disorder", scan_cfg))
    return {
        "chain": {"N": int(N), "alpha": float(block.get("alpha", 5.0)), "wall_radius": float(block.get("wall_radius", 1.0)),
                  "first_seed": int(block.get("first_seed", 0)), "realizations": int(block["realizations"])},
        "excitation": selection_kwargs(scan_cfg),
        "energies": {"models": list(block.get("models", panels.models())), "n_energies": int(block["n_energies"]),
                     "energy_min": float(block["energy_min"]), "energy_max": float(block["energy_max"]),
                     "spacing": block.get("spacing", "log")},
        "orbit": {k: v for k, v in settings.items() if k not in (*CRITERIA_KEYS, *SCHEDULING_KEYS)},
        "criteria": {k: settings[k] for k in CRITERIA_KEYS},
    }


def settings_for(kind: str, scan_cfg: dict) -> StudySettings:
    """The ``scan.settings`` block overridden by the kind's own keys (t_final, dt, ...)."""
    merged = {**scan_cfg.get("settings", {}), **scan_cfg[kind]}
    return StudySettings.from_config(merged)


def realization_chain(scan_cfg: dict, r: int, N: int = 40):
    block = scan_cfg["disorder"]
    return random_chain(int(block.get("first_seed", 0)) + r, float(block.get("alpha", 5.0)), N,
                        float(block.get("wall_radius", 1.0)))


def selection_kwargs(scan_cfg: dict) -> dict:
    sel = scan_cfg["disorder"].get("selection", {})
    return {"high_frequency_modes": int(sel.get("high_frequency_modes", 14)),
            "centre_window": int(sel.get("centre_window", 5)),
            "convention": sel.get("convention", "potential")}


# ----------------------------------------------------------------------------------------------
# Group datasets and their merge
# ----------------------------------------------------------------------------------------------

#: The per-trajectory series a group file keeps (``orbits.SERIES``; long names from the registry).
SERIES = ("participation", "log_growth", "eta")
#: The studies the scan kinds are (``scan_study``), by their base kind.
TITLES = {"energy_scan": "Energy scan: delocalization and chaos of a single-site excitation on the chosen chain",
          "disorder": "Disorder statistics of delocalization and chaos"}
REALIZATION = {"units": "1", "long_name": "realization r: random_chain(first_seed + r, alpha)"}


# ----------------------------------------------------------------------------------------------
# The scans as studies
# ----------------------------------------------------------------------------------------------

def scan_study(kind: str, scan_cfg: dict, N: int = 40, chain_file: str | None = None) -> dict:
    """The study (``chainchaos.studies.study``, the keys of a study file) that a scan kind of the
    config block ``scan`` is: every orbit of the kind, run by the study's rules and functions.

    ``energy_scan``: the models on the chain of ``chain_file`` (the chosen chain), bead ``site``
    displaced, on the energy grid of the block; ``disorder`` (and ``disorder_full``, the disorder
    block with the keys of its own): the realizations random_chain(first_seed + r, alpha, N), each
    excited at the bead of the paper's rule (site ``selected``, :func:`select_excitation`). Every
    setting is the value :func:`settings_for` gives, so that an orbit is the one the scan's
    settings describe; one lane per orbit, the series P, ln|v| and eta, and ln GALI_k with
    ``alignment``."""
    base, cfg = scan_config(kind, scan_cfg)
    block = cfg[base]
    settings = settings_for(base, cfg)
    models = list(block.get("models", panels.models()))
    if base == "energy_scan":
        lattice = {"model": models, "chain_file": chain_file}
        site = int(block.get("site", 21))
    else:
        lattice = {"model": models, "N": int(N), "alpha": float(block.get("alpha", 5.0)),
                   "wall_radius": float(block.get("wall_radius", 1.0)), "realizations": int(block["realizations"]),
                   "first_seed": int(block.get("first_seed", 0))}
        site = "selected"
    excitation = {"kind": "site", "variable": "displacement", "site": site,
                  "energies": {"min": float(block["energy_min"]), "max": float(block["energy_max"]),
                               "n": int(block["n_energies"]), "spacing": block.get("spacing", "log")}}
    if site == "selected":
        excitation["selection"] = selection_kwargs(cfg)
    return {
        "name": kind, "title": TITLES[base], "lattice": lattice, "excitation": excitation,
        **settings_blocks(settings),
        "observables": ["participation", "log_growth", "eta", *(["log_gali"] if settings.alignment else [])],
        "jobs": {"orbits_per_job": int(block["trajectories_per_job"])},
        "figures": [],
    }
