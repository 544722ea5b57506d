"""Tests of the figures: every panel and composite of the paper, drawn from small synthetic
Datasets that follow the data contract (docs/conventions.md#data-contract), and their
byte-stable, atomic saving."""

import io
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import LogNorm, to_rgb
from matplotlib.image import imread
from matplotlib.text import Text

from chainchaos.output.plotting import plot_figure, plot_panel, save_figure, style
from chainchaos.paper import panels

N = 40  # sites; Fig. 1b's inset shows mode 34
T_FINAL = 1000.0  # shorter than the profile time 1e5 of Figs. 3c,d
EQUIPARTITION = 0.115


def _times() -> np.ndarray:
    return np.concatenate(([0.0], np.logspace(-1, np.log10(T_FINAL), 61)))


def _densities(rng, shape) -> np.ndarray:
    """Positive rows summing to 1, spread over a few decades like h_n or w_n."""
    x = 10.0 ** rng.uniform(-6, 0, shape)
    return x / x.sum(axis=-1, keepdims=True)


def synthetic_scene(scene: panels.Scene, rng) -> xr.Dataset:
    """A scene Dataset with every observable of the contract (gaps only for Hertz)."""
    t = _times()
    S = t.size
    h, w = _densities(rng, (S, N)), _densities(rng, (S, N))
    E = 10.0 ** rng.uniform(-4, 0, (S, N))
    with np.errstate(divide="ignore"):
        mlce = np.where(t > 0, (1.0 + rng.random(S)) / np.where(t > 0, t, 1.0), np.nan)
    data = {
        "energy_density": (("time", "site"), h),
        "participation": ("time", 1.0 / (h**2).sum(-1)),
        "energy_centre": ("time", h @ np.arange(1, N + 1)),
        "mlce": ("time", mlce),
        "dvd": (("time", "site"), w),
        "dvd_participation": ("time", 1.0 / (w**2).sum(-1)),
        "mode_energy": (("time", "mode"), E),
        "eta": ("time", np.linspace(1.0, 0.1, S), {"equipartition_value": EQUIPARTITION}),
        "frequency": ("mode", np.sort(rng.uniform(0.01, 2.5, N))),
        "energy_error": ("time", 1e-8 * rng.random(S)),
    }
    if scene.model == "hertz":
        is_open = (rng.random((S, N + 1)) < 0.05).astype(np.int8)
        n_gaps = is_open.sum(-1).astype(np.int32)
        data.update({
            "gap_open": (("time", "bond"), is_open),
            "gap_fraction": (("time", "bond"), rng.random((S, N + 1)) * 0.3),
            "n_gaps": ("time", n_gaps),
            "n_gaps_max": ("time", n_gaps + rng.integers(0, 3, S).astype(np.int32)),
        })
    coords = {"time": t, "site": np.arange(1, N + 1), "bond": np.arange(1, N + 2), "mode": np.arange(1, N + 1)}
    attrs = {"model": scene.model, "energy": float(scene.energy), "t_final": float(t[-1]),
             "scene": scene.name, "dt": 0.01, "integrator": "SRKN6b", "u0": 1.0, "K4_sign": 1.0}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def synthetic_chain(rng) -> xr.Dataset:
    shape = rng.normal(size=(N, N))
    return xr.Dataset(
        {"frequency": ("mode", np.sort(rng.uniform(0.01, 2.5, N))),
         "mode_shape": (("site", "mode"), shape / np.linalg.norm(shape, axis=0)),
         "mode_participation": ("mode", rng.uniform(1.5, 30.0, N))},
        coords={"site": np.arange(1, N + 1), "mode": np.arange(1, N + 1)},
        attrs={"alpha": 5.0, "seed": 879, "generator": "numpy.random.default_rng (PCG64)"})


def synthetic_ensemble(rng) -> xr.Dataset:
    alphas = np.array([1.0, 3.0, 5.0])
    mean = np.sort(rng.uniform(2.0, 30.0, (alphas.size, N)), axis=1)[:, ::-1]
    return xr.Dataset(
        {"mean_participation": (("alpha", "rank"), mean),
         "std_participation": (("alpha", "rank"), 0.1 * mean)},
        coords={"alpha": alphas, "rank": np.arange(1, N + 1)})


@pytest.fixture(scope="module")
def data() -> dict:
    rng = np.random.default_rng(2024)
    scenes = {name: synthetic_scene(scene, rng) for name, scene in sorted(panels.scenes().items())}
    return {**scenes, "chain": synthetic_chain(rng), "ensemble": synthetic_ensemble(rng)}


def _render(fig) -> bytes:
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=40)
    return buffer.getvalue()


def _texts(legend) -> list[str]:
    return [text.get_text() for text in legend.get_texts()]


# --------------------------------------------------------------------------- every panel, every figure


@pytest.mark.parametrize("panel_id", sorted(panels.PANELS))
def test_every_panel_draws(panel_id, data):
    fig = plot_panel(panel_id, data)
    ax = fig.axes[0]
    assert ax.lines or ax.collections, f"panel {panel_id} drew nothing"
    assert _render(fig).startswith(b"\x89PNG")


@pytest.mark.parametrize("number", sorted(panels.LAYOUTS))
def test_every_figure_draws_its_panels_lettered(number, data):
    fig = plot_figure(number, data)
    letters = [ax.get_title(loc="left").split("$")[1] for ax in fig.axes if ax.get_title(loc="left")]
    expected = [rf"\bf{{({letter})}}" for row in panels.LAYOUTS[number] for letter in row]
    assert letters == expected
    assert len(expected) == len(panels.panels_of_figure(number))
    assert _render(fig).startswith(b"\x89PNG")


@pytest.mark.parametrize("number", sorted(panels.LAYOUTS))
def test_panel_titles_clear_the_colour_bar_labels(number, data):
    """A lettered title that reaches over a map's colour bar (Fig. 9h) does not touch its tick labels."""
    fig = plot_figure(number, data)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    labels = [(label.get_text(), label.get_window_extent(renderer)) for bar in bars
              for tick in bar.yaxis.get_major_ticks() if min(bar.get_ylim()) <= tick.get_loc() <= max(bar.get_ylim())
              for label in (tick.label1, tick.label2) if label.get_visible() and label.get_text()]
    for ax in fig.axes:
        title = ax.get_title(loc="left")
        if not title:
            continue
        text = next(t for t in ax.get_children() if isinstance(t, Text) and t.get_text() == title)
        box = text.get_window_extent(renderer)
        clashes = [name for name, extent in labels if box.overlaps(extent)]
        assert not clashes, f"figure {number}: title {title!r} overlaps colour-bar label(s) {clashes}"


def test_unknown_panel_and_figure_are_refused(data):
    with pytest.raises(KeyError, match="unknown panel '4z'"):
        plot_panel("4z", data)
    with pytest.raises(KeyError, match="unknown figure 10"):
        plot_figure(10, data)


def test_missing_scene_or_variable_is_named(data):
    without_scene = {k: v for k, v in data.items() if k != "fput_H0.5"}
    with pytest.raises(KeyError, match="fput_H0.5"):
        plot_panel("4d", without_scene)
    without_mlce = {**data, "hertz_H0.5": data["hertz_H0.5"].drop_vars("mlce")}
    with pytest.raises(KeyError, match="mlce"):
        plot_panel("4d", without_mlce)


# --------------------------------------------------------------------------- what the panels show


def test_energy_map_has_log_colour_bar_centre_line_and_no_t0(data):
    fig = plot_panel("2a", data)
    ax, bar = fig.axes
    mesh = ax.collections[0]
    assert isinstance(mesh.norm, LogNorm) and mesh.norm.vmin > 0
    assert bar.get_ylabel() == style.ENERGY_DENSITY_LABEL
    assert ax.get_xscale() == "log" and ax.get_xlim()[0] > 0
    centre = data["hertz_H0.25"].energy_centre.values[1:]
    assert any(np.array_equal(line.get_ydata(), centre) and to_rgb(line.get_color()) == (0, 0, 0)
               for line in ax.lines)


def test_participation_colours_models_and_names_energies(data):
    ax = plot_panel("4c", data).axes[0]
    labels = _texts(ax.get_legend())
    assert labels == ["Hertz, $H = 0.5$", "Hertz, $H = 1.8$", "FPUT, $H = 0.5$", "FPUT, $H = 1.8$"]
    for line in ax.get_legend().legend_handles:
        red, _, blue = to_rgb(line.get_color())
        assert (red > blue) == line.get_label().startswith("Hertz")
    assert len({line.get_linestyle() for line in ax.get_legend().legend_handles}) == 2
    # raw values plus a smoothed curve per scene; the smoothed one is not the raw data
    assert len(ax.lines) == 8
    raw = data["hertz_H0.5"].participation.values[1:]
    smoothed = next(line for line in ax.lines if line.get_label() == "Hertz, $H = 0.5$")
    assert not np.allclose(smoothed.get_ydata(), raw)


def test_mlce_is_log_log_with_inverse_time_law(data):
    ax = plot_panel("2d", data).axes[0]
    assert ax.get_xscale() == ax.get_yscale() == "log"
    law = next(line for line in ax.lines if line.get_label() == r"$\propto t^{-1}$")
    assert law.get_linestyle() == "--"
    (t0, t1), (y0, y1) = law.get_xdata(), law.get_ydata()
    assert np.log(y1 / y0) / np.log(t1 / t0) == pytest.approx(-1.0)


def test_dvd_profile_beyond_the_run_is_left_out_and_named(data):
    ax = plot_panel("3c", data).axes[0]
    t = data["hertz_H0.25"].time.values[1:]
    drawn = [line for line in ax.lines if len(line.get_xdata())]
    assert len(drawn) == 2  # t = 10 and 1e3 drawn, t = 1e5 not
    used = t[np.argmin(np.abs(np.log(t / 10.0)))]
    assert drawn[0].get_label() == f"$t = {style.time_text(used)}$"
    assert drawn[1].get_label() == "$t = 10^{3}$"
    beyond = [text for text in _texts(ax.get_legend()) if "beyond run" in text]
    assert beyond == [r"$t = 10^{5}$ beyond run ($t_{\rm final} = 10^{3}$)"]


def test_dvd_map_marks_the_profile_times_within_the_run(data):
    ax = plot_panel("3a", data).axes[0]
    marks = [line.get_xdata()[0] for line in ax.lines]
    t = data["hertz_H0.25"].time.values
    assert len(marks) == 2 and all(mark in t for mark in marks)


def test_eta_equipartition_line_only_when_asked(data):
    def flat_lines(panel_id):
        ax = plot_panel(panel_id, data).axes[0]
        return [line for line in ax.lines if np.ptp(line.get_ydata()) == 0]

    (line,) = flat_lines("8c")
    assert line.get_ydata()[0] == EQUIPARTITION and line.get_linestyle() == "--"
    assert flat_lines("8a") == []


def test_mode_energy_map_is_normalised_per_time(data):
    fig = plot_panel("8e", data)
    values = np.asarray(fig.axes[0].collections[0].get_array()).reshape(N, -1)
    np.testing.assert_allclose(values.sum(axis=0), 1.0, rtol=1e-9)


def test_gap_count_shows_the_largest_since_previous_sample(data):
    ax = plot_panel("7c", data).axes[0]
    assert _texts(ax.get_legend()) == ["largest since previous sample", "at the sample"]
    np.testing.assert_array_equal(ax.lines[0].get_ydata(), data["hertz_H0.5"].n_gaps.values[1:])


def test_chain_spectrum_inset_names_the_mode_and_its_participation(data):
    ax = plot_panel("1b", data).axes[0]
    (inset,) = ax.child_axes
    P = data["chain"].mode_participation.sel(mode=34).item()
    assert inset.get_title() == rf"mode 34, $P = {P:.2f}$"
    np.testing.assert_allclose(np.abs(inset.lines[0].get_ydata()),
                               np.abs(data["chain"].mode_shape.sel(mode=34).values))


# --------------------------------------------------------------------------- saving


def test_saved_png_is_not_blank_and_has_the_journal_size(data, tmp_path):
    pdf, png = save_figure(plot_panel("4a", data), tmp_path / "fig4a")
    image = imread(png)
    assert image.shape[:2] == (round(style.PANEL_HEIGHT * style.DPI), round(style.COLUMN_WIDTH * style.DPI))
    assert image[..., :3].std() > 0.05
    assert (image[..., :3] < 0.9).any(axis=-1).mean() > 0.05  # a real share of the pixels is not white
    assert pdf.read_bytes().startswith(b"%PDF")


def test_saving_is_byte_stable(data, tmp_path):
    fig = plot_panel("2a", data)  # a rasterised map, a colour bar and constrained layout
    first = save_figure(fig, tmp_path / "a")
    second = save_figure(fig, tmp_path / "b")
    fresh = save_figure(plot_panel("2a", data), tmp_path / "c")
    low = save_figure(plot_panel("2a", data), tmp_path / "d", dpi=100)
    for a, b, c in zip(first, second, fresh):
        assert a.read_bytes() == b.read_bytes() == c.read_bytes(), a.suffix
    pdf, png = (path.read_bytes() for path in first)
    assert b"CreationDate" not in pdf and b"ModDate" not in pdf
    assert b"tIME" not in png
    assert imread(low[1]).shape[1] == round(style.COLUMN_WIDTH * 100)


def test_interrupted_save_leaves_no_complete_looking_file(data, tmp_path, monkeypatch):
    fig = plot_panel("2d", data)
    savefig = fig.savefig

    def fail_on_png(target, format, **kwargs):
        if format == "png":
            Path(target).write_bytes(b"\x89PNG partial")
            raise KeyboardInterrupt
        savefig(target, format=format, **kwargs)

    monkeypatch.setattr(fig, "savefig", fail_on_png)
    with pytest.raises(KeyboardInterrupt):
        save_figure(fig, tmp_path / "fig2d")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig2d.pdf"]


def test_the_panel_and_figure_jobs_draw_what_the_plotting_functions_draw(data, tmp_path):
    """Rules plot_panel and plot_figure: the same bytes as plot_panel and plot_figure drawn and
    saved on their own."""
    from chainchaos.workflow.tasks.figures import plot_figure as figure_job
    from chainchaos.workflow.tasks.figures import plot_panel as panel_job

    number = 1
    inputs = {}
    for name in ("chain", "ensemble"):
        inputs[name] = str(tmp_path / f"{name}.nc")
        data[name].to_netcdf(inputs[name])
    loaded = {name: xr.load_dataset(path) for name, path in inputs.items()}
    jobs = [(panel_job, {"panel": p}, f"fig{p}", plot_panel(p, loaded)) for p in panels.panels_of_figure(number)]
    jobs.append((figure_job, {"number": str(number)}, f"fig{number}", plot_figure(number, loaded)))
    for job, wildcards, stem, figure in jobs:
        outputs = {ext: str(tmp_path / "job" / f"{stem}.{ext}") for ext in ("pdf", "png")}
        job(inputs, outputs, {"dpi": 50}, wildcards)
        for path in save_figure(figure, tmp_path / "alone" / stem, dpi=50):
            assert (tmp_path / "job" / path.name).read_bytes() == path.read_bytes(), path.name


def test_mathtext_is_parsed_once_per_output_type_for_every_renderer():
    """A figure job parses hundreds of mathtext strings (log tick labels, for every panel's layout,
    PDF and PNG): style, imported above, keeps one cache for every renderer, so a second figure
    drawing the same labels parses nothing, and its PNG is the one drawn before. If a matplotlib
    release renames what style replaces, this fails instead of the jobs silently slowing down."""
    import io

    from matplotlib.figure import Figure
    from matplotlib.mathtext import MathTextParser

    def png(label):
        fig = Figure(figsize=(2, 1))
        fig.text(0.1, 0.5, label)
        out = io.BytesIO()
        fig.savefig(out, format="png", dpi=50)
        return out.getvalue()

    info = MathTextParser._parse_cached.cache_info
    assert info().maxsize >= 4096
    first = png(r"$10^{-7}\,\Lambda_{\max}$")
    misses = info().misses
    assert png(r"$10^{-7}\,\Lambda_{\max}$") == first and info().misses == misses
    png(r"$10^{-6}$")
    assert info().misses > misses


def test_a_font_subset_is_made_once_per_glyph_set_and_every_pdf_is_written_as_without_sharing(data, tmp_path,
                                                                                               monkeypatch):
    """Each PDF embeds subsets of its fonts; style keeps one per font and glyph set for the
    process. A PDF written with a kept subset is the same bytes as one subset afresh. If a
    matplotlib release renames what style replaces, this fails instead of the jobs silently
    slowing down."""
    from matplotlib.backends import _backend_pdf_ps

    shared = _backend_pdf_ps.get_glyphs_subset
    info = shared.cache_info
    fig = plot_panel("4a", data)
    first = save_figure(fig, tmp_path / "first")[0].read_bytes()
    hits = info().hits
    again = save_figure(fig, tmp_path / "again")[0].read_bytes()
    assert info().hits > hits  # every subset of the second PDF was kept from the first
    monkeypatch.setattr(_backend_pdf_ps, "get_glyphs_subset", shared.__wrapped__)
    fresh = save_figure(fig, tmp_path / "fresh")[0].read_bytes()
    assert first == again == fresh


def test_the_plotting_package_loads_no_compiled_kernel():
    """A figure job needs matplotlib and the labels and colours, not Numba: importing the plotting
    package (and the figure task) loads neither numba nor a model's kernels."""
    import subprocess
    import sys

    code = ("import sys; import chainchaos.output.plotting, chainchaos.workflow.tasks.figures; "
            "print(sorted(m for m in sys.modules if m == 'numba' or m.startswith('chainchaos.system.models')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "[]", done.stdout
