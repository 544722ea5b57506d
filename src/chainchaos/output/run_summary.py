"""What a run of the paper did, read from its own files: the table the HTML report's front page
points to (rule run_summary). Nothing here comes from the config: a run pinned to an archive, a
quick scale or a changed key each say what they did."""

import csv
import io
import math
from collections import Counter

from chainchaos.records.formatting import plain_number


def plain_time(t: float) -> str:
    """A time as the project writes it: 10^5 for a power of ten, else its plain digits."""
    exponent = math.log10(t) if t > 0 else float("nan")
    if math.isfinite(exponent) and exponent == round(exponent) and abs(exponent) >= 3:
        return f"10^{round(exponent)}"
    return plain_number(t)


def _chain_rows(chain) -> list[tuple[str, str]]:
    a = chain.attrs
    rows = [("chain", (f"seed {int(a['seed'])}, N = {chain.sizes['site']}, "
                       f"alpha = {plain_number(a['alpha'])}"))]
    source = str(a.get("selection_source", ""))
    if int(a.get("selection_pinned", 0)):
        how = "pinned by the config (search.pinned_seed)"
    elif source.startswith("data/") or "search_full" in source:
        how = (f"the archived full search {source}: {int(a['selection_seeds_scanned'])} seeds scanned, "
               f"{int(a['selection_candidates'])} candidates passed the linear rule, "
               f"{int(a.get('selection_search_scored', -1))} scored, score {plain_number(a['selection_search_score'], 4)}")
    else:
        how = (f"this run's realization search ({source}): {int(a['selection_search_candidates'])} candidates, "
               f"score {plain_number(a['selection_search_score'], 4)}")
    rows.append(("chain chosen by", how))
    rows.append(("excited bead, linear mode", f"{int(a['selection_site'])}, mode {int(a['selection_mode'])}"))
    return rows


def summary_rows(chain, scene, energy_scan, disorder, claims_csv: str,
                 environment: str | None = None) -> list[tuple[str, str]]:
    """(what, value) rows: the chain and how it was chosen, the scenes' integration, the energy
    scan's and the disorder statistics' sizes and sources, the claims' verdicts and, when given,
    whether the environment is the locked one (``chainchaos.records.environment.lock_status``)."""
    rows = _chain_rows(chain)
    s = scene.attrs
    rows.append(("scenes", f"{s['integrator']} at dt = {plain_number(s['dt'])}, to t = {plain_time(float(s['t_final']))}"))
    e = energy_scan
    rows.append(("energy scan", (f"{e.sizes['energy']} energies, H = {plain_number(e.energy.values[0])} to "
                                 f"{plain_number(e.energy.values[-1])}, to t = {plain_time(float(e.attrs['t_final']))}, "
                                 f"dt = {plain_number(e.attrs['dt'])}")))
    d = disorder
    origin = d.attrs.get("kept_file") or "this run's own disorder statistics"
    rows.append(("disorder statistics", (f"{d.sizes['realization']} realizations x {d.sizes['energy']} energies, "
                                         f"to t = {plain_time(float(d.attrs['t_final']))}: {origin}")))
    with open(claims_csv, newline="") as f:
        verdicts = Counter(row["verdict"] for row in csv.DictReader(f))
    rows.append(("claims", ", ".join(f"{n} {v}" for v, n in sorted(verdicts.items()))))
    if environment is not None:
        rows.append(("environment", environment))
    return rows


def summary_csv(rows: list[tuple[str, str]]) -> str:
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["what", "this run"])
    writer.writerows(rows)
    return out.getvalue()
