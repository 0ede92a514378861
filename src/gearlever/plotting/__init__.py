"""Figures drawn with matplotlib from the numeric modules' results.

This package is the only place in gearlever that imports ``matplotlib.pyplot``.
Every drawing function takes ``ax=None`` (a new figure is made when it is
None) and returns the Axes (or the Figure, for multi-panel drawings).
"""
