"""gearlever: kinematic analysis of gear-lever differential mechanisms.

The numeric modules (``vector_loop``, ``differential``, ``structure``,
``zrdpm`` and the others) work on floats and numpy arrays and import neither
matplotlib nor pandas; ``tables`` (pandas) and ``plotting`` (matplotlib) sit on
top of them and are imported only when asked for.
"""

__version__ = "0.1.0"

from gearlever.loops import fourbar  # noqa: E402  (numpy-only)
