"""A fork server for the workflow's jobs: the libraries imported once, a forked worker per job.

Every job of the workflow is a fresh Python process, and before it does any work it imports NumPy,
xarray and pandas, Numba (whose CPU target then loads its registries and SciPy's BLAS on the
first kernel it loads) and, to draw, matplotlib: about a second of every job, as much as the
work of most jobs of the quick scale. For a local run the Snakefile's ``onstart`` starts one
server process (:func:`start`) that imports all of that once; a job whose task reads, reduces or
draws (``tasks.run_rule``, ``tasks.SERVED_TASKS``) then hands it to the server (:func:`submit`),
which forks a worker that runs it with the job's own standard output and error, environment and
working directory, and the job exits with the worker's status. The work and its results are
those of the job run alone: the same task function, the same Numba kernels from the same on-disk
cache.

A job runs in its own process instead (``submit`` returns None) when there is no server (a
cluster run, where each job runs on its node; ``--no-hooks``; the server's first seconds, while it
imports) or when its environment differs from the server's in a variable other than those of
:data:`PER_JOB_VARIABLES` (a job with more than one thread, say): the libraries read theirs when
imported. A worker ends when its job's process does (an interrupted run leaves no worker
running); the server ends with the run (:func:`Server.stop`, from ``onsuccess`` and ``onerror``)
or when the Snakemake process that started it is gone. A job's ``benchmark:`` file keeps its wall
time; its CPU time and memory are those of the waiting job process, not of the worker.
"""

import importlib
import os
import pickle
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import traceback
from pathlib import Path

#: The environment variable that gives a job the server's socket (set by :func:`start`).
ADDRESS_VARIABLE = "CHAINCHAOS_JOB_SERVER"

#: Variables that may differ between the server and a job, which the worker then takes from the
#: job: a shell's own, and the temporary directory Snakemake gives each job (its ``tmpdir``).
PER_JOB_VARIABLES = frozenset({"_", "SHLVL", "PWD", "OLDPWD", "TMPDIR", "TMP", "TEMP", "TEMPDIR"})

#: The threads of the linear-algebra libraries, which Snakemake sets to a job's ``threads``
#: (every rule here: 1) and the libraries read when imported: the server is started with them at 1.
THREAD_VARIABLES = ("OMP_NUM_THREADS", "GOTO_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")

#: Seconds a job waits for the server to take it before running in its own process.
CONNECT_TIMEOUT = 5.0

_HEADER = struct.Struct("!Q")  # the length of a pickled message
_STREAMS = 2  # a job's standard output and error, passed to its worker as file descriptors


def _preload(modules) -> None:
    """Import ``modules`` (and what they import) and matplotlib's and Snakemake's parts that a
    job's first call would, and have Numba's CPU target load its registries."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot  # the font manager and the Agg and PDF backends
    import snakemake.script  # noqa: F401 (what unpickles a job's ``snakemake`` object)

    for module in modules:
        importlib.import_module(module)
    try:  # what loading the first kernel from the cache does in each job otherwise
        from numba.core.registry import cpu_target

        cpu_target.target_context.refresh()
    except (ImportError, AttributeError):
        pass


def _comparable(environ) -> dict:
    return {key: value for key, value in environ.items() if key not in PER_JOB_VARIABLES}


def _receive(conn: socket.socket, size: int) -> bytes:
    data = bytearray()
    while len(data) < size:
        chunk = conn.recv(size - len(data))
        if not chunk:
            raise ConnectionError("the job's process closed the connection")
        data += chunk
    return bytes(data)


def _send_message(conn: socket.socket, obj) -> None:
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    conn.sendall(_HEADER.pack(len(data)) + data)


def _receive_message(conn: socket.socket):
    (size,) = _HEADER.unpack(_receive(conn, _HEADER.size))
    return pickle.loads(_receive(conn, size))


def _exit_status(code) -> int:
    """The process exit status of ``SystemExit(code)``, printing a message code as Python does."""
    if code is None:
        return 0
    if isinstance(code, int):
        return code & 0xFF
    print(code, file=sys.stderr)
    return 1


def _work(conn: socket.socket, streams: list[int], request: dict) -> None:
    """In the forked worker: become the job (its streams, environment, directory), run its call
    and send the exit status. Never returns."""
    status = 1
    try:
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGCHLD):
            signal.signal(sig, signal.SIG_DFL)
        for fd, target in zip(streams, (1, 2)):
            os.dup2(fd, target)
            os.close(fd)
        os.environ.clear()
        os.environ.update(request["environ"])
        tempfile.tempdir = None  # read again from the job's TMPDIR
        os.chdir(request["cwd"])
        sys.path[:0] = [entry for entry in request["path"] if entry not in sys.path]
        sys.argv = request["argv"]

        def end_with_the_job():  # the job's process closes the connection only when it ends
            try:
                conn.recv(1)
            finally:
                os._exit(1)

        _send_message(conn, {"refused": None})
        threading.Thread(target=end_with_the_job, daemon=True).start()
        module, name = request["call"]
        try:
            getattr(__import__(module, fromlist=[name]), name)(*request["args"])
            status = 0
        except SystemExit as end:
            status = _exit_status(end.code)
        except BaseException:  # noqa: BLE001 (reported as the job's own process would: traceback, status 1)
            traceback.print_exc()
            status = 1
        sys.stdout.flush()
        sys.stderr.flush()
        conn.sendall(bytes([status]))
    finally:
        os._exit(status)


def serve(address: str, parent: int, modules=()) -> None:
    """Import ``modules``, then fork a worker for every job that connects to ``address`` (a Unix
    socket), until SIGTERM or until process ``parent`` (the run's Snakemake) is gone."""
    _preload(modules)
    environ = _comparable(os.environ)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(address + ".binding")
    listener.listen(16)
    os.rename(address + ".binding", address)  # a job connects only once the server accepts
    listener.settimeout(1.0)
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    served = 0
    try:
        while not stop.is_set() and os.getppid() == parent:
            while True:  # reap finished workers
                try:
                    if os.waitpid(-1, os.WNOHANG)[0] == 0:
                        break
                except ChildProcessError:
                    break
            try:
                conn, _ = listener.accept()
            except (TimeoutError, InterruptedError):
                continue
            with conn:
                streams = []
                try:
                    conn.settimeout(CONNECT_TIMEOUT)  # a job that connects and sends nothing holds no one up
                    _, streams, _, _ = socket.recv_fds(conn, 1, _STREAMS)
                    request = _receive_message(conn)
                    conn.settimeout(None)
                    theirs = _comparable(request["environ"])
                    differing = sorted(k for k in environ.keys() | theirs.keys() if environ.get(k) != theirs.get(k))
                    if len(streams) != _STREAMS or differing:
                        _send_message(conn, {"refused": differing or ["the job's streams"]})
                    elif os.fork() == 0:
                        listener.close()
                        _work(conn, streams, request)
                    else:
                        served += 1
                except (OSError, ConnectionError, pickle.UnpicklingError, EOFError, AttributeError, ImportError):
                    continue  # the job's process runs the job itself
                finally:
                    for fd in streams:
                        os.close(fd)
    finally:
        listener.close()
        Path(address).unlink(missing_ok=True)
        print(f"served {served} jobs", flush=True)
        if os.getppid() != parent:  # no one is left to stop it: remove its directory too
            shutil.rmtree(Path(address).parent, ignore_errors=True)


def submit(module: str, name: str, *args) -> int | None:
    """Run ``module.name(*args)`` in a worker of the run's server as this process would: with its
    standard output and error, environment, directory and ``sys.path``. Returns the worker's exit
    status, or None when no server takes the job (the caller then runs it itself)."""
    address = os.environ.get(ADDRESS_VARIABLE)
    if not address or not hasattr(socket, "send_fds") or not os.path.exists(address):
        return None
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        conn.settimeout(CONNECT_TIMEOUT)
        conn.connect(address)
        conn.settimeout(None)
        sys.stdout.flush()
        sys.stderr.flush()
        socket.send_fds(conn, [b"j"], [sys.stdout.fileno(), sys.stderr.fileno()])
        _send_message(conn, {"call": (module, name), "args": args, "environ": dict(os.environ),
                             "cwd": os.getcwd(), "path": list(sys.path), "argv": list(sys.argv)})
        if _receive_message(conn)["refused"] is not None:
            conn.close()
            return None
    except (OSError, ConnectionError, EOFError, pickle.PicklingError, TypeError, AttributeError):
        conn.close()
        return None
    with conn:
        status = conn.recv(1)
    if not status:
        print(f"chainchaos job server: the worker of {module}.{name} ended without a status "
              "(killed, or a crash of the interpreter)", file=sys.stderr)
        return 1
    return status[0]


class Server:
    """A running server (:func:`start`): its process, socket and directory."""

    def __init__(self, process: subprocess.Popen, directory: Path):
        self.process, self.directory = process, directory
        self.address = str(directory / "socket")

    def stop(self) -> str:
        """End the server and remove its directory; returns what it reported ("served N jobs")."""
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        report = (self.directory / "server.log").read_text().strip().splitlines()
        for path in self.directory.iterdir():
            path.unlink()
        self.directory.rmdir()
        if os.environ.get(ADDRESS_VARIABLE) == self.address:
            del os.environ[ADDRESS_VARIABLE]
        return report[-1] if report else f"ended with status {self.process.returncode}"


def start(modules=()) -> Server:
    """Start a server for the jobs this process (Snakemake's) starts afterwards, which imports
    ``modules`` (those of the calls the jobs submit): its socket in a new private directory, its
    address in the environment they inherit (:data:`ADDRESS_VARIABLE`)."""
    directory = Path(tempfile.mkdtemp(prefix="chainchaos-jobs-"))
    address = str(directory / "socket")
    os.environ[ADDRESS_VARIABLE] = address
    with open(directory / "server.log", "w") as log:
        process = subprocess.Popen([sys.executable, "-m", __name__, address, str(os.getpid()), *modules],
                                   env={**os.environ, **dict.fromkeys(THREAD_VARIABLES, "1")},
                                   stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT)
    return Server(process, directory)


def wait_until_ready(server: Server, timeout: float = 60.0) -> bool:
    """Whether the server accepts jobs within ``timeout`` seconds (False: it ended or is slow)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end and server.process.poll() is None:
        if os.path.exists(server.address):
            return True
        time.sleep(0.05)
    return os.path.exists(server.address)


if __name__ == "__main__":
    serve(sys.argv[1], int(sys.argv[2]), sys.argv[3:])
