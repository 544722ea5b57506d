"""The workflow's scripts and the task functions they run (chainchaos.workflow.tasks).

Every rule `X` of workflow/rules/F.smk runs workflow/scripts/X.py, which names its task: an import
of ``chainchaos.workflow.tasks.F.X`` and ``run(snakemake, X)``, which runs it with stderr in the
rule's log. The end-to-end run of every task is the quick pipeline (tests/project/test_pipeline.py); the
cheap ones are also run here on small inputs."""

import ast
import importlib
import json
import os
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from chainchaos.output.manuscript import GENERATED
from chainchaos.records.io import ensemble_dataset
from chainchaos.workflow.tasks import run
from chainchaos.workflow.tasks.chain import compute_ensemble
from chainchaos.workflow.tasks.simulate import simulate_scene

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "workflow" / "scripts"
RULE_FILES = [ROOT / "Snakefile", *sorted((ROOT / "workflow" / "rules").glob("*.smk"))]


def rules() -> dict[str, tuple[Path, str]]:
    """Every rule of the workflow: name -> (its rule file, its rule's text)."""
    found = {}
    for path in RULE_FILES:
        text = path.read_text()
        for m in re.finditer(r"^( *)(?:rule|checkpoint) (\w+):", text, re.M):
            end = re.search(rf"^ {{0,{len(m.group(1))}}}\S", text[m.end():], re.M)  # the next line at the rule's level
            found[m.group(2)] = (path, text[m.start():m.end() + (end.start() if end else len(text))])
    return found


def script_of(rule_text: str) -> str | None:
    m = re.search(r"^ +script:\n\s+\"\.\./scripts/([^\"]+)\"", rule_text, re.M)
    return m and m.group(1)


def script_calls(path: Path) -> tuple[str, str]:
    """(the task module, the task) a script names: ``from M import T`` and ``run(snakemake, T)``."""
    body = ast.parse(path.read_text()).body
    if isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
        body = body[1:]  # the docstring
    assert ast.unparse(body[0]) == "from chainchaos.workflow.tasks import run", path.name
    assert isinstance(body[1], ast.ImportFrom) and len(body[1].names) == 1, path.name
    task = body[1].names[0].name
    assert [ast.unparse(node) for node in body[2:]] == [f"run(snakemake, {task})"], path.name
    return body[1].module, task


def fake_rule(rule, log, input=(), output=(), params=(), wildcards=()):
    """What run reads of the `snakemake` object of a script."""
    return SimpleNamespace(rule=rule, log=[str(log)], input=dict(input), output=dict(output), params=dict(params),
                           wildcards=dict(wildcards))


# ------------------------------------------------------------------ one path: rule = script = task


def test_every_rule_is_written_once_with_its_name():
    """No rule made in a loop or named at run time (``rule:`` with ``name:``): wildcards instead."""
    for path in RULE_FILES:
        text = path.read_text()
        assert not re.search(r"^\s*(?:rule|checkpoint)\s*:", text, re.M), path.name
        assert not re.search(r"^\s+name:", text, re.M), path.name


def test_every_rule_runs_the_script_named_like_it_and_its_task_from_its_rule_file_s_module():
    found = rules()
    assert {"all", "simulate_scene", "numerics_work_precision", "build_manuscript", "keep_study_group",
            "search_full"} <= set(found)
    for name, (path, text) in found.items():
        script = script_of(text)
        if script is None:  # a target rule: inputs only
            assert not re.search(r"^ +(output|shell|run):", text, re.M), name
            continue
        assert script == f"{name}.py", f"rule {name} runs {script}"
        module, task = script_calls(SCRIPTS / script)
        assert module == f"chainchaos.workflow.tasks.{path.stem}", name
        assert task == name, f"script {script} runs {task}"
        assert callable(getattr(importlib.import_module(module), task)), name


def test_every_script_belongs_to_a_rule():
    scripted = {name for name, (_, text) in rules().items() if script_of(text)}
    assert {p.stem for p in SCRIPTS.glob("*")} == scripted


def test_every_rule_with_an_action_has_a_log_and_a_benchmark():
    for name, (_, text) in rules().items():
        if script_of(text):
            assert re.search(r"^ +log:", text, re.M), name
            assert re.search(r"^ +benchmark:", text, re.M), name


# ------------------------------------------------------------------ run


def test_run_sends_stderr_and_a_failure_s_traceback_to_the_log(tmp_path):
    def fails(inputs, outputs, params, wildcards):
        print(f"working on {wildcards['scene']}", file=sys.stderr)
        raise ValueError("bad value")

    log = tmp_path / "fails.log"
    with pytest.raises(ValueError, match="bad value"):
        run(fake_rule("fails", log, wildcards={"scene": "hertz_H1"}), fails)
    text = log.read_text()
    assert text.startswith("working on hertz_H1\n") and "Traceback" in text and "ValueError: bad value" in text


def test_missing_tex_stops_with_the_debian_packages_and_no_traceback(tmp_path):
    """The README's message: TeX is looked for before anything else, and no PDF is written."""
    empty = tmp_path / "bin"
    empty.mkdir()
    pdf, log = tmp_path / "ms.pdf", tmp_path / "build.log"
    inputs = {"tex": "manuscript/ms.tex", **{key: str(tmp_path / "missing" / name) for key, name in GENERATED.items()}}
    rule = dict(rule="build_manuscript", log=[str(log)], input=inputs,
                output={"pdf": str(pdf)}, params={"build_dir": str(tmp_path / "build")}, wildcards={})
    code = ("import json, sys, types\nfrom chainchaos.workflow.tasks import run\n"
            "from chainchaos.workflow.tasks.manuscript import build_manuscript\n"
            "run(types.SimpleNamespace(**json.loads(sys.argv[1])), build_manuscript)")
    done = subprocess.run([sys.executable, "-c", code, json.dumps(rule)], cwd=ROOT, capture_output=True, text=True,
                          env={**os.environ, "PATH": str(empty)})
    assert done.returncode == 1
    assert done.stderr.startswith("build_manuscript: cannot build the manuscript: TeX is missing (latexmk, ")
    assert "apt-get install texlive-latex-base" in done.stderr and "texlive-publishers" in done.stderr
    assert "Traceback" not in done.stderr + done.stdout + log.read_text()
    assert done.stderr.strip() in log.read_text()
    assert not pdf.exists() and not (tmp_path / "build").exists()


# ------------------------------------------------------------------ cheap tasks on small inputs


def test_compute_ensemble_honours_every_key_of_the_ensemble_block(tmp_path):
    block = {"alphas": [2.0, 5.0], "realizations": 4, "first_seed": 7, "convention": "period_averaged"}
    out = tmp_path / "stats.nc"
    run(fake_rule("compute_ensemble", tmp_path / "log", output={"stats": str(out)},
                  params={"ensemble": block, "N": 12}), compute_ensemble)
    written = xr.load_dataset(out)
    expected = ensemble_dataset([2.0, 5.0], 4, 12, 7, "period_averaged")
    assert written.attrs["first_seed"] == 7 and written.attrs["convention"] == "period_averaged"
    for name in expected.data_vars:
        np.testing.assert_array_equal(written[name].values, expected[name].values)
    assert not np.array_equal(written["mean_participation"].values,
                              ensemble_dataset([2.0, 5.0], 4, 12)["mean_participation"].values)


def test_simulate_scene_writes_the_scene_as_simulate_integrates_it(tmp_path):
    """The job of one scene writes the Dataset of chainchaos.run.scenes.simulate, to the bit."""
    from dataclasses import asdict

    from chainchaos.records.io import chain_dataset, write_netcdf
    from chainchaos.run.scenes import SceneParameters, simulate
    from chainchaos.system.chain import random_chain

    chain = random_chain(879, 5.0, 12)
    chain_file = write_netcdf(chain_dataset(chain), tmp_path / "chain.nc")
    scene = SceneParameters(model="fput", t_final=5.0, dt=0.01, samples_per_decade=4, check_every=100, energy=1.8,
                            excited_site=6, observables=("participation", "mlce"), name="fput_H1.8")
    output = str(tmp_path / "scenes" / "fput_H1.8.nc")
    run(fake_rule("simulate_scene", tmp_path / "log", input={"chain": str(chain_file), "kernels": []},
                  output={"scene": output}, params={"scene": asdict(scene)}, wildcards={"scene": scene.name}),
        simulate_scene)
    written, alone = xr.load_dataset(output), simulate(chain, scene)
    assert set(written.data_vars) == set(alone.data_vars)
    for name in alone.data_vars:
        np.testing.assert_array_equal(written[name].values, alone[name].values, err_msg=name)
