# Shared helpers: where things go, and what each scene and panel needs (from the panel table).

import json
import re

from chainchaos import paper
from chainchaos.simd import LANES
from chainchaos.simulate import SceneParameters, scene_batches

RESULTS = config["results"]
SCENES = paper.scenes()
FIGURES = sorted(paper.LAYOUTS)

_unknown = sorted(set(config.get("scenes", {})) - set(SCENES))
if _unknown:
    raise ValueError(
        f"config key scenes: unknown scene name(s) {_unknown}; allowed are {sorted(SCENES)}"
    )


def result(*parts):
    return "/".join([RESULTS, *parts])


def log_file(rule_name, stem="run"):
    return result("logs", rule_name, f"{stem}.log")


def benchmark_file(rule_name, stem="run"):
    return result("benchmarks", rule_name, f"{stem}.tsv")


def scene_parameters(scene_name):
    """SceneParameters keyword arguments of a scene: the `simulation` block, the scene's own
    overrides, and the observables its panels use (paper.scene_observables)."""
    scene = SCENES[scene_name]
    params = {**config["simulation"], **config.get("scenes", {}).get(scene_name, {})}
    params.update(
        model=scene.model,
        energy=scene.energy,
        observables=paper.scene_observables(scene_name),
        name=scene_name,
    )
    return params


# Scenes that share their integration settings run together, as many as the SIMD width of this
# machine's batch engine (chainchaos.simd.LANES); results do not depend on the grouping.
SCENE_BATCHES = scene_batches(
    {name: SceneParameters(**scene_parameters(name)) for name in SCENES}, LANES
)
SCENE_BATCH = {name: batch for batch, names in SCENE_BATCHES.items() for name in names}


def scene_file(scene_name):
    return result("scenes", f"{scene_name}.nc")


def panel_inputs(panel_id):
    """Files a panel is drawn from."""
    panel = paper.PANELS[panel_id]
    files = {s.name: scene_file(s.name) for s in panel.scenes}
    if panel.kind == "ensemble_participation":
        files["ensemble"] = result("ensemble", "participation_stats.nc")
    if panel.kind == "chain_spectrum":
        files["chain"] = result("chain", "chain.nc")
    return files


def figure_inputs(number):
    files = {}
    for panel_id in paper.panels_of_figure(number):
        files.update(panel_inputs(panel_id))
    return files


PANEL_TARGETS = [
    result("figures", f"fig{p}.{ext}") for p in sorted(paper.PANELS) for ext in ("pdf", "png")
]
FIGURE_TARGETS = [result("figures", f"fig{n}.{ext}") for n in FIGURES for ext in ("pdf", "png")]
ALL_TARGETS = PANEL_TARGETS + FIGURE_TARGETS
