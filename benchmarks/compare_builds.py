"""Run one Python snippet under emulated CPU builds and compare its NetCDF outputs bit for bit.

    python benchmarks/compare_builds.py [--builds avx512 avx2] [--snippet FILE] [--workdir DIR]

Every build is a set of environment variables set before Python starts, which make NumPy, Numba
and OpenBLAS pick the code they would pick on another x86-64 CPU:

    native   nothing changed: this machine's choices
    avx512   OpenBLAS' SkylakeX kernels (an AVX-512 Intel CPU); NumPy and Numba as on this machine
    avx2     chainchaos.records.provenance.EMULATED_AVX2: NumPy without its AVX-512 dispatch targets
             (NPY_DISABLE_CPU_FEATURES), Numba/LLVM code for Haswell with Haswell's features only
             (NUMBA_CPU_NAME, NUMBA_CPU_FEATURES), OpenBLAS' Haswell kernels (OPENBLAS_CORETYPE,
             honoured by NumPy's and SciPy's bundled OpenBLAS alike)
    numpy_avx2, numba_haswell, blas_haswell
             avx512 with one of the three changes of avx2, to tell which library makes a difference
    sse4     a CPU without AVX and FMA (x86-64-v2), down to glibc's libm (GLIBC_TUNABLES); the
             package assumes FMA for the C library's log10, pow and log (chainchaos.kernels.exactmath)

Each build gets its own Numba cache (``<workdir>/numba_cache/<build>/<kernel key>``), so kernels
compiled for one target are never loaded by another. The snippet is run as
``python SNIPPET OUTDIR`` and writes NetCDF files into OUTDIR; the default snippet (DEFAULT_SNIPPET)
writes the chain file of random_chain(5346, 5.0, 40), one Hertz and one FPUT scene with every
observable, and a small Fig. 1(a) ensemble. Then every data variable and coordinate of every file is
compared with np.array_equal between the first build and each other one, and what differs is
printed: number of differing values, the largest absolute, relative and ULP difference. Attributes
that differ are listed too, except the machine provenance (which names the build).

Exits 0 when all files are bit-identical, 1 otherwise.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

from chainchaos.kernels.cache import kernel_key  # noqa: E402  (does not import numba)
from chainchaos.records.provenance import (  # noqa: E402
    EMULATED_AVX2,
    cpu_model,
    cpu_vector_extensions,
)

BUILDS = {
    "native": {},
    "avx512": {"OPENBLAS_CORETYPE": "SkylakeX"},
    "avx2": EMULATED_AVX2,
    # avx512 with one of the three changes of avx2, to tell which library makes a difference
    "numpy_avx2": {"OPENBLAS_CORETYPE": "SkylakeX", "NPY_DISABLE_CPU_FEATURES": "X86_V4 AVX512_ICL AVX512_SPR"},
    "numba_haswell": {"OPENBLAS_CORETYPE": "SkylakeX", "NUMBA_CPU_NAME": "haswell", "NUMBA_CPU_FEATURES": ""},
    "blas_haswell": {"OPENBLAS_CORETYPE": "Haswell"},
    # a CPU without AVX and FMA (x86-64-v2): glibc's libm too runs its variants without FMA
    "sse4": {
        "NPY_DISABLE_CPU_FEATURES": "X86_V3 X86_V4 AVX512_ICL AVX512_SPR",
        "NUMBA_CPU_NAME": "nehalem",
        "NUMBA_CPU_FEATURES": "",
        "OPENBLAS_CORETYPE": "Nehalem",
        "GLIBC_TUNABLES": "glibc.cpu.hwcaps=-AVX,-AVX2,-FMA,-AVX512F",
    },
}

#: Attributes that describe the build or the run, not the data.
MACHINE_ATTRS = {"cpu_model", "cpu_vector_extensions", "numpy_simd_targets", "numba_target_cpu",
                 "git_commit", "python_version", "numpy_version", "scipy_version", "numba_version",
                 "llvmlite_version", "xarray_version"}

DEFAULT_SNIPPET = textwrap.dedent('''
    """Chain file, a Hertz and an FPUT scene with every observable, a small ensemble."""
    import sys
    from pathlib import Path

    from chainchaos.observe.registry import model_observables
    from chainchaos.records.io import chain_dataset, ensemble_dataset, write_netcdf
    from chainchaos.run.scenes import SceneParameters, simulate
    from chainchaos.system.chain import random_chain

    out = Path(sys.argv[1])
    chain = random_chain(5346, 5.0, 40)
    write_netcdf(chain_dataset(chain), out / "chain.nc")
    for model, energy in {"hertz": 3.0, "fput": 8.7381}.items():
        params = SceneParameters(model=model, energy=energy, t_final=1000.0, dt=0.005,
                                 observables=model_observables(model), samples_per_decade=10, t_first_sample=0.1)
        write_netcdf(simulate(chain, params), out / f"{model}.nc")
    write_netcdf(ensemble_dataset([2.0, 5.0], 100), out / "ensemble.nc")
''')


def build_environment(build: str, cache_root: Path) -> dict:
    """os.environ with the build's variables and its own Numba cache directory."""
    env = {k: v for k, v in os.environ.items()
           if k not in {"NUMBA_CACHE_DIR", *(key for b in BUILDS.values() for key in b)}}
    env.update(BUILDS[build])
    env["NUMBA_CACHE_DIR"] = str(cache_root / build / kernel_key())
    return env


def run_build(build: str, snippet: Path, out: Path, cache_root: Path) -> None:
    """Run ``python snippet out`` in the build's environment; exits with its output on failure."""
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.nc"):
        old.unlink()
    done = subprocess.run([sys.executable, str(snippet), str(out)], cwd=ROOT, capture_output=True, text=True,
                          env=build_environment(build, cache_root))
    if done.returncode != 0:
        sys.exit(f"build {build}: the snippet failed (exit {done.returncode}):\n{done.stdout}\n{done.stderr}")


def ulp_distance(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Number of float64 values between a and b (0 for equal values, also of opposite zero sign)."""
    def ordered(x):
        i = np.ascontiguousarray(x, dtype=np.float64).view(np.int64)
        return np.where(i < 0, np.int64(-(2**63)) - i, i)

    return np.abs(ordered(a) - ordered(b).astype(np.int64))


def describe_difference(a: np.ndarray, b: np.ndarray) -> str:
    """Count of differing values and the largest absolute, relative and ULP difference."""
    if a.shape != b.shape:
        return f"shapes differ: {a.shape} vs {b.shape}"
    if a.dtype.kind != "f" or b.dtype.kind != "f":
        differ = a != b
        return f"{int(differ.sum())} of {a.size} values differ"
    differ = ~((a == b) | (np.isnan(a) & np.isnan(b)))
    x, y = a[differ].astype(float), b[differ].astype(float)
    absolute = np.abs(x - y)
    scale = np.maximum(np.abs(x), np.abs(y))
    with np.errstate(divide="ignore", invalid="ignore"):
        relative = np.where(scale > 0, absolute / scale, 0.0)
    ulps = ulp_distance(x, y)
    return (f"{int(differ.sum())} of {a.size} values differ; max |diff| {np.nanmax(absolute):.3g}, "
            f"max rel {np.nanmax(relative):.3g}, max {int(ulps.max())} ulp")


def compare_files(path_a: Path, path_b: Path) -> list[str]:
    """One line per variable (data or coordinate) or attribute that is not identical."""
    import xarray as xr

    lines = []
    with xr.open_dataset(path_a, engine="netcdf4") as A, xr.open_dataset(path_b, engine="netcdf4") as B:
        names = sorted(set(A.variables) | set(B.variables))
        for name in names:
            if name not in A.variables or name not in B.variables:
                lines.append(f"  {name}: only in one build")
                continue
            a, b = A[name].values, B[name].values
            same = a.dtype == b.dtype and a.shape == b.shape and np.array_equal(
                a, b, equal_nan=a.dtype.kind == "f")
            if not same:
                lines.append(f"  {name}: {describe_difference(a, b)}")
        for key in sorted((set(A.attrs) | set(B.attrs)) - MACHINE_ATTRS):
            if str(A.attrs.get(key)) != str(B.attrs.get(key)):
                lines.append(f"  attribute {key}: {A.attrs.get(key)!r} vs {B.attrs.get(key)!r}")
    return lines


def build_description(path: Path) -> str:
    import xarray as xr

    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ", ".join(f"{k} = {ds.attrs.get(k, '?')}" for k in ("numpy_simd_targets", "numba_target_cpu"))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--builds", nargs="+", choices=sorted(BUILDS), default=["avx512", "avx2"],
                        help="builds to run; the first is the reference (default: avx512 avx2)")
    parser.add_argument("--snippet", type=Path, help="Python file run as 'python SNIPPET OUTDIR' "
                        "(default: the chain file, two scenes and an ensemble)")
    parser.add_argument("--workdir", type=Path, default=Path(tempfile.gettempdir()) / "chainchaos_compare_builds",
                        help="outputs in WORKDIR/<build>, Numba caches in WORKDIR/numba_cache")
    args = parser.parse_args(argv)
    if len(args.builds) < 2:
        parser.error("give at least two builds")

    print(f"CPU: {cpu_model()}")
    print(f"vector extensions: {cpu_vector_extensions()}")
    snippet = args.snippet
    if snippet is None:
        snippet = args.workdir / "snippet.py"
        snippet.parent.mkdir(parents=True, exist_ok=True)
        snippet.write_text(DEFAULT_SNIPPET)
    outputs = {}
    for build in args.builds:
        settings = " ".join(f"{k}={v!r}" for k, v in BUILDS[build].items()) or "(no variables)"
        print(f"running build {build}: {settings}", flush=True)
        outputs[build] = args.workdir / build
        run_build(build, snippet.resolve(), outputs[build], args.workdir / "numba_cache")

    reference, *others = args.builds
    files = sorted(p.name for p in outputs[reference].glob("*.nc"))
    identical = True
    for build in others:
        print(f"\n{reference} vs {build}")
        for name in files:
            a, b = outputs[reference] / name, outputs[build] / name
            if not b.is_file():
                print(f"{name}: missing in build {build}")
                identical = False
                continue
            lines = compare_files(a, b)
            identical &= not lines
            print(f"{name}: {'bit-identical' if not lines else 'DIFFERS'} "
                  f"({build_description(a)} | {build_description(b)})")
            for line in lines:
                print(line)
    print("\nall files bit-identical" if identical else "\nthe builds differ")
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main())
