"""Follower kinds of disc cams, one module per kind, behind the registry :data:`FOLLOWERS`.

Each kind subclasses :class:`~gearlever.cams.followers._base.RollerFollower`
(the roller centre's path) or :class:`~gearlever.cams.followers._base.FlatFollower`
(the face line); :mod:`gearlever.cams.design` loops over this registry.
Imports numpy, the standard library and gearlever.errors only.
"""

from gearlever.cams.followers._base import FlatFollower, FollowerKind, FollowerParams, RollerFollower
from gearlever.cams.followers.oscillating_flat import OscillatingFlat
from gearlever.cams.followers.oscillating_roller import OscillatingRoller
from gearlever.cams.followers.translating_flat import TranslatingFlat
from gearlever.cams.followers.translating_roller import TranslatingRoller

#: Follower kinds by name.
FOLLOWERS: dict[str, FollowerKind] = {
    k.name: k for k in (TranslatingRoller(), TranslatingFlat(), OscillatingRoller(), OscillatingFlat())
}

__all__ = ["FOLLOWERS", "FlatFollower", "FollowerKind", "FollowerParams", "RollerFollower"]
