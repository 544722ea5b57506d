"""The realization search: the linear rule (``selection``), the stages that run the paper's
statements on candidate chains (``stages``), its figure (``plots``) and the manuscript's tables
and numbers of it (``report``).
"""
