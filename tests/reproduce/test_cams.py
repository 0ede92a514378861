"""The law/cam step of ``make reproduce``: one SVAJ + profile figure per shipped law."""

from gearlever.reproduce import cams


def test_reproduce_cams_writes_a_figure_per_shipped_law(tmp_path):
    lines = cams.run(tmp_path, tmp_path)
    assert len(lines) == len(cams.CASES)
    for name in cams.CASES:
        assert (tmp_path / f"cam_{name}.png").read_bytes()[:4] == b"\x89PNG"
    assert all("undercut False" in ln for ln in lines)
