"""Running integrations: the run settings, the sampling driver with its monitors, scenes, orbit
sets, progress reports and the one warm-up that compiles every kernel.
"""
