"""Size caps and shared argument checks of the tooth-number design modules.

Every size argument of :mod:`gearlever.trains.design` and
:mod:`gearlever.trains.search` is bounded so that no call can exhaust the
memory or run for minutes; the caps are derived in the docstrings of the
constants below and named in every refusal.
"""

from __future__ import annotations

from gearlever import _validate
from gearlever.errors import GearleverError

#: Most pairs (drivers = followers = K) of a search or design.  The exact
#: search keeps products of K teeth below 2**52 (exact in float64), and the
#: multiset count sums over the p(K) partitions of K (p(12) = 77); 12 pairs
#: of the least involute wheel already give 24**12 = 3.7e16 > 2**52.
MAX_PAIRS = 12
#: Largest tooth number accepted.  A one-pair search over 1..MAX_TEETH is
#: instantaneous; larger wheels only enter through bigger search spaces,
#: which :data:`MAX_SPACE_CAP` bounds.
MAX_TEETH = 10_000
#: Default refusal size of :func:`~gearlever.trains.search.search_best`:
#: tooth multisets per side (about 3 s and 0.5 GB at most on one core).
DEFAULT_MAX_SPACE = 5_000_000
#: Largest ``max_space`` accepted: the sorted product lists grow to about
#: K x max_space entries of 8 bytes (several arrays at once), so 20 million
#: multisets per side keeps the peak near 2 GB.
MAX_SPACE_CAP = 20_000_000
#: Default number of optimal tooth sets listed by a search.
DEFAULT_LIMIT = 20
#: Most optimal tooth sets listed (each is factored back into teeth and
#: paired for even wear, about a millisecond each); the count is always complete.
MAX_LIMIT = 1000
#: Most designs kept by :func:`~gearlever.trains.design.design_train`.
MAX_KEEP = 1000


def capped_int(name: str, value, cap: int) -> int:
    """A positive integer no larger than ``cap`` (the message names both)."""
    v = _validate.positive_int(name, value)
    if v > cap:
        raise GearleverError(f"{name} must be at most {cap:,}, got {v:,}")
    return v


def teeth_range(min_teeth, max_teeth) -> tuple[int, int]:
    """Check a tooth range: 1 <= min_teeth <= max_teeth <= MAX_TEETH."""
    lo = capped_int("min_teeth", min_teeth, MAX_TEETH)
    hi = capped_int("max_teeth", max_teeth, MAX_TEETH)
    if lo > hi:
        raise GearleverError(f"min_teeth must not exceed max_teeth, got min_teeth={lo} > max_teeth={hi}")
    return lo, hi
