"""Table of the published textbook problems of epicyclic torques, crank effort and flywheels, solved by the model."""

from __future__ import annotations

import pandas as pd

from gearlever.flywheels.published import TextbookCheck, textbook_checks
from gearlever.tables._common import frame

#: The book the worked examples come from (edition of the pages cited).
SOURCE = "Khurmi & Gupta, Theory of Machines, 14th ed. (2009)"


def textbook_table(checks: TextbookCheck | None = None) -> pd.DataFrame:
    """One row per published answer: source, example, page, quantity, unit, published, computed, deviation.

    Examples
    --------
    >>> df = textbook_table()
    >>> bool(df.within.all()), list(df.columns[:4])
    (True, ['source', 'example', 'page', 'quantity'])
    """
    c = textbook_checks() if checks is None else checks
    return frame(
        {
            "source": [f"{SOURCE}, Ex. {e}, p. {p}" for e, p in zip(c.example, c.page, strict=True)],
            "example": c.example,
            "page": c.page,
            "quantity": c.quantity,
            "unit": c.unit,
            "published": c.published,
            "computed": c.computed,
            "deviation": [float(f"{x:.3g}") for x in c.deviation],  # 3 digits: machine-independent
            "tolerance": c.tolerance,
            "within": c.within,
            "basis": c.basis,
        }
    )
