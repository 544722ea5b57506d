"""The paper as data: its panels and scenes, its statements, the criteria that turn its words into
numbers, the verdicts on ensembles of orbits, and the claims table.
"""
