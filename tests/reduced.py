"""One orbit's numbers outside a study, for tests that compare them with a study's group or a kept file."""

import math

from chainchaos.run.orbits import integrate
from chainchaos.studies.study.orbits import reduce_orbit


def reduced_orbits(orbits, settings):
    """Each orbit integrated (orbits.integrate) and reduced as a study's orbit is
    (studies.study.orbits.reduce_orbit), with its times and series P, ln|v| and eta: one orbit's
    numbers outside a study, to compare with a study's group or a kept file."""
    times, runs = integrate(orbits, settings, gali_stop=math.log(settings.gali_threshold))
    return [{**reduce_orbit(times, r, settings), "times": times, "participation": r["participation"],
             "log_growth": r["log_growth"], "eta": r["eta"]} for r in runs]
