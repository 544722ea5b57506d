"""How the package's models appear in figures and tables, as plain data: each model's label, its
colour and the symbol of the amount an excitation gives it (its energy H, or the norm S of a split
model). The models (``chainchaos.system.models``) take theirs from here, and drawing a figure of
them needs no compiled kernel; a model of one's own carries its own (``Model.label``,
``Model.colour``)."""

from typing import NamedTuple


class Appearance(NamedTuple):
    """A model's label (figures and tables), colour and excitation amount symbol."""

    label: str
    colour: str
    amount: str = "H"


APPEARANCE = {
    "hertz": Appearance("Hertz", "#c62828"),
    "fput": Appearance("FPUT", "#1565c0"),
    "toda": Appearance("Toda", "#2e7d32"),
    "harmonic": Appearance("harmonic", "#616161"),
    "kg": Appearance("KG", "#6a1b9a"),
    "kg_linear": Appearance("linear KG", "#ce93d8"),
    "dnls": Appearance("DNLS", "#00838f", "S"),
    "dnls_linear": Appearance("linear DNLS", "#80deea", "S"),
}
