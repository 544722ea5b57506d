"""Chaos indicators beyond the paper's Λ, as products of the pipeline: the Lyapunov spectra of the
most chaotic scenes (:mod:`~chainchaos.studies.indicators.spectra`) and their figure
(:mod:`~chainchaos.output.plotting.indicators`, imported on demand: it pulls in matplotlib).
"""
