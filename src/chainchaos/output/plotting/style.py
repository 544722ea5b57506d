"""The figure style of the paper: sizes, fonts, colours, axis labels, and byte-stable saving.

Sizes follow a two-column journal: a single panel is one column (3.4 in) wide, a composite of
several panels per row spans both columns (7.0 in). The model is nondimensional (docs/conventions.md#units),
so the labels give times in units of 1/omega_max and frequencies in units of omega_max.
"""

import functools
from pathlib import Path

import matplotlib

# plain data and the standard library: a figure job loads no compiled kernel (tests/output)
from chainchaos.observe.labels import LABELS
from chainchaos.records.atomic import atomic_output
from chainchaos.system.appearance import APPEARANCE, Appearance

# Figures are drawn on matplotlib.figure.Figure, never through pyplot, and only ever written to
# files (PNG by Agg, PDF by matplotlib's PDF backend); a caller's pyplot gets Agg too.
matplotlib.use("Agg")


def _shared_mathtext_cache(size: int = 4096) -> None:
    """One mathtext cache for every renderer of the process. matplotlib keeps the last 50 parses
    per parser, and every renderer has its own parser: each panel's layout pass, PDF and PNG
    parsed every log tick label again (hundreds of parses per figure job, a quarter of its time).
    A parse depends on the parser's output type only (the grammar is one class-wide object), so
    the parses are kept per output type, whichever renderer asked first."""
    from matplotlib.mathtext import MathTextParser

    cached = getattr(MathTextParser, "_parse_cached", None)
    unwrapped = getattr(cached, "__wrapped__", None)
    if unwrapped is None:  # matplotlib changed, or already replaced here
        return
    parsers = {}

    @functools.lru_cache(size)
    def parse(output_type, s, dpi, prop, antialiased, load_glyph_flags):
        return unwrapped(parsers[output_type], s, dpi, prop, antialiased, load_glyph_flags)

    def _parse_cached(self, s, dpi, prop, antialiased, load_glyph_flags):
        parsers.setdefault(self._output_type, self)
        return parse(self._output_type, s, dpi, prop, antialiased, load_glyph_flags)

    _parse_cached.cache_info = parse.cache_info
    MathTextParser._parse_cached = _parse_cached


_shared_mathtext_cache()


def _shared_font_subsets(size: int = 256) -> None:
    """One TrueType subset per font and glyph set for every PDF of the process. Each PDF embeds
    the subsets of the fonts it uses (fontTools, about 15 ms each, a tenth of a figure job), and
    the panels of a figure mostly use the same glyphs: 60 % of a figure job's subsets were
    repeats. A subset is kept as the bytes of the font; every PDF gets its own font object read
    from them, so each file is written as before."""
    from io import BytesIO

    from fontTools.ttLib import TTFont
    from matplotlib.backends import _backend_pdf_ps

    original = getattr(_backend_pdf_ps, "get_glyphs_subset", None)
    if original is None or hasattr(original, "cache_info"):  # matplotlib changed, or already replaced here
        return

    @functools.lru_cache(size)
    def subset(fontfile, face, glyphs: frozenset):
        with original(fontfile, set(glyphs)) as result:
            return _backend_pdf_ps.font_as_file(result.font).getvalue(), dict(result.glyph_index_map)

    def get_glyphs_subset(fontfile, glyphs):
        # the face is part of the key: a FontPath hashes and compares as its path alone
        data, index_map = subset(fontfile, getattr(fontfile, "face_index", 0), frozenset(glyphs))
        font = TTFont(BytesIO(data), recalcBBoxes=False, recalcTimestamp=False)  # saved again as it was read
        return _backend_pdf_ps.SubsetResults(font, dict(index_map))._as_cm()

    get_glyphs_subset.cache_info, get_glyphs_subset.__wrapped__ = subset.cache_info, original
    _backend_pdf_ps.get_glyphs_subset = get_glyphs_subset


_shared_font_subsets()

COLUMN_WIDTH = 3.4  # in, one column: a single panel
PAGE_WIDTH = 7.0  # in, both columns: composites
PANEL_HEIGHT = 2.55  # in, a single panel
ROW_HEIGHT = {1: 2.55, 2: 2.45, 3: 2.1, 4: 1.8}  # in, a composite row by its number of panels
DPI = 300

RC = {
    # STIX, shipped with matplotlib (the files do not depend on the host): Times-like, as APS
    # journals set the text, with its own math fonts. Embedding a subset of it in each PDF costs
    # half what DejaVu Sans does (smaller layout tables), a quarter of a figure job.
    "font.family": "STIXGeneral",
    "mathtext.fontset": "stix",
    "font.size": 8,
    "axes.labelsize": 8,
    "axes.titlesize": 7,
    "legend.fontsize": 6.5,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "axes.linewidth": 0.6,
    "xtick.major.width": 0.6,
    "ytick.major.width": 0.6,
    "xtick.minor.width": 0.4,
    "ytick.minor.width": 0.4,
    "lines.linewidth": 1.0,
    "axes.titlepad": 3.0,
    "legend.frameon": False,
    "legend.handlelength": 1.8,
    "legend.columnspacing": 1.0,
    "pdf.fonttype": 42,  # embedded TrueType: text stays text for the journal
    "savefig.dpi": DPI,
    "figure.dpi": 100,
}

# One colour map for every density map (energy density, DVD, modal energies); floor of its log scale.
MAP_CMAP = "viridis"
MAP_FLOOR = 1e-8
GAP_CMAP = "viridis"  # open bonds light (yellow), as in the paper's Fig. 7

HERTZ_RED = APPEARANCE["hertz"].colour  # also of the chain's drawing (Fig. 1b)
# Several energies of one model in a panel: lower energies solid and lighter, higher ones dashed.
ENERGY_LINESTYLES = ("-", "--", "-.", ":")
ENERGY_SHADES = (0.0, 0.35, 0.55, 0.7)  # fraction of white mixed in, by energy rank, highest first
RAW_ALPHA = 0.22  # raw values drawn faintly behind a smoothed curve
# DVD profile times, in order (the paper's Fig. 5: red, magenta, blue, black), on the map and profiles.
PROFILE_COLOURS = ("#d62728", "#c71fc7", "#1f5fd6", "black")
PROFILE_LINESTYLES = (":", "--", "-", "-.")

TIME_LABEL = r"$t$ [$1/\omega_{\max}$]"
SITE_LABEL = r"$n$ (site)"
BOND_LABEL = r"$n$ (bond, sites $n-1$ to $n$)"
MODE_LABEL = r"$k$ (mode)"
RANK_LABEL = r"$k$ (rank)"
FREQUENCY_LABEL = r"$\omega_k$ [$\omega_{\max}$]"
# the axis labels of scene observables are those of their registry entries
ENERGY_DENSITY_LABEL = LABELS["energy_density"]
DVD_LABEL = LABELS["dvd"]
MODE_ENERGY_LABEL = r"$v_k$"  # the modal energies normalised per sample
P_LABEL = LABELS["participation"]
PD_LABEL = LABELS["dvd_participation"]
MEAN_P_LABEL = r"$\langle P \rangle$"
MLCE_LABEL = LABELS["mlce"]
ETA_LABEL = LABELS["eta"]
GAP_FRACTION_LABEL = LABELS["gap_fraction"]
GAP_COUNT_LABEL = LABELS["n_gaps"]

PDF_METADATA = {"CreationDate": None, "ModDate": None, "Creator": "chainchaos"}
PNG_METADATA = {"Software": "chainchaos"}  # matplotlib writes no timestamp into PNG files


def context():
    """The style as a context: plotting and saving run inside it, so importing the package leaves
    the caller's rcParams alone."""
    return matplotlib.rc_context(RC)


def composite_size(rows: int, columns: int) -> tuple[float, float]:
    """Figure size (in) of a composite: one column wide for a single column of panels, else two."""
    width = COLUMN_WIDTH if columns == 1 else PAGE_WIDTH
    return width, rows * ROW_HEIGHT.get(columns, ROW_HEIGHT[4])


def _appearance(model: str) -> Appearance:
    """The package's table (``system.appearance``) for its models; a model of one's own, loaded by
    the job that draws it, from the registry (which compiles its kernels)."""
    if model in APPEARANCE:
        return APPEARANCE[model]
    from chainchaos.system.models import get_model

    own = get_model(model)
    return Appearance(own.label, own.colour, "S" if own.is_split else "H")


def model_colour(model: str) -> str:
    """The model's colour: Hertz red, FPUT blue."""
    return _appearance(model).colour


def model_label(model: str) -> str:
    """How figures and tables name the model (e.g. 'Hertz', 'FPUT')."""
    return _appearance(model).label


def amount_symbol(model: str) -> str:
    """What an excitation of ``model`` is given by: its energy H, or the norm S of a split model."""
    return _appearance(model).amount


def scene_label(model: str, energy: float) -> str:
    """E.g. ``Hertz, $H = 0.25$`` (``DNLS, $S = 21$``)."""
    return f"{model_label(model)}, ${amount_symbol(model)} = {energy:g}$"


def time_text(t: float) -> str:
    """A time to three significant digits as mathtext (no dollars): 16.8, 10^{3}, 1.68\\times10^{4}."""
    text = f"{t:.3g}"
    if "e" not in text:
        return text
    mantissa, exponent = text.split("e")
    power = f"10^{{{int(exponent)}}}"
    return power if mantissa == "1" else rf"{mantissa}\times{power}"


def save_figure(fig, path_stem, dpi: int = DPI) -> tuple[Path, Path]:
    """Write ``<path_stem>.pdf`` and ``<path_stem>.png`` byte-stably and atomically.

    Same figure, same bytes: a fixed ``dpi`` (of the PNG and of the PDF's rasterised maps), no
    dates in the PDF, no timestamps in the PNG, and the layout computed once and then kept (see
    ``_freeze_layout``). Each file is written to a temporary file in the target directory and
    renamed into place, so an interrupted run leaves no complete-looking file. Returns the paths.
    """
    stem = Path(path_stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    paths = Path(f"{stem}.pdf"), Path(f"{stem}.png")
    with context():
        _freeze_layout(fig)
        _write_atomically(fig, paths[0], "pdf", dpi, PDF_METADATA)
        _write_atomically(fig, paths[1], "png", dpi, PNG_METADATA)
    return paths


def _freeze_layout(fig) -> None:
    """Run the figure's layout engine once and keep its result. Constrained layout starts from the
    current positions, so every draw would shift them slightly: a frozen layout gives the PDF and
    the PNG the same positions and every later save the same bytes. The engine runs as the
    first draw would run it (after the axes' aspects), without the rest of that draw: a full
    pass over every tick and label that the PDF's draw makes again."""
    engine = fig.get_layout_engine()
    if engine is not None:
        fig._get_draw_artists(fig._get_renderer())  # applies the axes' aspects and locators
        engine.execute(fig)
        fig.set_layout_engine("none")


def _write_atomically(fig, path: Path, fmt: str, dpi: int, metadata: dict) -> None:
    with atomic_output(path) as tmp:
        fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
