"""Symplectic schemes for Hamiltonians split into three exactly solvable parts A + B + C.

A scheme is a table: one step of size dt is the stages (part_i, c_i) in turn, each the exact flow
of part_i (0 = A, 1 = B, 2 = C; ``models.split``) for a time c_i dt. The base scheme is the
second-order

    ABC^2(t) = A(t/2) B(t/2) C(t) B(t/2) A(t/2),

and the others are symmetric compositions ABC^2(g_1 dt) ABC^2(g_2 dt) ... ABC^2(g_s dt) with
published weights g_i (summing to 1), written out as stages with the two A flows where one
ABC^2 meets the next merged into one (A(a) A(b) = A(a + b): A's flow is exact). Skokos,
Gerlach, Bodyfelt, Papamikos & Eggl, Phys. Lett. A 378, 1809 (2014) built them for the DNLS;
Danieli, Many Manda, Mithun & Skokos, Math. Eng. 1, 447 (2019) measured s9ABC6 and s11ABC6 best
at moderate accuracy, s17ABC8 at high accuracy.
"""

from dataclasses import dataclass

import numpy as np

from chainchaos.errors import require

#: The parts, by their index in a scheme's ``parts``.
PARTS = ("A", "B", "C")


@dataclass(frozen=True, kw_only=True)
class SplitScheme:
    """A three-part splitting scheme, an entry of :data:`SPLIT_SCHEMES`.

    Parameters
    ----------
    name : str
        Its key in ``SPLIT_SCHEMES`` and in configs (``integrator``).
    order : int
        Its order: the energy error of a run scales as dt^order.
    parts : numpy.ndarray of shape (s,), dtype int
        The part of every stage: 0 = A, 1 = B, 2 = C.
    coefficients : numpy.ndarray of shape (s,)
        The time of every stage, in units of dt (each part's sum to 1).
    weights : tuple of float
        The composition weights g_i of ABC^2.
    reference : str
        Where it is published.
    """

    name: str
    order: int
    parts: np.ndarray
    coefficients: np.ndarray
    weights: tuple
    reference: str

    @property
    def stages(self) -> int:
        """Flows per step."""
        return int(self.parts.size)


def compose(weights) -> tuple[np.ndarray, np.ndarray]:
    """The stages (parts, coefficients) of ABC^2(g_1 dt) ... ABC^2(g_s dt), adjacent A flows merged.

    Parameters
    ----------
    weights : sequence of float
        The composition weights g_i.

    Returns
    -------
    parts : numpy.ndarray of int
        0, 1, 2 for A, B, C.
    coefficients : numpy.ndarray
        The time of every stage in units of dt.
    """
    stages: list[list] = []
    for g in weights:
        for part, c in ((0, g / 2), (1, g / 2), (2, g), (1, g / 2), (0, g / 2)):
            if stages and stages[-1][0] == part == 0:
                stages[-1][1] += c
            else:
                stages.append([part, c])
    return np.array([p for p, _ in stages], dtype=np.int64), np.array([c for _, c in stages])


def _build_table() -> dict[str, SplitScheme]:
    table = {}

    def add(name, order, half, middle, reference):
        weights = tuple(half) + (() if middle is None else (middle,)) + tuple(half[::-1])
        parts, coefficients = compose(weights)
        for part in range(3):
            assert abs(coefficients[parts == part].sum() - 1) < 1e-14, (name, part)
        table[name] = SplitScheme(name=name, order=order, parts=parts, coefficients=coefficients, weights=weights,
                                  reference=reference)

    add("ABC2", 2, [], 1.0, "Skokos et al., Phys. Lett. A 378, 1809 (2014), ABC^2")
    # Yoshida's triple jump: x1 = 1/(2 - 2^(1/3)), x0 = -2^(1/3)/(2 - 2^(1/3))
    x1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
    add("ABC4", 4, [x1], 1.0 - 2.0 * x1,
        "Yoshida, Phys. Lett. A 150, 262 (1990) on ABC^2: Skokos et al. (2014), ABC^4_[Y]")
    # Kahan & Li, Math. Comput. 66, 1089 (1997), s9odr6a
    add("s9ABC6", 6, [0.39216144400731413928, 0.33259913678935943860, -0.70624617255763935981,
                      0.08221359629355080023], 0.79854399093482996340,
        "Kahan & Li, Math. Comput. 66, 1089 (1997), s9odr6a, on ABC^2: Skokos et al. (2014)")
    # Sofroniou & Spaletta, Optim. Methods Softw. 20, 597 (2005), s11odr6
    add("s11ABC6", 6, [0.21375583945878254555518066964857, 0.18329381407425713911385974425217,
                       0.17692819473098943794898811709929, -0.44329082681170215849622829626258,
                       0.11728560432865935385403585669228], 0.50405474843802736404228688323539,
        "Sofroniou & Spaletta, Optim. Methods Softw. 20, 597 (2005), s11odr6, on ABC^2: Skokos et al. (2014)")
    # Kahan & Li (1997), s17odr8a
    add("s17ABC8", 8, [0.13020248308889008087881763, 0.56116298177510838456196441, -0.38947496264484728640807860,
                       0.15884190655515560089621075, -0.39590389413323757733623154, 0.18453964097831570709183254,
                       0.25837438768632204729397911, 0.29501172360931029887096624], -0.60550853383003451169892108,
        "Kahan & Li, Math. Comput. 66, 1089 (1997), s17odr8a, on ABC^2: Skokos et al. (2014)")
    return table


#: Every three-part scheme, by name.
SPLIT_SCHEMES: dict[str, SplitScheme] = _build_table()


def get_split_scheme(name: str) -> SplitScheme:
    """The three-part scheme called ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`SPLIT_SCHEMES`.

    Returns
    -------
    SplitScheme
        Its entry.

    Raises
    ------
    ParameterError
        For a name not in ``SPLIT_SCHEMES`` (the message lists those that are).
    """
    require(name in SPLIT_SCHEMES, "integrator", name, f"one of {sorted(SPLIT_SCHEMES)} for a split model")
    return SPLIT_SCHEMES[name]
