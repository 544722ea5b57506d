"""NetCDF input and output: chain files, atomic writes (docs/conventions.md#data-contract)."""

import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from chainchaos.errors import ChainFileError
from chainchaos.records import cf, kept
from chainchaos.records.atomic import atomic_output
from chainchaos.records.provenance import provenance_attrs
from chainchaos.system.chain import GENERATOR, Chain
from chainchaos.system.linear import (
    mode_energy_density,
    normal_modes,
    participation_number,
)

CHAIN_VARIABLES = ("radius", "mass", "A", "delta", "K2", "K3", "K4", "frequency", "mode_shape",
                   "mode_participation")


def write_netcdf(ds: xr.Dataset, path, seal: bool = False) -> Path:
    """Write ``ds`` to ``path`` atomically, zlib-compressed, in the CF and ACDD conventions of
    chainchaos.records.cf (the same values; ``ds`` itself is not changed).

    Parameters
    ----------
    ds : xarray.Dataset
        The data and attributes to write.
    path : str or Path
        The file to write (replaced when it exists).
    seal : bool, optional
        Also record the checksum of the data as written (``chainchaos.records.kept.DATA_ATTR``),
        before the file appears: for a kept file, whose key ``ds`` carries.

    Returns
    -------
    Path
        ``path``.
    """
    out, encoding = cf.encoded(ds)
    with atomic_output(path) as tmp:
        out.to_netcdf(tmp, engine="netcdf4", encoding=encoding)
        if seal:
            kept.record_checksum(tmp)
    return Path(path)


def write_text(text: str, path) -> Path:
    """Write ``text`` to ``path`` atomically."""
    with atomic_output(path) as tmp:
        tmp.write_text(text, encoding="utf-8", newline="")
    return Path(path)


def chain_dataset(chain: Chain, extra_attrs: dict | None = None) -> xr.Dataset:
    """The chain file of the data contract: parameters, frequencies, modes, participation numbers."""
    omega, U = normal_modes(chain)
    N = chain.N
    coords = {"site": np.arange(1, N + 1), "bond": np.arange(1, N + 2), "mode": np.arange(1, N + 1)}
    dimless = {"units": "1"}
    P = participation_number(mode_energy_density(chain, omega, U, "potential"))
    P_avg = participation_number(mode_energy_density(chain, omega, U, "period_averaged"))
    ds = xr.Dataset(
        {
            "radius": ("site", chain.radius, {**dimless, "long_name": "bead radius R_n / R_ref"}),
            "mass": ("site", chain.mass, {**dimless, "long_name": "bead mass m_n = r_n^3"}),
            "A": ("bond", chain.A, {**dimless, "long_name": "Hertz contact coefficient A_n"}),
            "delta": ("bond", chain.delta, {**dimless, "long_name": "static overlap delta_n"}),
            "K2": ("bond", chain.K2, {**dimless, "long_name": "harmonic coefficient K2_n"}),
            "K3": ("bond", chain.K3, {**dimless, "long_name": "cubic coefficient K3_n"}),
            "K4": ("bond", chain.K4, {**dimless, "long_name": "quartic coefficient K4_n",
                                      "comment": f"K4_sign = {chain.k4_sign:+g}"}),
            "frequency": ("mode", omega, {**dimless, "long_name": "linear mode frequency omega_k / omega_max"}),
            "mode_shape": (("site", "mode"), U, {**dimless, "long_name": "mass-orthonormal mode shape U_nk"}),
            "mode_participation": ("mode", P, {**dimless, "long_name": "mode participation number",
                                               "comment": "P = 1/sum h_n^2, h from u = U_k, p = 0, bond energies split half-half"}),
            "mode_participation_period_averaged": ("mode", P_avg, {
                **dimless, "long_name": "mode participation number, period-averaged energy density"}),
        },
        coords=coords,
    )
    ds.site.attrs.update(long_name="bead index n", units="1")
    ds.bond.attrs.update(long_name="bond index (bond n joins beads n-1 and n)", units="1")
    ds.mode.attrs.update(long_name="mode number, by increasing frequency", units="1")
    params = {"alpha": chain.alpha, "seed": chain.seed, "N": N, "wall_radius": chain.wall_radius,
              "K4_sign": chain.k4_sign}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title="Disordered chain (chainchaos)", alpha=chain.alpha,
                    seed=-1 if chain.seed is None else int(chain.seed), generator=GENERATOR,
                    wall_radius=chain.wall_radius, K4_sign=chain.k4_sign)
    ds.attrs.update(extra_attrs or {})
    return ds


#: Dimension of each variable of a chain file that read_chain relies on.
CHAIN_DIMS = {"radius": ("site",), "mass": ("site",), "A": ("bond",), "delta": ("bond",), "K2": ("bond",),
              "K3": ("bond",), "K4": ("bond",), "frequency": ("mode",), "mode_shape": ("site", "mode"),
              "mode_participation": ("mode",)}


def read_chain(path, k4_sign: float = 1.0) -> Chain:
    """The chain stored in a chain file (written by ``chainchaos chain`` or chain_dataset).

    Raises ChainFileError naming the file and what is wrong: missing, not a readable NetCDF file,
    a NetCDF file that is not a chain (a variable, dimension or attribute of the data contract
    missing or of the wrong shape), or radii that make no chain."""
    path = Path(path)
    name = repr(str(path))
    if not path.exists():
        raise ChainFileError(f"chain file {name} does not exist")
    if not path.is_file():
        raise ChainFileError(f"chain file {name} is not a file")
    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            _check_chain_dataset(ds, name)
            radius, attrs = ds["radius"].values, dict(ds.attrs)
    except ChainFileError:
        raise
    except (OSError, ValueError, RuntimeError) as err:
        raise ChainFileError(f"chain file {name} is not a readable NetCDF file ({err}); "
                             "write one with 'chainchaos chain'") from err
    try:
        seed = int(attrs["seed"])
        return Chain(radius, float(attrs["alpha"]), seed=None if seed < 0 else seed,
                     wall_radius=float(attrs.get("wall_radius", 1.0)), k4_sign=float(k4_sign))
    except (ValueError, TypeError) as err:  # ParameterError is a ValueError
        raise ChainFileError(f"chain file {name} holds no valid chain: {err}") from err


def read_radii(path) -> np.ndarray:
    """The radii of a text file, one number per line ('#' starts a comment); ChainFileError names
    the file when it is missing, unreadable, or holds anything but at least two numbers."""
    path = Path(path)
    name = repr(str(path))
    if not path.is_file():
        raise ChainFileError(f"radii file {name} does not exist" if not path.exists()
                             else f"radii file {name} is not a file")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # numpy's "input contained no data"
            radii = np.loadtxt(path, ndmin=1)
    except (ValueError, UnicodeDecodeError) as err:
        raise ChainFileError(f"radii file {name} is not one number per line ({err})") from err
    if radii.ndim != 1 or radii.size < 2:
        raise ChainFileError(f"radii file {name} holds {radii.size} number(s) in shape {radii.shape}; "
                             "a chain needs one radius per line, at least 2")
    return radii


def _check_chain_dataset(ds: xr.Dataset, name: str) -> None:
    missing = [v for v in CHAIN_VARIABLES if v not in ds.variables]
    if missing:
        raise ChainFileError(f"chain file {name} lacks variable(s) {missing}; "
                             f"a chain file holds {list(CHAIN_VARIABLES)}")
    wrong = {v: ds[v].dims for v, dims in CHAIN_DIMS.items() if ds[v].dims != dims}
    if wrong:
        raise ChainFileError(f"chain file {name}: variable(s) with the wrong dimensions {wrong}; "
                             f"a chain file has {CHAIN_DIMS}")
    N = ds.sizes["site"]
    sizes = {"site": N, "bond": ds.sizes["bond"], "mode": ds.sizes["mode"]}
    if N < 2 or sizes != {"site": N, "bond": N + 1, "mode": N}:
        raise ChainFileError(f"chain file {name}: dimension sizes {sizes}; a chain of N >= 2 beads has "
                             "N sites, N + 1 bonds and N modes")
    for attr in ("alpha", "seed"):
        if attr not in ds.attrs:
            raise ChainFileError(f"chain file {name} lacks attribute {attr!r}")


def ensemble_dataset(alphas, n_realizations: int, N: int = 40, first_seed: int = 0,
                     convention: str = "potential") -> xr.Dataset:
    """Fig. 1(a) statistics: mean and standard deviation of the sorted mode participation numbers."""
    from chainchaos.system.linear import ensemble_participation

    stats = ensemble_participation(alphas, n_realizations, N, first_seed, convention)
    ds = xr.Dataset(
        {
            "mean_participation": (("alpha", "rank"), stats["mean"], {
                "units": "1", "long_name": "mean participation number of the rank-k mode"}),
            "std_participation": (("alpha", "rank"), stats["std"], {
                "units": "1", "long_name": "standard deviation of the participation number of the rank-k mode"}),
        },
        coords={"alpha": np.asarray(alphas, dtype=float), "rank": np.arange(1, N + 1)},
    )
    ds["alpha"].attrs.update(units="1", long_name="disorder strength alpha = max R / min R")
    ds["rank"].attrs.update(units="1", long_name="rank k of the mode, by decreasing participation number")
    params = {"alphas": [float(a) for a in np.atleast_1d(alphas)], "n_realizations": int(n_realizations),
              "N": int(N), "first_seed": int(first_seed), "convention": convention}
    ds.attrs.update(provenance_attrs(params))
    ds.attrs.update(title="Participation numbers of linear modes over disorder realizations",
                    n_realizations=int(n_realizations), first_seed=int(first_seed), generator=GENERATOR,
                    convention=convention)
    return ds
