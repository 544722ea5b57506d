"""Results kept as data, keyed by their settings (chainchaos.records.kept): the digest, the one-line
reasons, `all` using an archive only when its key is the run's, and the disorder archive's numbers
recomputed bit for bit."""

import json
import shutil
import re
import subprocess
import sys
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml

from chainchaos.errors import KeptFileError
from chainchaos.records import kept
from chainchaos.records.io import write_netcdf
from chainchaos.run.orbits import Orbit
from chainchaos.studies.scan import runs
from chainchaos.studies.search import archive
from chainchaos.studies.search.stages import SEARCH_RESULT_VERSION
from chainchaos.studies.study import orbits
from reduced import reduced_orbits

ROOT = Path(__file__).resolve().parents[2]
SEARCH_ARCHIVE = ROOT / "data" / "search" / "search_full.nc"
DISORDER_ARCHIVE = ROOT / "data" / "disorder" / "disorder_full.nc"
CONFIG = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())


def search_settings(config=CONFIG):
    """The full search's settings as workflow/rules/common.smk builds them (search_params)."""
    selection = {**config["chain"]["selection"], "n_seeds": config["search_full"]["n_seeds"]}
    return archive.search_settings({
        "search": {**config["search_full"], "settings": config["search"]["settings"]},
        "chain": {**config["chain"], "selection": selection},
        "claims": config["claims"], "site": config["simulation"]["excited_site"]})


def disorder_settings(config=CONFIG):
    return runs.disorder_settings(runs.scan_config("disorder_full", config["scan"])[1], config["chain"]["N"])


def leaves(data, path=()):
    """(path, value) of every leaf of plain data."""
    if isinstance(data, dict):
        for key, value in data.items():
            yield from leaves(value, (*path, key))
    elif isinstance(data, list) and data:
        for i, value in enumerate(data):
            yield from leaves(value, (*path, i))
    else:
        yield path, data


def changed(data, path):
    """``data`` with the leaf at ``path`` changed (another value of its kind)."""
    data = json.loads(json.dumps(data))
    *head, last = path
    target = data
    for key in head:
        target = target[key]
    value = target[last]
    target[last] = (not value if isinstance(value, bool) else value + 1 if isinstance(value, (int, float))
                    else 1 if value is None else [*value, 1] if isinstance(value, list) else f"{value}x")
    return data


@pytest.mark.parametrize("settings", [search_settings(), disorder_settings()], ids=["search", "disorder"])
def test_the_digest_changes_when_any_setting_changes(settings):
    canonical = kept.canonical(settings)
    base = kept.digest(canonical)
    paths = [path for path, _ in leaves(canonical)]
    assert len(paths) > 20
    for path in paths:
        assert kept.digest(changed(canonical, path)) != base, path


def test_one_setting_written_two_ways_is_one_setting():
    assert kept.digest({"t_final": 1.0e5, "dt": 0.01}) == kept.digest({"dt": 0.01, "t_final": 100000})
    assert kept.digest({"alignment": True}) != kept.digest({"alignment": 1})
    with pytest.raises(ValueError):
        kept.canonical({"dt": float("nan")})


def test_the_archives_are_keyed_by_todays_settings():
    """The kept files of the repository may stand in for `all`'s computations as configured."""
    assert kept.why_not_usable(SEARCH_ARCHIVE, search_settings(), SEARCH_RESULT_VERSION, "remake") is None
    assert kept.why_not_usable(DISORDER_ARCHIVE, disorder_settings(), runs.DISORDER_RESULT_VERSION, "remake") is None


def test_the_reason_names_the_first_differing_key_or_the_version():
    config = json.loads(json.dumps(CONFIG))
    config["chain"]["N"] = 41
    why = kept.why_not_usable(SEARCH_ARCHIVE, search_settings(config), SEARCH_RESULT_VERSION, "remake")
    assert why == f"kept file {SEARCH_ARCHIVE}: chain.N is 40 in the file, 41 in this run"
    why = kept.why_not_usable(SEARCH_ARCHIVE, search_settings(), SEARCH_RESULT_VERSION + 1, "remake")
    assert why == (f"kept file {SEARCH_ARCHIVE}: result_version is {SEARCH_RESULT_VERSION} in the file, "
                   f"{SEARCH_RESULT_VERSION + 1} in this code")
    # only the chain block compared (a scale that only shortens runs): shorter orbits still match
    config = json.loads(json.dumps(CONFIG))
    config["search"]["settings"]["t_final"] = 1e3
    assert kept.why_not_usable(SEARCH_ARCHIVE, search_settings(config), SEARCH_RESULT_VERSION, "remake",
                               keys=("chain",)) is None
    why = kept.why_not_usable(SEARCH_ARCHIVE, search_settings(config), SEARCH_RESULT_VERSION, "remake")
    assert why.endswith("orbit.t_final is 100000 in the file, 1000 in this run"), why


def test_an_unreadable_or_unkeyed_file_gives_one_line_naming_the_remedy(tmp_path):
    truncated = tmp_path / "search_full.nc"
    truncated.write_bytes(SEARCH_ARCHIVE.read_bytes()[:5000])
    with pytest.raises(KeptFileError) as error:
        kept.why_not_usable(truncated, search_settings(), SEARCH_RESULT_VERSION, "snakemake --cores 2 search_full")
    message = str(error.value)
    assert "\n" not in message and "cannot be read (NetCDF: HDF error)" in message
    assert f"git checkout -- {truncated}" in message and "snakemake --cores 2 search_full" in message
    unkeyed = tmp_path / "unkeyed.nc"
    xr.Dataset(attrs={"chosen_seed": 879}).to_netcdf(unkeyed)
    with pytest.raises(KeptFileError, match="records no kept_settings"):
        kept.read_key(unkeyed, "snakemake --cores 2 search_full")


def test_a_stamp_leaves_every_variable_as_it_is(tmp_path):
    path = tmp_path / "result.nc"
    xr.Dataset({"x": ("i", np.array([0.1, np.nan, 3.0]))}, attrs={"title": "t"}).to_netcdf(path)
    kept.stamp(path, {"a": 1}, 2)
    ds = xr.load_dataset(path)
    assert ds["x"].values.tobytes() == np.array([0.1, np.nan, 3.0]).tobytes() and ds.attrs["title"] == "t"
    assert kept.read_key(path, "remake") == ({"a": 1}, 2)


# ---- the checksum of a kept file's data: a file damaged inside its data is named -----------------

REMAKE = "snakemake --cores 2 keep --config keep=search_full"


def small_kept_file(path, sealed=True) -> xr.Dataset:
    """A small kept file (floats with a NaN, integers, strings, a scalar, a coordinate) with the
    settings ``{"a": 1}``: written as the workflow writes kept files (compressed, with the checksum
    of its data), or else by xarray as it is (uncompressed, no checksum)."""
    ds = xr.Dataset({"x": ("i", np.array([0.1, np.nan, 3.0])), "n": ("i", np.arange(3, dtype=np.int32)),
                     "name": ("i", np.array(["a", "bé", ""], dtype=object)), "t": ((), 2.5)},
                    coords={"i": np.array([10, 20, 30], dtype=np.int32)},  # the dtype write_netcdf gives it
                    attrs={"title": "t", **kept.kept_attrs({"a": 1}, 1)})
    if sealed:
        write_netcdf(ds, path, seal=True)
    else:
        ds.to_netcdf(path, engine="netcdf4")
    return ds


def one_line_naming(error, path, what: str) -> None:
    message = str(error.value)
    assert "\n" not in message and message.startswith(f"kept file {path}") and what in message, message
    assert f"restore it with 'git checkout -- {path}', or delete it and remake it with '{REMAKE}'" in message


def test_the_checksum_is_that_of_the_data_not_of_the_attributes(tmp_path):
    sealed, plain = tmp_path / "sealed.nc", tmp_path / "plain.nc"
    ds = small_kept_file(sealed)
    small_kept_file(plain, sealed=False)  # the same data, uncompressed
    checksum = kept.data_checksum(sealed)
    assert xr.load_dataset(sealed).attrs[kept.DATA_ATTR] == checksum == kept.data_checksum(plain)
    assert kept.check_data(sealed, REMAKE) is True
    assert xr.load_dataset(sealed).drop_attrs().identical(ds.drop_attrs())
    kept.stamp(sealed, {"b": 2}, 3)  # another key, and sealed again: the data and their checksum as they were
    assert kept.data_checksum(sealed) == checksum and kept.check_data(sealed, REMAKE)
    assert kept.read_key(sealed, REMAKE) == ({"b": 2}, 3)
    kept.seal(plain)
    assert xr.load_dataset(plain).attrs[kept.DATA_ATTR] == checksum
    other = tmp_path / "other.nc"
    ds["x"].values[0] = 0.2
    ds.to_netcdf(other, engine="netcdf4")
    assert kept.data_checksum(other) != checksum


def test_a_file_altered_inside_its_data_stops_with_one_line(tmp_path):
    path = tmp_path / "search_full.nc"
    small_kept_file(path)
    with netCDF4.Dataset(path, "a") as nc:  # one value changed, its header intact
        nc["n"][1] = 7
    assert kept.read_key(path, REMAKE) == ({"a": 1}, 1)  # what the workflow reads while it is parsed
    with pytest.raises(KeptFileError) as error:
        kept.check_data(path, REMAKE)
    one_line_naming(error, path, "its data do not match the checksum it records (kept_data_checksum)")


def test_a_truncated_or_undecodable_file_stops_with_one_line(tmp_path):
    path = tmp_path / "search_full.nc"
    rng = np.random.default_rng(1)  # a compressed variable filling the middle of the file
    write_netcdf(xr.Dataset({"x": ("i", rng.random(100_000))}, attrs=kept.kept_attrs({"a": 1}, 1)), path, seal=True)
    data = bytearray(path.read_bytes())
    data[len(data) // 2] ^= 0xFF
    path.write_bytes(data)
    with pytest.raises(KeptFileError) as error:
        kept.check_data(path, REMAKE)
    one_line_naming(error, path, "cannot be read (NetCDF: HDF error in its variable x)")
    path.write_bytes(data[:len(data) // 2])
    with pytest.raises(KeptFileError) as error:
        kept.check_data(path, REMAKE)
    one_line_naming(error, path, "cannot be read (NetCDF: HDF error)")


def test_a_kept_file_without_a_checksum_stops_and_a_result_is_not_checked(tmp_path):
    unsealed, result = tmp_path / "unsealed.nc", tmp_path / "result.nc"
    small_kept_file(unsealed, sealed=False)
    with pytest.raises(KeptFileError) as error:
        kept.check_data(unsealed, REMAKE)
    one_line_naming(error, unsealed, "records no kept_data_checksum")
    xr.Dataset({"x": ("i", [1.0])}).to_netcdf(result)
    assert kept.check_data(result, REMAKE) is False


def test_a_job_that_reads_a_damaged_kept_file_stops_with_one_line(tmp_path):
    """merge_disorder with the kept disorder statistics as its input: the job stops, naming them."""
    from chainchaos.workflow.tasks.scan import merge_disorder

    damaged = tmp_path / "disorder_full.nc"
    damaged.write_bytes(DISORDER_ARCHIVE.read_bytes())
    with netCDF4.Dataset(damaged, "a") as nc:
        nc["energy"][0] = -1.0  # an energy the grid does not hold
    merged = tmp_path / "disorder_statistics.nc"
    with pytest.raises(KeptFileError, match=f"^kept file {re.escape(str(damaged))}: its data do not match") as error:
        merge_disorder({"archive": str(damaged)}, {"merged": str(merged)}, {}, {})
    assert "keep=disorder_full" in str(error.value) and not merged.exists()


def test_every_kept_file_of_the_repository_records_the_checksum_of_its_data():
    paths = sorted((ROOT / "data").rglob("*.nc"))
    assert SEARCH_ARCHIVE in paths and DISORDER_ARCHIVE in paths
    for path in paths:
        assert kept.check_data(path, REMAKE) is True, path


# ---- the pipeline: the config chooses the kept results, jobs check them ----------------------

def dry_run(*args):
    done = subprocess.run([sys.executable, "-m", "snakemake", "--cores", "2", "--nolock", "-n", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)
    return done.returncode, done.stdout + done.stderr


def snakemake(*args):
    done = subprocess.run([sys.executable, "-m", "snakemake", "--cores", "1", "--nolock", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=600)
    return done.returncode, done.stdout + done.stderr


def planned_jobs(output: str) -> dict[str, int]:
    table = output.split("Job stats:")[-1]
    return {m.group(1): int(m.group(2)) for m in re.finditer(r"^(\w+)\s+(\d+)$", table, re.M) if m.group(1) != "total"}


def rule_inputs(output: str, rule: str) -> str:
    """The input line of the (first) job of ``rule`` in a dry run's listing."""
    found = re.search(rf"^(?:local)?rule {rule}:\n\s+input: (.*)$", output, re.M)
    assert found, f"no job of {rule} planned"
    return found.group(1)


#: Run Snakemake in a process where opening any file under data/ raises: by Python (the audit
#: event of every open) or by netCDF4 (whose C library opens files without that event).
NO_DATA_READ = """
import sys
from pathlib import Path

import netCDF4

data = str(Path("data").resolve())


def refuse(path):
    if str(Path(str(path)).resolve()).startswith(data):
        raise RuntimeError(f"opened while the plan is made: {path}")


def hook(event, args):
    if event == "open" and isinstance(args[0], (str, bytes, Path)):
        refuse(args[0] if not isinstance(args[0], bytes) else args[0].decode())


class Dataset(netCDF4.Dataset):
    def __init__(self, filename, *args, **kwargs):
        refuse(filename)
        super().__init__(filename, *args, **kwargs)


netCDF4.Dataset = Dataset
sys.addaudithook(hook)
from snakemake.cli import main

sys.argv = ["snakemake", *sys.argv[1:]]
main()
"""


@pytest.mark.pipeline
def test_the_plan_of_all_opens_no_kept_file_and_prints_nothing(tmp_path):
    """No file under data/ is opened while the Snakefile is parsed and the dry run of `all` is
    built, at either scale; and nothing is printed to stderr before Snakemake's own lines."""
    for scale in ([], ["--configfile", "config/quick.yaml"]):
        done = subprocess.run([sys.executable, "-c", NO_DATA_READ, "--cores", "2", "--nolock", "-n", "all", *scale,
                               "--config", f"results={tmp_path}"], cwd=ROOT, capture_output=True, text=True,
                              timeout=300)
        out = done.stdout + done.stderr
        assert done.returncode == 0 and "opened while the plan is made" not in out, out[-4000:]
        assert "kept file" not in out and planned_jobs(out)["check_kept_archive"] >= 1


@pytest.mark.pipeline
def test_the_plan_is_the_same_whether_the_kept_files_are_intact_or_damaged(tmp_path):
    """A truncated archive and a damaged kept group plan the same jobs as intact ones: judging
    them is the work of the jobs that read them."""
    truncated = tmp_path / "search_full.nc"
    truncated.write_bytes(SEARCH_ARCHIVE.read_bytes()[:5000])
    studies = tmp_path / "studies"
    shutil.copytree(ROOT / "data" / "studies", studies)
    group = studies / "kg_weak_chaos" / "groups" / "0000.nc"
    group.write_bytes(group.read_bytes()[:3000])
    results = f"results={tmp_path / 'results'}"
    code, intact = dry_run("all", "--config", results)
    assert code == 0, intact[-4000:]
    code, damaged = dry_run("all", "--config", results, f"search={{archive: {truncated}}}", f"kept_studies={studies}")
    assert code == 0, damaged[-4000:]
    assert planned_jobs(damaged) == planned_jobs(intact)
    assert rule_inputs(damaged, "select_chain") == f"{truncated}, {tmp_path}/results/kept/search_full.txt"


@pytest.mark.pipeline
def test_a_kept_file_with_one_changed_setting_stops_only_the_jobs_that_read_it(tmp_path):
    """The same plan as with the kept settings; the checks of both archives fail with one line
    naming the setting and the two ways out; a target that reads neither is made."""
    results = tmp_path / "results"
    config = ["--configfile", "config/quick.yaml", "--config", f"results={results}", "chain={N: 41}",
              "scan={disorder: {archive: data/disorder/disorder_full.nc}}"]
    code, changed = dry_run("all", *config)
    assert code == 0, changed[-4000:]
    code, kept_settings = dry_run("all", *config[:-2], config[-1])
    assert planned_jobs(changed) == planned_jobs(kept_settings)
    code, out = snakemake(*config, "--keep-going", "--", str(results / "ensemble" / "participation_stats.nc"),
                          str(results / "kept" / "search_full.txt"), str(results / "kept" / "disorder_full.txt"))
    assert code != 0 and (results / "ensemble" / "participation_stats.nc").exists(), out[-4000:]
    for name, path, compute in [
            ("search_full", SEARCH_ARCHIVE.relative_to(ROOT), "search.archive and search.pinned_seed to search"),
            ("disorder_full", DISORDER_ARCHIVE.relative_to(ROOT), "scan.disorder.archive to compute it")]:
        log = (results / "logs" / "check_kept_archive" / f"{name}.log").read_text()
        assert log == (f"check_kept_archive: kept file {path}: chain.N is 40 in the file, 41 in this run; remake it "
                       f"with 'snakemake --cores 2 keep --config keep={name}', or empty config {compute} at this "
                       "run's scale\n"), log
        assert not (results / "kept" / f"{name}.txt").exists()


@pytest.mark.pipeline
def test_a_chosen_kept_file_that_is_absent_is_named_and_nothing_computes_it(tmp_path):
    code, out = dry_run("all", "--config", f"results={tmp_path}", f"search={{archive: {tmp_path}/absent.nc}}")
    assert code != 0
    assert (f"kept file {tmp_path}/absent.nc is absent; restore it with 'git checkout -- {tmp_path}/absent.nc', "
            "remake it with 'snakemake --cores 2 keep --config keep=search_full', or empty config search.archive "
            "and search.pinned_seed to search at this run's scale") in out, out[-4000:]
    assert "search_seeds" not in out


@pytest.mark.pipeline
def test_a_truncated_archive_stops_its_check_with_one_line(tmp_path):
    """The job that checks the file stops with the line naming it and its remedy, no traceback,
    and the jobs that read it do not run."""
    truncated = tmp_path / "search_full.nc"
    truncated.write_bytes(SEARCH_ARCHIVE.read_bytes()[:5000])
    remedy = (f"kept file {truncated} cannot be read (NetCDF: HDF error); restore it with 'git checkout -- "
              f"{truncated}', or delete it and remake it with 'snakemake --cores 2 keep --config keep=search_full'")
    config = ["--configfile", "config/quick.yaml", "--config", f"results={tmp_path}",
              f"search={{archive: {truncated}}}"]
    code, out = snakemake(*config, "--", str(tmp_path / "chain" / "chain.nc"))
    log = (tmp_path / "logs" / "check_kept_archive" / "search_full.log").read_text()
    assert code != 0 and log == f"check_kept_archive: {remedy}\n", log
    assert "Traceback" not in log and not (tmp_path / "chain" / "chain.nc").exists()


# ---- bit identity of the kept disorder statistics ----------------------------------------------

def test_one_disorder_trajectory_recomputed_is_bit_identical_to_the_archive():
    """One trajectory of the kept disorder statistics (one model, realization and energy) at the
    archive's own settings (its kept_settings), run again by today's code: every scalar equal bit
    for bit. A failure means the code now computes other numbers: bump
    runs.DISORDER_RESULT_VERSION and remake the archive (snakemake --cores 2 keep --config keep=disorder_full)."""
    ds = xr.load_dataset(DISORDER_ARCHIVE)
    settings, version = kept.read_key(DISORDER_ARCHIVE, "snakemake --cores 2 disorder_full")
    assert version == runs.DISORDER_RESULT_VERSION
    chain, energies = settings["chain"], settings["energies"]
    scan = {"settings": {**settings["orbit"], **settings["criteria"]},
            "disorder": {**{k: chain[k] for k in ("alpha", "wall_radius", "first_seed", "realizations")},
                         **energies, "selection": settings["excitation"]}}
    model, r, e = "hertz", 3, 12
    realization = runs.realization_chain(scan, r, chain["N"])
    pick = orbits.select_excitation(realization, **runs.selection_kwargs(scan))
    energy = orbits.energy_grid(scan["disorder"])[e]
    assert energy == ds["energy"].values[e] and pick["site"] == ds["excited_site"].values[r]
    [result] = reduced_orbits([Orbit(model=model, energy=float(energy), chain=realization, site=pick["site"])],
                                     runs.settings_for("disorder", scan))
    kept_values = ds.sel(model=model).isel(energy=e, realization=r)
    for key, (_, dtype) in orbits.SCALARS.items():
        ours, theirs = np.asarray(result[key]).astype(dtype), kept_values[key].values
        assert ours.tobytes() == theirs.astype(dtype).tobytes(), (key, ours, theirs)
