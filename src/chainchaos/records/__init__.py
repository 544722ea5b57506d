"""The files the package writes and reads: NetCDF written atomically with CF attributes and
provenance (``cf``, ``io``, ``provenance``, ``environment``), results kept as data with the
settings that key them (``kept``), numbers as text (``formatting``), and the schemas config and
study files are checked against (``schema``). Below the runs, studies and documents that write
them; above the system, engines and observables whose results they hold.
"""
