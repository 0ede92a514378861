"""The gear-lever differential mechanism (ZRDPM) of Alimukhamedov et al. (2020).

Modules by concern: :mod:`~gearlever.zrdpm.parameters` (the contours'
parameters, the paper's names), :mod:`~gearlever.zrdpm.model` (the
self-consistent and the tables model), :mod:`~gearlever.zrdpm.fast` (their
fast path), :mod:`~gearlever.zrdpm.published` (the published Tables I and II,
the identification of the constants they were computed with, the recovery of
analogues from point accelerations).  Radians throughout the API.

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy and gearlever's
``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``, ``data``,
``errors``, ``gears``, ``loops``; never pandas or matplotlib.
"""

from gearlever.zrdpm.model import (
    analogues,
    contour1,
    contour2,
    lever_angle,
    tables_outputs,
    tables_point_accelerations,
)
from gearlever.zrdpm.parameters import (
    CONTOUR_OF_TABLE,
    PAPER_NAMES,
    TABLE_OF_CONTOUR,
    ContourKinematics,
    TablesConstants,
    ZrdpmContour,
    x_sign,
)
from gearlever.zrdpm.published import (
    PublishedTable,
    SelfConsistentFit,
    TablesFit,
    fit_self_consistent,
    gear_acceleration_from_points,
    identify_tables_constants,
    published_table,
    recover_lever_analogues,
    recover_tables_constants,
)

__all__ = [
    "CONTOUR_OF_TABLE",
    "PAPER_NAMES",
    "TABLE_OF_CONTOUR",
    "ContourKinematics",
    "PublishedTable",
    "SelfConsistentFit",
    "TablesConstants",
    "TablesFit",
    "ZrdpmContour",
    "analogues",
    "contour1",
    "contour2",
    "fit_self_consistent",
    "gear_acceleration_from_points",
    "identify_tables_constants",
    "lever_angle",
    "published_table",
    "recover_lever_analogues",
    "recover_tables_constants",
    "tables_outputs",
    "tables_point_accelerations",
    "x_sign",
]
