"""The gear-lever differential mechanism (ZRDPM) of Alimukhamedov et al. (2020).

Parameters of the two contours, the self-consistent model and its fast path,
the tables model, the published Tables I and II and the identification of the
constants they were computed with.

Numeric core: may import numpy, scipy, :mod:`gearlever.gears.willis`,
:mod:`gearlever.loops`, :mod:`gearlever.mechanism.structure`,
:mod:`gearlever.data`, :mod:`gearlever.errors`; never pandas or matplotlib.
"""

from gearlever.zrdpm.model import (
    CONTOUR_OF_TABLE,
    PAPER_NAMES,
    TABLE_OF_CONTOUR,
    ContourKinematics,
    PublishedTable,
    SelfConsistentFit,
    TablesConstants,
    TablesFit,
    ZrdpmContour,
    analogues,
    contour1,
    contour2,
    fit_self_consistent,
    gear_acceleration_from_points,
    identify_tables_constants,
    lever_angle,
    published_table,
    recover_lever_analogues,
    recover_tables_constants,
    tables_outputs,
    tables_point_accelerations,
    x_sign,
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
