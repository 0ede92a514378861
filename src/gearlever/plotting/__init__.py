"""Figures drawn with matplotlib from the numeric modules' results.

This package is the only place in gearlever that imports ``matplotlib.pyplot``.
Every drawing function takes ``ax=None`` (a new figure is made when it is
None) and returns the Axes (or the Figure, for multi-panel drawings).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import matplotlib and gearlever's
``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``, ``cams``,
``curves``, ``data``, ``dynamics``, ``errors``, ``gears``, ``laws``, ``loops``,
``mechanism``, ``synthesis``, ``trains``, ``zrdpm``; never the CLI.
"""
