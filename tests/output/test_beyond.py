"""The manuscript's section Beyond the paper (chainchaos.output.beyond) and its optional part."""

import numpy as np
import xarray as xr

from chainchaos.output import manuscript
from chainchaos.output.beyond import body, law_rows, tex_text


def _laws(lower, upper, expected=1 / 3, exponent=0.3, t_walls=np.inf):
    ds = xr.Dataset(coords={"model": ["kg"], "energy": [0.4], "law": ["m2"]})
    for key, value, dtype in (("exponent", exponent, float), ("lower", lower, float), ("upper", upper, float),
                              ("t_start", 1e4, float), ("t_end", 1e7, float), ("settled", 1, np.int8),
                              ("realizations", 64, np.int32), ("t_walls", t_walls, float)):
        ds[key] = (("model", "energy", "law"), np.full((1, 1, 1), value, dtype=dtype))
    ds["energy_error_max"] = (("model", "energy"), [[2.5e-6]])
    ds["expected"] = ("law", [expected])
    ds["reference"] = ("law", np.array(["Flach, Krimer & Skokos_2009"], dtype=object))
    ds["series"] = ("law", np.array(["second_moment"], dtype=object))
    ds.attrs.update(fit_t_min=100.0, fit_band=0.1, fit_window_decades=1.0, fit_min_decades=1.0, fit_bootstrap=1000,
                    cost_s=7260.0, cost_kind="CPU")
    return ds


def test_a_published_exponent_inside_or_outside_the_interval_is_said_so():
    assert law_rows("kg_weak_chaos", _laws(0.25, 0.35))[0]["inside"]
    assert not law_rows("kg_weak_chaos", _laws(0.25, 0.30))[0]["inside"]
    text = body({"kg_weak_chaos": _laws(0.25, 0.35)}, {"kg_weak_chaos": ["chaos"]})
    assert r"\texttt{kg\_weak\_chaos}" in text and "& yes" in text and r"Krimer \& Skokos\_2009" in text
    assert r"{beyond/kg_weak_chaos_chaos}" in text
    assert r"\texttt{kg\_weak\_chaos} 121 CPU-min, largest relative energy error $2.5\times10^{-6}$" in text
    assert "(no interval)" in body({"s": _laws(np.nan, np.nan)}, {})


def test_a_law_cut_by_the_walls_says_so():
    cut = _laws(0.25, 0.35, t_walls=1e6)
    cut.attrs.update(walls_edge_energy=1e-6, walls_participation_fraction="none")
    text = body({"s": cut}, {})
    assert r"$10^{4.0}$--$10^{7.0}$$^\ddagger$" in text and r"exceeds $\log_{10} 10^{-6}$" in text
    short = body({"s": _laws(np.nan, np.nan, exponent=np.nan, t_walls=10 ** 2.5)}, {})
    assert "(chain too short)" in short and r"ends felt at $10^{2.5}$$^\ddagger$" in short
    unfitted = body({"s": _laws(np.nan, np.nan, exponent=np.nan)}, {})  # no walls: the run itself is short
    assert "(run too short) & ---" in unfitted and "chain too short" not in unfitted


def test_tex_text_escapes_in_one_pass():
    assert tex_text(r"a_b & {c} 5% ^ \ ") == r"a\_b \& \{c\} 5\% \^{} \textbackslash{} "
    assert tex_text("|Lambda| t") == r"\textbar{}Lambda\textbar{} t"


def test_an_optional_part_without_files_switches_its_section_off(tmp_path):
    tex = tmp_path / "ms.tex"
    tex.write_text("x")
    generated = {}
    for key, name in manuscript.GENERATED.items():
        (tmp_path / name).write_text("%")
        generated[key] = tmp_path / name
    figure = tmp_path / "spreading.pdf"
    figure.write_bytes(b"%PDF-")
    manuscript.prepare(tmp_path / "build", tex, generated, {}, {"beyond": {"kg_spreading": figure}})
    assert r"\beyondtrue" in (tmp_path / "build" / "generated" / "beyond.tex").read_text()
    assert r"{beyond/kg_spreading.pdf}" in (tmp_path / "build" / "generated" / "beyond.tex").read_text()
    assert (tmp_path / "build" / "beyond" / "kg_spreading.pdf").exists()
    assert r"\numericsfalse" in (tmp_path / "build" / "generated" / "numerics.tex").read_text()


def test_a_published_uncertainty_asks_for_overlapping_intervals():
    """0.33 +- 0.02 against our [0.25, 0.30]: the intervals [0.31, 0.35] and [0.25, 0.30] do not
    overlap; against [0.25, 0.32] they do, though 0.33 lies outside ours."""
    apart, touching = _laws(0.25, 0.30, expected=0.33), _laws(0.25, 0.32, expected=0.33)
    for ds in (apart, touching):
        ds["uncertainty"] = ("law", [0.02])
    assert not law_rows("s", apart)[0]["inside"] and law_rows("s", touching)[0]["inside"]
    assert r"$0.33 \pm 0.02$ & yes" in body({"s": touching}, {})


def test_a_crossover_row_gives_the_largest_local_derivative_and_its_band():
    ds = _laws(0.25, 0.35)
    ds = ds.assign_coords(crossover=["second_moment"])
    for key, value in (("crossover_max", 0.52), ("crossover_t_max", 10 ** 3.5), ("crossover_max_lower", 0.47),
                       ("crossover_max_upper", 0.56)):
        ds[key] = (("model", "energy", "crossover"), np.full((1, 1, 1), value))
    ds["crossover_lines"] = (("crossover", "line"), [[0.5, 1 / 3]])
    ds["crossover_reference"] = ("crossover", np.array(["Laptyeva et al. 2010"], dtype=object))
    text = body({"dnls_strong_chaos": ds}, {})
    assert r"$0.520$ [$0.470$, $0.560$] & largest at $10^{3.5}$ & --- & $0.5$ $\to$ $0.333$ & yes" in text
    assert "Laptyeva et al. 2010" in text


def test_a_self_trapped_law_is_not_read_as_a_spreading_law():
    ds = _laws(0.25, 0.35)
    ds["self_trapped"] = (("model", "energy", "law"), np.full((1, 1, 1), 0.75))
    text = body({"s": ds}, {})
    assert r"(self-trapped in 75\,\%: not a spreading law)" in text and "& ---" in text
