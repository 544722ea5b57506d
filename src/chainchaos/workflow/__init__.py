"""The glue to Snakemake and the shell: one task per workflow rule (``tasks``), the config check
and its documentation, and the ``chainchaos`` command.
"""
