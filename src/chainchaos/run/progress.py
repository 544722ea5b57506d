"""Progress of a long run in its job's log: simulated time, percent done, time left."""

import sys
import time


class ProgressReporter:
    """A ``progress(t, fraction)`` callable that prints the simulated time t (of ``t_final``), the
    percentage done and the estimated wall time left to stderr, at most every ``every`` seconds
    and always at the end."""

    def __init__(self, name: str, t_final: float, every: float = 5.0, stream=None):
        # sys.stderr is looked up when printing, so a redirected stderr (the job's log) is honoured
        self.name, self.t_final, self.every, self.stream = name, t_final, every, stream
        self.start = self.last = time.perf_counter()

    def __call__(self, t: float, fraction: float) -> None:
        now = time.perf_counter()
        if now - self.last < self.every and fraction < 1.0:
            return
        self.last = now
        elapsed = now - self.start
        left = elapsed * (1.0 - fraction) / fraction if fraction > 0 else float("nan")
        print(f"[{self.name}] t = {t:.6g} / {self.t_final:g} ({100 * fraction:5.1f}%), "
              f"elapsed {elapsed:.1f} s, left ~{left:.1f} s", file=self.stream or sys.stderr, flush=True)
