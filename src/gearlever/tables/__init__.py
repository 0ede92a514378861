"""Tables (pandas DataFrames) built from the numeric modules, and their CSV output.

This package is the only place in gearlever that imports pandas.  Columns
carry their units in their names (``phi_deg``, ``a_B_cm``).
"""
