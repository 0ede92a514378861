"""Printed output compared as numbers: the rule the guide's and the README's examples are checked by.

A printed line agrees with the line shown in the documentation when its text
between numbers is the same and each number agrees within the tolerance of
the computation behind it.  The last digits of a linear solve differ between
machines (OpenBLAS picks its kernels by CPU), and so do the digits a search or
an integrator carries below its own tolerance; a printed example is checked to
the digits it determines, never by its last printed digit.

* ``REL``: relative tolerance, 1e-8.  Every solver behind a printed number
  (Newton on the loop equations, the polish of a synthesis, the integrator
  of ``simulate``) meets a tolerance of 1e-10 of the size or tighter, and a
  kernel moves a well-conditioned result by a few units in its 15th digit.
* ``ABS``: absolute tolerance, 1e-11 of the largest number on the line (at
  least 1e-11): a coordinate or residual that is zero up to rounding (a pivot
  at 4.5e-08 of a link of 4, a residual of 5.6e-16 of the size) is compared
  with the line's scale, not with itself.
"""

from __future__ import annotations

import math
import re

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
REL = 1e-8
ABS = 1e-11


def _split(line: str):
    nums = [m.group(0) for m in NUMBER.finditer(line)]
    return NUMBER.sub("#", line.rstrip()), nums


def numbers_agree(shown: str, printed: str, rel: float = REL, abs_: float = ABS) -> bool:
    """``printed`` agrees with ``shown``: the same text, each number within the tolerances above.

    >>> numbers_agree("x 1.000000000001, r 5.6e-16", "x 1.000000000002, r 2.3e-16")
    True
    >>> numbers_agree("x 1.0001", "x 1.0002") or numbers_agree("x 1", "y 1")
    False
    """
    t1, n1 = _split(shown)
    t2, n2 = _split(printed)
    if t1 != t2 or len(n1) != len(n2):
        return False
    if n1 == n2:
        return True
    a = [float(v) for v in n1]
    b = [float(v) for v in n2]
    if not all(map(math.isfinite, a + b)):
        return n1 == n2
    floor = abs_ * max([1.0] + [abs(v) for v in a])
    return all(abs(x - y) <= rel * max(abs(x), abs(y)) + floor for x, y in zip(a, b, strict=True))
