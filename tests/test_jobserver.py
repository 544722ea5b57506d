"""The job server (chainchaos.workflow.jobserver): a job handed to a forked worker runs as it would
in its own process (its standard streams, environment, directory and exit status), its worker ends
with the job's process, the server with the process that started it; a job without a server, or
whose environment differs from the server's, runs in its own process (``submit`` returns None)."""

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

from chainchaos.workflow import jobserver

HERE = Path(__file__).resolve().parent


# ---- what the workers run (imported there by this module's name, from the job's sys.path)


def report(path):
    Path(path).write_text(json.dumps({"pid": os.getpid(), "cwd": os.getcwd(),
                                      "marker": os.environ.get("CHAINCHAOS_TEST_MARKER")}))
    print("out of the worker")
    print("err of the worker", file=sys.stderr)


def fail(kind):
    if kind == "exception":
        raise ValueError("bad value")
    raise SystemExit(3 if kind == "three" else kind)


def sleep_and_tell(path):
    Path(path).write_text(str(os.getpid()))
    time.sleep(120)


# ---- helpers


@pytest.fixture(scope="module")
def server():
    """A server started as Snakemake's onstart starts it, for jobs of one thread."""
    with pytest.MonkeyPatch.context() as monkeypatch:
        for name in jobserver.THREAD_VARIABLES:
            monkeypatch.setenv(name, "1")  # what Snakemake gives a job of one thread
        monkeypatch.setenv("CHAINCHAOS_TEST_MARKER", "from the run")
        monkeypatch.delenv("PYTEST_CURRENT_TEST", raising=False)  # pytest's, which changes with each phase
        running = jobserver.start()
        running.environ = dict(os.environ)  # the server's, as a job inherits it from Snakemake
        assert jobserver.wait_until_ready(running), (running.directory / "server.log").read_text()
        yield running
        running.stop()


def submit(*call):
    os.environ.pop("PYTEST_CURRENT_TEST", None)
    return jobserver.submit(__name__, *call)


def ended(pid: int, timeout: float) -> bool:
    """Whether process ``pid`` is gone (or a zombie) within ``timeout`` seconds."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            if Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] == "Z":
                return True
        except (FileNotFoundError, ProcessLookupError):
            return True
        time.sleep(0.1)
    return False


# ---- tests


def test_a_job_runs_in_a_worker_with_its_streams_environment_and_directory(server, tmp_path, capfd, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert submit("report", "report.json") == 0
    seen = json.loads((tmp_path / "report.json").read_text())
    assert seen["pid"] not in (os.getpid(), server.process.pid)
    assert seen["cwd"] == str(tmp_path) and seen["marker"] == "from the run"
    out, err = capfd.readouterr()
    assert "out of the worker" in out and "err of the worker" in err


@pytest.mark.parametrize("kind, status, text", [("exception", 1, "ValueError: bad value"),
                                                ("a message", 1, "a message"), ("three", 3, "")])
def test_a_failing_job_ends_with_its_exit_status_and_its_error(server, capfd, kind, status, text):
    assert submit("fail", kind) == status
    assert text in capfd.readouterr().err


def test_a_job_whose_environment_differs_from_the_server_s_runs_in_its_own_process(server, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("TMPDIR", str(tmp_path))  # Snakemake's per-job temporary directory: taken over
    assert submit("report", "taken.json") == 0
    monkeypatch.setenv("OMP_NUM_THREADS", "4")  # a job of four threads: the libraries read it when imported
    assert submit("report", "refused.json") is None
    assert not (tmp_path / "refused.json").exists()


def test_without_a_server_a_job_runs_in_its_own_process(tmp_path, monkeypatch):
    monkeypatch.delenv(jobserver.ADDRESS_VARIABLE, raising=False)
    assert submit("report", str(tmp_path / "a.json")) is None
    monkeypatch.setenv(jobserver.ADDRESS_VARIABLE, str(tmp_path / "gone" / "socket"))  # a server that ended
    assert submit("report", str(tmp_path / "b.json")) is None
    assert not list(tmp_path.glob("*.json"))


def test_a_worker_ends_when_its_job_s_process_is_killed(server, tmp_path):
    told = tmp_path / "worker.pid"
    code = (f"import sys; sys.path.insert(0, {str(HERE)!r}); from chainchaos.workflow import jobserver; "
            f"jobserver.submit({__name__!r}, 'sleep_and_tell', {str(told)!r})")
    job = subprocess.Popen([sys.executable, "-c", code], env=server.environ)
    end = time.monotonic() + 60
    while not (told.exists() and told.read_text()) and time.monotonic() < end:
        time.sleep(0.05)
    worker = int(told.read_text())
    job.kill()
    job.wait()
    assert ended(worker, 10)


def test_the_server_ends_and_leaves_nothing_when_the_process_that_started_it_is_gone(tmp_path):
    code = ("from chainchaos.workflow import jobserver; s = jobserver.start(); "
            "print(s.process.pid, s.directory, flush=True)")  # ends without stopping it
    pid, directory = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                    timeout=60, check=True).stdout.split()
    assert ended(int(pid), 60)
    assert not Path(directory).exists()
