"""The reproduce step of the published textbook problems writes every answer beside the model's."""

import pandas as pd

from gearlever.data import read_records
from gearlever.flywheels.published import ANSWERS
from gearlever.reproduce import textbook


def test_textbook_step_writes_every_published_answer_within_tolerance(tmp_path):
    lines = textbook.run(tmp_path, tmp_path)
    df = pd.read_csv(tmp_path / "textbook_checks.csv", dtype={"example": str})
    published = read_records(ANSWERS)
    assert len(df) == len(published) and bool(df.within.all())
    assert list(df.example) == [r["example"] for r in published]
    assert df.source.str.contains("Khurmi & Gupta, Theory of Machines").all()
    assert f"{len(df)}/{len(df)} published answers" in lines[0]


def test_textbook_step_output_is_identical_on_a_second_run(tmp_path):
    textbook.run(tmp_path, tmp_path)
    first = (tmp_path / "textbook_checks.csv").read_bytes()
    textbook.run(tmp_path, tmp_path)
    assert (tmp_path / "textbook_checks.csv").read_bytes() == first
