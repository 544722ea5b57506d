"""Files and documents: NetCDF and text written atomically with CF attributes and provenance,
number formatting, the figures (one style), the captions of the HTML report and the manuscript.
"""
