"""The workflow's scripts and the task functions they run (chainchaos.workflow.tasks).

Every rule `X` of workflow/rules/F.smk runs workflow/scripts/X.py, two lines that call
``run_rule(snakemake)``, which runs ``chainchaos.workflow.tasks.F.X`` with stderr in the rule's log. The
end-to-end run of every task is the quick pipeline (tests/test_pipeline.py); the cheap ones are
also run here on small inputs."""

import ast
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

from chainchaos.output.io import ensemble_dataset
from chainchaos.output.manuscript import GENERATED
from chainchaos.workflow.tasks import TASKS, run_rule

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = ROOT / "workflow" / "scripts"
RULE_FILES = [ROOT / "Snakefile", *sorted((ROOT / "workflow" / "rules").glob("*.smk"))]


def rules() -> dict[str, tuple[Path, str]]:
    """Every rule of the workflow: name -> (its rule file, its rule's text). The rules of a loop
    (``for number in FIGURES: rule: name: f"plot_figure_{number}"``) count once, by the name
    before the loop variable (plot_figure), the name of their script and task."""
    found = {}
    for path in RULE_FILES:
        text = path.read_text()
        for m in re.finditer(r"^(?:rule|checkpoint) (\w+):|^( +)rule:\n\s+name:\n\s+f\"(\w+)_\{\w+\}\"$", text, re.M):
            indent = m.group(2) or ""
            end = re.search(rf"^ {{0,{len(indent)}}}\S", text[m.end():], re.M)  # the next line at the rule's level
            found[m.group(1) or m.group(3)] = (path, text[m.start():m.end() + (end.start() if end else len(text))])
    return found


def script_of(rule_text: str) -> str | None:
    m = re.search(r"^ +script:\n\s+\"\.\./scripts/([^\"]+)\"", rule_text, re.M)
    return m and m.group(1)


def fake_rule(rule, log, input=(), output=(), params=(), wildcards=()):
    """What run_rule reads of the `snakemake` object of a script."""
    return SimpleNamespace(rule=rule, log=[str(log)], input=dict(input), output=dict(output), params=dict(params),
                           wildcards=dict(wildcards))


# ------------------------------------------------------------------ one path: rule = script = task


def test_every_rule_runs_the_script_and_task_named_like_it():
    found = rules()
    assert {"all", "simulate_scenes", "numerics_work_precision", "build_manuscript"} <= set(found)
    for name, (path, text) in found.items():
        script = script_of(text)
        if script is None:  # a target rule: inputs only
            assert not re.search(r"^    (output|shell|run):", text, re.M), name
            continue
        assert script == f"{name}.py", f"rule {name} runs {script}"
        assert name in TASKS, f"rule {name} has no task"
        assert TASKS[name].__module__ == f"chainchaos.workflow.tasks.{path.stem}", name


def test_a_script_s_task_is_found_through_its_rule_file_alone():
    """A job imports only the task module named like its rule's file (the scripts' `scriptdir`)."""
    code = ("import sys, types\nfrom chainchaos.workflow.tasks import _family_and_task_name, _task\n"
            f"task = _task(*_family_and_task_name(types.SimpleNamespace(rule='plot_figure_4', scriptdir={str(SCRIPTS)!r})))\n"
            "print(task.__module__, sorted(m for m in sys.modules if m.startswith(('chainchaos.workflow.tasks.', 'numba'))))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split(" ", 1) == ["chainchaos.workflow.tasks.figures", "['chainchaos.workflow.tasks.figures']\n"]


def test_every_task_and_script_belongs_to_a_rule():
    scripted = {name for name, (_, text) in rules().items() if script_of(text)}
    assert set(TASKS) == scripted
    assert {p.stem for p in SCRIPTS.glob("*")} == scripted


@pytest.mark.parametrize("path", sorted(SCRIPTS.glob("*.py")), ids=lambda p: p.stem)
def test_a_script_is_the_call_into_the_package(path):
    body = ast.parse(path.read_text()).body
    if isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
        body = body[1:]  # the docstring
    assert [ast.unparse(node) for node in body] == ["from chainchaos.workflow.tasks import run_rule", "run_rule(snakemake)"]


# ------------------------------------------------------------------ run_rule


def test_run_rule_sends_stderr_and_a_failure_s_traceback_to_the_log(tmp_path, monkeypatch):
    def fails(inputs, outputs, params, wildcards):
        print(f"working on {wildcards['scene']}", file=sys.stderr)
        raise ValueError("bad value")

    monkeypatch.setitem(TASKS, "fails", fails)
    log = tmp_path / "fails.log"
    with pytest.raises(ValueError, match="bad value"):
        run_rule(fake_rule("fails", log, wildcards={"scene": "hertz_H1"}))
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
    code = ("import json, sys, types\nfrom chainchaos.workflow.tasks import run_rule\n"
            "run_rule(types.SimpleNamespace(**json.loads(sys.argv[1])))")
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
    run_rule(fake_rule("compute_ensemble", tmp_path / "log", output={"stats": str(out)},
                       params={"ensemble": block, "N": 12}))
    written = xr.load_dataset(out)
    expected = ensemble_dataset([2.0, 5.0], 4, 12, 7, "period_averaged")
    assert written.attrs["first_seed"] == 7 and written.attrs["convention"] == "period_averaged"
    for name in expected.data_vars:
        np.testing.assert_array_equal(written[name].values, expected[name].values)
    assert not np.array_equal(written["mean_participation"].values,
                              ensemble_dataset([2.0, 5.0], 4, 12)["mean_participation"].values)


def test_simulate_scenes_writes_each_scene_of_its_batch_to_its_own_file(tmp_path):
    """A batch job's scenes, integrated together, each in the file of its name: the scene file
    of the scene run alone (chainchaos.run.scenes.simulate), to the bit."""
    from chainchaos.output.io import chain_dataset, write_netcdf
    from chainchaos.run.scenes import SceneParameters, simulate
    from chainchaos.system.chain import random_chain

    chain = random_chain(879, 5.0, 12)
    chain_file = write_netcdf(chain_dataset(chain), tmp_path / "chain.nc")
    common = {"model": "fput", "t_final": 5.0, "dt": 0.01, "samples_per_decade": 4, "check_every": 100}
    scenes = [SceneParameters(energy=1.8, excited_site=6, observables=("participation", "mlce"), name="fput_H1.8", **common),
              SceneParameters(energy=0.5, excited_site=6, observables=("energy_density",), name="fput_H0.5", **common)]
    outputs = {s.name: str(tmp_path / "scenes" / f"{s.name}.nc") for s in scenes}
    run_rule(fake_rule("simulate_scenes", tmp_path / "log", input={"chain": str(chain_file), "kernels": []},
                       output=outputs, params={"scenes": scenes, "batch": "fput_1"}))
    for params in scenes:
        written, alone = xr.load_dataset(outputs[params.name]), simulate(chain, params)
        assert set(written.data_vars) == set(alone.data_vars), params.name
        for name in alone.data_vars:
            np.testing.assert_array_equal(written[name].values, alone[name].values, err_msg=f"{params.name}: {name}")
