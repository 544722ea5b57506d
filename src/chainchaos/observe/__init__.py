"""What is measured: the formulas of the observables, their registry (what a scene file or an
orbit set can hold, and what each needs), and the reductions of time series to numbers.
"""
