"""Tables (pandas DataFrames) built from the numeric modules, and their CSV output.

This package is the only place in gearlever that imports pandas.  Columns
carry their units in their names (``phi_deg``, ``a_B_cm``).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import pandas and gearlever's ``_format``,
``_frame``, ``_io``, ``_progress``, ``_result``, ``_validate``, ``cams``,
``curves``, ``data``, ``dynamics``, ``errors``, ``gears``, ``laws``, ``loops``,
``mechanism``, ``synthesis``, ``trains``, ``zrdpm``.
"""
