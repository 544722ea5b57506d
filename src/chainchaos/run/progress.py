"""Progress of a long job in its log: how far it is, the share done, the time elapsed and left.

One format for every job that runs longer than a minute: ``[name] <how far> (<share>%), elapsed
<s> s, left ~<s> s``, at most every ``every`` seconds and always at the end. How far is the
simulated time of a run (:class:`ProgressReporter`) or the orbits done of an ensemble
(:class:`OrbitProgress`).
"""

import sys
import time


class _Reporter:
    """Prints :func:`line` to stderr at most every ``every`` seconds, and always at the end."""

    def __init__(self, name: str, every: float = 5.0, stream=None):
        # sys.stderr is looked up when printing, so a redirected stderr (the job's log) is honoured
        self.name, self.every, self.stream = name, every, stream
        self.start = self.last = time.perf_counter()

    def report(self, how_far: str, fraction: float) -> None:
        now = time.perf_counter()
        if now - self.last < self.every and fraction < 1.0:
            return
        self.last = now
        elapsed = now - self.start
        left = elapsed * (1.0 - fraction) / fraction if fraction > 0 else float("nan")
        print(f"[{self.name}] {how_far} ({100 * fraction:5.1f}%), elapsed {elapsed:.1f} s, left ~{left:.1f} s",
              file=self.stream or sys.stderr, flush=True)


class ProgressReporter(_Reporter):
    """A ``progress(t, fraction)`` callable: the simulated time t of ``t_final``."""

    def __init__(self, name: str, t_final: float, every: float = 5.0, stream=None):
        super().__init__(name, every, stream)
        self.t_final = t_final

    def __call__(self, t: float, fraction: float) -> None:
        self.report(f"t = {t:.6g} / {self.t_final:g}", fraction)


class OrbitProgress(_Reporter):
    """A ``progress(done, total)`` callable: the orbits done of ``total`` (``done`` counts an
    orbit part-way through by the share of its steps taken)."""

    def __call__(self, done: float, total: int) -> None:
        self.report(f"{done:.1f} of {total} orbits", done / total if total else 1.0)
