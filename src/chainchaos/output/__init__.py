"""Documents: the figures (one style), the captions of the HTML report, the run summary, what to
cite, the manuscript and its section beyond the paper. Above the paper and the studies whose
results they show; the files they read and write are ``chainchaos.records``.
"""
