"""Provenance recorded in every NetCDF file: package version, git commit, parameters, and the
machine: CPU model, its vector extensions, Numba's code-generation target and library versions.

The numbers of a file do not depend on the CPU (chainchaos.kernels.exactmath): the machine is recorded so
that a difference between two files can be traced to its build.
"""

import json
import platform
import subprocess
from functools import lru_cache
from pathlib import Path

from chainchaos.project import package_checkout

#: x86 vector extensions reported, in this order, when the CPU has them (/proc/cpuinfo "flags").
VECTOR_FLAGS = ("sse2", "sse4_1", "sse4_2", "avx", "avx2", "fma", "avx512f", "avx512dq", "avx512cd",
                "avx512bw", "avx512vl", "avx512ifma", "avx512vbmi", "avx512_vbmi2", "avx512_vnni",
                "avx512_bitalg", "avx512_vpopcntdq", "avx512_bf16", "avx512_fp16", "avx_vnni", "amx_tile")

LIBRARIES = ("numpy", "scipy", "numba", "llvmlite", "xarray")

#: Environment variables, set before Python starts, that make NumPy, Numba and OpenBLAS on an
#: AVX-512 machine run the code they would run on an AVX2-only x86-64 CPU (with FMA). Give such a
#: process its own NUMBA_CACHE_DIR too: kernels compiled for one target must not be loaded by another.
EMULATED_AVX2 = {
    "NPY_DISABLE_CPU_FEATURES": "X86_V4 AVX512_ICL AVX512_SPR",  # NumPy's AVX-512 dispatch targets
    "NUMBA_CPU_NAME": "haswell",
    "NUMBA_CPU_FEATURES": "",  # empty: the features LLVM's "haswell" implies (no AVX-512)
    "OPENBLAS_CORETYPE": "Haswell",  # honoured by NumPy's and SciPy's bundled OpenBLAS alike
}


def git_commit() -> str:
    """The checkout's commit, with ``-dirty`` when tracked files differ, or ``unknown``."""
    root = package_checkout()
    if root is None:
        return "unknown"
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True, timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True, timeout=10).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("-dirty" if dirty else "")


def _cpuinfo_field(name: str, cpuinfo: str = "/proc/cpuinfo") -> str:
    """The value of the first ``name : value`` line of /proc/cpuinfo, or "" (no such file or line)."""
    try:
        text = Path(cpuinfo).read_text(encoding="utf-8", errors="replace")
    except OSError:
        return ""
    for line in text.splitlines():
        key, sep, value = line.partition(":")
        if sep and key.strip() == name:
            return value.strip()
    return ""


@lru_cache(maxsize=1)
def cpu_model() -> str:
    """The CPU's model name (/proc/cpuinfo), else platform.processor(), else ``unknown``."""
    return _cpuinfo_field("model name") or platform.processor() or "unknown"


@lru_cache(maxsize=1)
def cpu_vector_extensions() -> str:
    """The CPU's x86 vector extensions among VECTOR_FLAGS, space-separated ("" if not known)."""
    flags = set(_cpuinfo_field("flags").split())
    return " ".join(flag for flag in VECTOR_FLAGS if flag in flags)


def numba_target_cpu() -> str:
    """The CPU Numba compiles for: NUMBA_CPU_NAME if set, else LLVM's name of the host CPU."""
    from numba import config

    if config.CPU_NAME:
        return str(config.CPU_NAME)
    import llvmlite.binding as llvm

    return llvm.get_host_cpu_name()


@lru_cache(maxsize=1)
def library_versions() -> dict:
    """``<name>_version`` of python and of every library in LIBRARIES that is installed."""
    from importlib.metadata import PackageNotFoundError, version

    versions = {"python_version": platform.python_version()}
    for name in LIBRARIES:
        try:
            versions[f"{name}_version"] = version(name)
        except PackageNotFoundError:
            versions[f"{name}_version"] = "not installed"
    return versions


def numpy_simd_targets() -> str:
    """NumPy's SIMD targets on this CPU, space-separated: those of its build's baseline and the
    dispatch targets it found (``numpy.show_config(mode="dicts")["SIMD Extensions"]``, the public
    way); "" when NumPy does not tell."""
    import numpy as np

    try:
        simd = np.show_config(mode="dicts")["SIMD Extensions"]
    except (KeyError, TypeError):
        return ""
    return " ".join([*simd.get("baseline", []), *simd.get("found", [])])


def machine_attrs() -> dict:
    """The machine that wrote a file: CPU model, vector extensions, NumPy's SIMD targets, Numba's
    target CPU and the library versions."""
    return {
        "cpu_model": cpu_model(),
        "cpu_vector_extensions": cpu_vector_extensions(),
        "numpy_simd_targets": numpy_simd_targets(),
        "numba_target_cpu": numba_target_cpu(),
        **library_versions(),
    }


def machine_line(attrs: dict | None = None) -> str:
    """One line naming a machine: CPU model, its vector extensions and the CPU Numba compiles for;
    by default this machine's, with the SIMD width of the engines (benchmarks), else the one whose
    :func:`machine_attrs` are ``attrs`` (a result file's provenance)."""
    width = ""
    if attrs is None:
        from chainchaos.kernels.simd import LANES

        attrs = {"cpu_model": cpu_model(), "cpu_vector_extensions": cpu_vector_extensions(),
                 "numba_target_cpu": numba_target_cpu()}
        width = f" | SIMD width: {LANES} doubles"
    extensions = attrs.get("cpu_vector_extensions") or "unknown"
    return (f"CPU: {attrs.get('cpu_model') or '?'} | vector extensions: {extensions} | "
            f"Numba target: {attrs.get('numba_target_cpu') or '?'}{width}")


def provenance_attrs(parameters: dict) -> dict:
    """Package version, git commit, ``parameters`` as JSON and the machine (the CF and ACDD global
    attributes are added where the file is written, chainchaos.records.cf)."""
    from chainchaos import __version__

    return {
        "chainchaos_version": __version__,
        "git_commit": git_commit(),
        "parameters": json.dumps(parameters, sort_keys=True),
        **machine_attrs(),
    }
