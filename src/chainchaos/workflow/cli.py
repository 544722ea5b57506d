"""Command line: ``chainchaos chain | ensemble | simulate | check-model | bench`` and
``chainchaos --version`` (also ``python -m chainchaos``); ``stamp-search-archive``, a maintenance
command of the kept search, is left out of the help."""

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from chainchaos.errors import ChainFileError, ParameterError, SimulationError

DEFAULT_ALPHA = 5.0


def _checked(convert, kind: str, ok, allowed: str):
    """argparse type: ``convert(text)`` (e.g. a ``kind`` "a number") for which ``ok`` holds; an
    error names the text and what is ``allowed``."""

    def parse(text: str):
        try:
            value = convert(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not {kind}; allowed is {allowed}")
        if not ok(value):
            raise argparse.ArgumentTypeError(f"{text!r}: allowed is {allowed}")
        return value

    return parse


def _number(minimum: float = 0.0, strict: bool = True):
    """argparse type: a finite number > minimum (>= minimum when not ``strict``)."""
    return _checked(float, "a number", lambda v: np.isfinite(v) and (v > minimum if strict else v >= minimum),
                    f"a finite number {'>' if strict else '>='} {minimum:g}")


def _integer(minimum: int):
    """argparse type: an integer >= minimum."""
    return _checked(int, "an integer", lambda v: v >= minimum, f"an integer >= {minimum}")


_positive_float = _number(0.0)


def _output(text: str) -> str:
    """argparse type: a file path to write (not an existing directory, nor below a file)."""
    path = Path(text)
    if not text or path.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r} is {'a directory' if text else 'empty'}; allowed is a file path")
    parent = next((p for p in path.absolute().parents if p.exists()), None)
    if parent is not None and not parent.is_dir():
        raise argparse.ArgumentTypeError(f"{text!r}: {str(parent)!r} is a file, not a directory")
    return text


def _read(option: str, read, path):
    """``read(path)`` with a ChainFileError naming the option that gave the file."""
    try:
        return read(path)
    except ChainFileError as err:
        raise ChainFileError(f"option {option}: {err}") from err


def _alpha(args) -> float:
    return DEFAULT_ALPHA if args.alpha is None else args.alpha


def _cmd_chain(args) -> None:
    from chainchaos.records.io import chain_dataset, read_radii, write_netcdf
    from chainchaos.studies.search.selection import (
        SelectionCriteria,
        select_realization,
    )
    from chainchaos.system.chain import chain_from_radii, random_chain

    extra = {}
    if args.reference_radius is not None and not args.radii:
        raise ParameterError("reference_radius", args.reference_radius, "only together with --radii")
    if args.radii:
        chain = chain_from_radii(_read("--radii", read_radii, args.radii), args.reference_radius,
                                 args.wall_radius, args.alpha)
    elif args.search:
        chain, extra = select_realization(SelectionCriteria(alpha=_alpha(args), N=args.N, n_seeds=args.n_seeds))
        print(f"selected seed {extra['selection_seed']} among {extra['selection_candidates']} candidates "
              f"(score {extra['selection_score']:.4g})", file=sys.stderr)
    else:
        chain = random_chain(args.seed, _alpha(args), args.N, args.wall_radius)
    write_netcdf(chain_dataset(chain, extra), args.out)
    print(args.out)


def _cmd_ensemble(args) -> None:
    from chainchaos.records.io import ensemble_dataset, write_netcdf

    write_netcdf(ensemble_dataset(args.alpha, args.realizations, args.N, args.first_seed, args.convention), args.out)
    print(args.out)


def _lattice(args, model):
    """The lattice ``model`` runs on, from the options: a bead chain file (``--chain``), or a KG
    lattice drawn from ``--seed``, ``--W`` and ``--N``."""
    from chainchaos.records.io import read_chain
    from chainchaos.system.chain import kg_chain
    from chainchaos.system.models.base import LATTICES

    if model.lattice == "kg":
        if args.chain is not None:
            raise ParameterError("chain", args.chain, f"no chain file for model {model.name!r}, which runs on "
                                                      f"{LATTICES['kg']}: give --seed, --W and --N")
        if args.W is None:
            raise ParameterError("W", None, f"the disorder strength W of model {model.name!r}'s KG lattice")
        return kg_chain(args.seed, args.W, args.N)
    if args.chain is None:
        raise ParameterError("chain", None, f"a chain file for model {model.name!r} (write one with "
                                            "'chainchaos chain')")
    if args.W is not None:
        raise ParameterError("W", args.W, f"only for a model on a KG lattice, not {model.name!r}")
    return _read("--chain", read_chain, args.chain)


def _cmd_simulate(args) -> None:
    from chainchaos.engine.model_checks import load_model
    from chainchaos.records.io import write_netcdf
    from chainchaos.run.progress import ProgressReporter
    from chainchaos.run.scenes import SceneParameters, simulate

    model = load_model(args.model)
    chain = _lattice(args, model)
    observables = None if "all" in args.observables else tuple(args.observables)
    params = SceneParameters(model=model.name, energy=args.energy, t_final=args.t_final, dt=args.dt,
                             integrator=args.integrator, observables=observables,
                             excited_site=args.site, k4_sign=args.k4_sign, deviation_seed=args.deviation_seed,
                             samples_per_decade=args.samples_per_decade,
                             max_energy_error=args.max_energy_error, exponents=args.exponents,
                             gali_order=args.gali_order)
    ds = simulate(chain, params, progress=ProgressReporter(params.name, params.t_final))
    write_netcdf(ds, args.out)
    print(args.out)


def _cmd_check_model(args) -> None:
    from chainchaos.engine.model_checks import CHECKS, load_model

    model = load_model(args.model)  # runs every check; refuses with the failed one named
    checks = [c for c in CHECKS if model.has_site_law or not c.startswith("site")]
    print(f"model {model.name!r} ({model.identity}) passes: {', '.join(checks)}")


def _cmd_bench(args) -> None:
    from chainchaos.studies.numerics.bench import kernel_report

    report = kernel_report(args.model, args.integrator, args.N, args.steps, args.repeats)
    print(json.dumps(report, indent=2) if args.json else
          "\n".join(f"{key}: {value:.4g}" if isinstance(value, float) else f"{key}: {value}"
                    for key, value in report.items()))


def _cmd_stamp_search_archive(args) -> None:
    from chainchaos.records.kept import digest
    from chainchaos.workflow.stamp import stamp_search_archive

    try:
        settings = stamp_search_archive(args.archive)
    except (OSError, ValueError, KeyError) as err:
        raise ParameterError("archive", args.archive, f"a full search whose key can be read off it ({err})") from None
    print(f"{args.archive}: kept_settings_digest {digest(settings)}")


def scene_defaults() -> dict:
    """The defaults of ``SceneParameters``' fields: those ``chainchaos simulate`` shows and uses."""
    from dataclasses import MISSING, fields

    from chainchaos.run.scenes import SceneParameters

    return {f.name: f.default for f in fields(SceneParameters) if f.default is not MISSING}


def build_parser() -> argparse.ArgumentParser:
    from chainchaos.engine.integrators import SCHEMES
    from chainchaos.observe.registry import OBSERVABLES, model_observables
    from chainchaos.system.linear import CONVENTIONS
    from chainchaos.system.models import BOND_MODELS

    package = __import__("chainchaos")
    parser = argparse.ArgumentParser(
        prog="chainchaos", description=package.__doc__.split("\n\n")[0],
        epilog="Environment variables (Numba's cache, the SIMD width): docs/reference/environment.md. "
               "The paper's pipeline: snakemake --cores 2 all (README.md).")
    # where the package was imported from: another installed copy would run instead of a checkout's
    # (printed whole: argparse's version action wraps a long path at the terminal's width)
    version = f"chainchaos {package.__version__} ({Path(package.__file__).parent})"

    class Version(argparse.Action):
        def __call__(self, parser, namespace, values, option_string=None):
            print(version)
            parser.exit()

    parser.add_argument("--version", action=Version, nargs=0, help="print the version and where it was imported "
                        "from, then exit")
    user_commands = "chain,ensemble,simulate,check-model,bench"
    sub = parser.add_subparsers(dest="command", required=True, metavar=f"{{{user_commands}}}")

    p = sub.add_parser("chain", help="write a chain file (NetCDF)",
                       description="Write a chain file from --seed/--alpha, from --radii FILE (one radius "
                                   "per line, any unit), or by the linear rule of the realization search "
                                   "(docs/conventions.md#realization). The radii of a chain file are in units "
                                   "of its R_ref: written one per line and read back with --radii FILE "
                                   "--reference-radius 1 --alpha ALPHA they give the same chain.")
    source = p.add_mutually_exclusive_group()
    source.add_argument("--radii", metavar="FILE", help="text file with one radius per line")
    source.add_argument("--search", action="store_true", help="scan seeds for the paper-like realization")
    p.add_argument("--seed", type=_integer(0), default=0, help="seed of numpy.random.default_rng (default 0)")
    p.add_argument("--alpha", type=_number(1.0, strict=False), default=None,
                   help=f"disorder strength max R / min R (default {DEFAULT_ALPHA:g}; with --radii: max/min "
                        "of the file's radii)")
    p.add_argument("--reference-radius", type=_positive_float, metavar="R",
                   help="with --radii: the radius R_ref that becomes 1, in the file's unit (default (min + max)/2 "
                        "of the file's radii; 1 for radii taken from a chain file)")
    p.add_argument("--N", type=_integer(2), default=40, help="number of beads (default 40)")
    p.add_argument("--n-seeds", type=_integer(1), default=10000, help="seeds scanned by --search (default 10000)")
    p.add_argument("--wall-radius", type=_positive_float, default=1.0,
                   help="reduced radius of the wall beads (default 1)")
    p.add_argument("--out", required=True, type=_output, help="output NetCDF file")
    p.set_defaults(func=_cmd_chain)

    p = sub.add_parser("ensemble", help="participation-number statistics over realizations (Fig. 1a)")
    p.add_argument("--alpha", type=_number(1.0, strict=False), nargs="+", required=True,
                   help="disorder strengths (each >= 1)")
    p.add_argument("--realizations", type=_integer(2), default=1000, help="realizations per alpha (default 1000)")
    p.add_argument("--N", type=_integer(2), default=40, help="number of beads (default 40)")
    p.add_argument("--first-seed", type=_integer(0), default=0, help="seed of the first realization (default 0)")
    p.add_argument("--convention", choices=CONVENTIONS, default="potential",
                   help="participation-number convention (default potential)")
    p.add_argument("--out", required=True, type=_output, help="output NetCDF file")
    p.set_defaults(func=_cmd_ensemble)

    models = ", ".join(BOND_MODELS)
    scene = scene_defaults()
    p = sub.add_parser("simulate", help="integrate one scene of any model",
                       description="Integrate one scene (model, energy) and write its observables as NetCDF. "
                                   "A bead model runs on a chain file (--chain), a Klein-Gordon model on the KG "
                                   "lattice of --seed, --W and --N. Progress goes to stderr.")
    p.add_argument("--model", required=True, metavar="MODEL",
                   help=f"a registered model ({models}) or one of your own: module:NAME or file.py:NAME")
    p.add_argument("--chain", help="bead models: chain file written by 'chainchaos chain'")
    p.add_argument("--W", type=_positive_float, help="KG models: disorder strength W of the KG lattice")
    p.add_argument("--seed", type=_integer(0), default=0, help="KG models: seed of the lattice (default 0)")
    p.add_argument("--N", type=_integer(2), default=40, help="KG models: number of sites (default 40)")
    p.add_argument("--energy", required=True, type=_positive_float, help="total energy H")
    p.add_argument("--t-final", required=True, type=_positive_float, help="final time, in the model's time unit (docs/conventions.md)")
    p.add_argument("--dt", type=_positive_float, default=5e-4, help="time step (default %(default)s, the paper's)")
    p.add_argument("--integrator", choices=sorted(SCHEMES), default=scene["integrator"],
                   help="splitting scheme (default %(default)s)")
    p.add_argument("--observables", nargs="+", default=["all"], choices=["all", *OBSERVABLES],
                   metavar="NAME", help=f"observables to compute: {', '.join(OBSERVABLES)} (default all: the "
                                        f"model's own, e.g. for hertz {', '.join(model_observables('hertz'))}; the "
                                        f"others when named)")
    p.add_argument("--exponents", type=_integer(0), default=scene["exponents"],
                   help="Lyapunov exponents of lyapunov_spectrum and ks_entropy (default %(default)s: all 2N)")
    p.add_argument("--gali-order", type=_integer(2), default=scene["gali_order"],
                   help="k of GALI_k for log_gali (default %(default)s)")
    p.add_argument("--site", type=_integer(1), default=scene["excited_site"],
                   help="excited bead or site, 1..N (default %(default)s)")
    p.add_argument("--k4-sign", type=float, choices=[1.0, -1.0], default=scene["k4_sign"],
                   help="sign of K4: +1 the paper's, -1 the Taylor expansion of Hertz (default %(default)s)")
    p.add_argument("--deviation-seed", type=_integer(0), default=scene["deviation_seed"],
                   help="seed of the initial deviation vector (default %(default)s)")
    p.add_argument("--samples-per-decade", type=_integer(1), default=scene["samples_per_decade"],
                   help="log-spaced samples per decade (default %(default)s)")
    p.add_argument("--max-energy-error", type=_positive_float, default=scene["max_energy_error"],
                   help="stop when the relative energy error exceeds this (default %(default)s)")
    p.add_argument("--out", required=True, type=_output, help="output NetCDF file")
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("check-model", help="check a model of your own before running it",
                       description="Run the checks a model passes before the engines run it (force = dV/dD, "
                                   "stiffness, rest, the vector lanes: chainchaos.engine.model_checks.CHECKS) and "
                                   "say which one fails.")
    p.add_argument("model", help="module:NAME or file.py:NAME (or a registered name)")
    p.set_defaults(func=_cmd_check_model)

    p = sub.add_parser("bench", help="nanoseconds per step of the kernel, with and without tangent dynamics")
    p.add_argument("--model", choices=sorted(BOND_MODELS), default="hertz")
    p.add_argument("--integrator", choices=sorted(SCHEMES), default="SRKN6b")
    p.add_argument("--N", type=_integer(2), default=40, help="number of beads (default 40)")
    p.add_argument("--steps", type=_integer(1), default=10000, help="steps per timing (default 10000)")
    p.add_argument("--repeats", type=_integer(1), default=50, help="timings; the best is reported (default 50)")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(func=_cmd_bench)

    p = sub.add_parser("stamp-search-archive",  # maintenance: not in the help's list
                       description="Write into an archived full search (snakemake keep --config keep=search_full) the settings that "
                                   "determine it and its result version (chainchaos.records.kept), read off what "
                                   "the file records and the config/config.yaml of the commit it records; its "
                                   "variables stay byte for byte. Refuses when the statements' code changed since "
                                   "that commit (chainchaos.workflow.stamp.stamp_search_archive). "
                                   "Run from the git checkout.")
    p.add_argument("archive", nargs="?", default="data/search/search_full.nc",
                   help="the archived full search (default data/search/search_full.nc)")
    p.set_defaults(func=_cmd_stamp_search_archive)
    return parser


#: Option of a parameter whose name differs from the option's (ParameterError.name -> dest).
OPTION_OF_PARAMETER = {"excited_site": "site", "K4_sign": "k4_sign", "n_realizations": "realizations",
                       "n_steps": "steps", "radius": "radii"}


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        args.func(args)
    except (ParameterError, ChainFileError, SimulationError) as err:
        dest = OPTION_OF_PARAMETER.get(getattr(err, "name", ""), getattr(err, "name", ""))
        option = f"option --{dest.replace('_', '-')}: " if dest and hasattr(args, dest) else ""
        print(f"chainchaos {args.command}: error: {option}{err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
