"""Numbers and messages (issue 25, section 5): each hostile class once, refused in one line naming the user's input.

One parametrized case per class: the command line, the words its one line on
stderr must hold (the user's flag or file element and what it must be), exit
status 2, no traceback (also none printed when the garbage collector runs
after the command: a failed dask client used to print one), and no file left
behind.  Cases run in-process in a sandbox folder; the dask scheduler cases
use a short connection timeout.  Then the inputs that users type and that are
now accepted (a byte-order mark, ``--budget 1e5``, ``--length-range 0 HI``),
the drawing that says which inputs it held, and library-level tests of each
fix where it lives.
"""

from __future__ import annotations

import contextlib
import gc
import io
import math
from pathlib import Path

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.errors import GearleverError

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
ENGINE = (EXAMPLES / "engine.toml").read_text()
FIVEBAR = (EXAMPLES / "fivebar_two_inputs.toml").read_text()
PLANETARY = (EXAMPLES / "simple_planetary.csv").read_text()
POSES = (EXAMPLES / "motion_poses.csv").read_text()

ROUGH = """[mechanism]
name = "four-bar from a rough sketch"
units = "mm"
[points]
O2 = [0, 0]
O4 = [40, 0]
A = [11, 1]
B = [44, 31]
P = [30, 44]
[links]
ground = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B", "P"]
rocker = ["O4", "B"]
[[inputs]]
link = "crank"
[lengths]
crank = CRANK
coupler = 45.0
rocker = 30.0
"""

PATH = "x,y\n0,0\n1,1\n2,1.5\n3,1\n4,0\n"

#: file name -> text, written in every sandbox
FILES = {
    "mass.toml": FIVEBAR.replace("left  = { mass = 0.05", "left  = { mass = 1e308"),
    "load.toml": FIVEBAR.replace("force = [0.0, -500.0]", "force = [0.0, -1e308]"),
    "engine.toml": ENGINE,
    "fivebar.toml": FIVEBAR,
    "planetary.csv": PLANETARY,
    "rough.toml": ROUGH.replace("CRANK", "1e308"),
    "huge.csv": "x,y\n0,0\n1,1\n2,1e308\n3,1\n4,0\n",
    "path.csv": PATH,
    "three.csv": "x,y\n0,0,7\n1,1\n2,1.5\n3,1\n4,0\n",
    "repeat.csv": "x,y\n0,0\n1,1\n1,1\n3,1\n4,0\n",
    "repeat_timed.csv": "x,y,input_deg\n0,0,0\n1,1,30\n1,1,30\n3,1,90\n4,0,120\n",
    "poses3.csv": "\n".join(POSES.splitlines()[:4]) + "\n",
}

SYN = ["synthesize", "path"]

#: class -> (argv, words of the one line on stderr)
CASES = {
    "mass-1e308-forces": (["mechanism", "forces", "mass.toml", "--points", "3"], ["mass.toml", "masses.left.mass"]),
    "mass-1e308-simulate": (
        ["mechanism", "simulate", "mass.toml", "--rpm", "left=60", "--rpm", "right=30", "--time", "0.1"],
        ["mass.toml", "masses.left.mass", "at most"],
    ),
    "load-1e308-forces": (["mechanism", "forces", "load.toml", "--points", "3"], ["load.toml", "loads[0].force"]),
    "simulate-torque-1e308": (
        ["mechanism", "simulate", "engine.toml", "--torque", "1e308", "--rpm", "60", "--time", "1"],
        ["--torque", "crank", "at most"],
    ),
    "simulate-torque-1e90": (
        ["mechanism", "simulate", "engine.toml", "--torque", "1e90", "--rpm", "60", "--time", "1"],
        ["--time", "--torque", "evaluations"],
    ),
    "network-torque-1e308": (
        ["network", "planetary.csv", "--inputs", "sun", "--torque", "sun=1e308", "--loads", "carrier"],
        ["--torque", "carrier", "must be smaller"],
    ),
    "network-speed-1e308": (
        ["network", "planetary.csv", "--inputs", "sun", "--torque", "carrier=1e3", "--loads", "sun"]
        + ["--speeds", "sun=1e308"],
        ["--torque", "power of sun", "speeds"],
    ),
    "assemble-length-1e308": (["mechanism", "assemble", "rough.toml"], ["rough.toml", "lengths.crank", "at most"]),
    "path-csv-1e308": ([*SYN, "huge.csv", "--out", "m.toml"], ["POINTS", "huge.csv", "line 4", "y", "at most"]),
    "fixed-pivots-nan": (
        ["synthesize", "motion", "poses3.csv", "--fixed-pivots", "nan", "0", "1", "0", "--out", "m.toml"],
        ["--fixed-pivots", "finite", "nan"],
    ),
    "budget-below-minimum": ([*SYN, "path.csv", "--out", "m.toml", "--budget", "100"], ["--budget", "480"]),
    # the length range 0 50 passes its check: the refusal is the budget's (run before any search)
    "length-range-0-accepted": (
        [*SYN, "path.csv", "--out", "m.toml", "--length-range", "0", "50", "--budget", "100"],
        ["--budget", "480"],
    ),
    "scheduler-nonsense": ([*SYN, "path.csv", "--out", "m.toml", "--scheduler", "nonsense"], ["--scheduler", "HOST"]),
    "scheduler-empty": ([*SYN, "path.csv", "--out", "m.toml", "--scheduler", ""], ["--scheduler", "HOST:PORT"]),
    "scheduler-file-url": (
        [*SYN, "path.csv", "--out", "m.toml", "--scheduler", "file:///tmp/x"],
        ["--scheduler", "tcp"],
    ),
    "scheduler-unreachable": (
        [*SYN, "path.csv", "--out", "m.toml", "--budget", "1000", "--scheduler", "tcp://127.0.0.1:9"],
        ["--scheduler", "no dask scheduler answered"],
    ),
    "scheduler-bad-port": (
        [*SYN, "path.csv", "--out", "m.toml", "--scheduler", "tcp://127.0.0.1:70000"],
        ["--scheduler", "port"],
    ),
    "simulate-work-cap": (
        ["mechanism", "simulate", "fivebar.toml", "--rpm", "left=60", "--rpm", "right=30", "--time", "1"],
        ["--time", "evaluations", "in 100)"],
    ),
    "path-csv-extra-value": ([*SYN, "three.csv", "--out", "m.toml"], ["three.csv", "line 2", "3 values", "x, y"]),
    "path-csv-untimed-repeat": ([*SYN, "repeat.csv", "--out", "m.toml"], ["repeat.csv", "line 4", "repeats"]),
    "path-csv-timed-repeat": (
        [*SYN, "repeat_timed.csv", "--out", "m.toml"],
        ["repeat_timed.csv", "line 4", "input_deg"],
    ),
}


@pytest.fixture
def box(tmp_path, monkeypatch):
    for name, text in FILES.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run(argv):
    """``gearlever argv`` in-process; stdout, stderr (including what the garbage collector prints after)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = main(argv)
        gc.collect()  # a client left half-made would print its traceback here
    return status, out.getvalue(), err.getvalue()


@pytest.mark.parametrize(("argv", "words"), [pytest.param(a, w, id=k) for k, (a, w) in CASES.items()])
def test_hostile_number_is_refused_in_one_line_naming_the_input(box, monkeypatch, argv, words):
    import gearlever.mechanism.dynamics as dyn
    import gearlever.synthesis._dask as dk

    monkeypatch.setattr(dk, "CONNECT_TIMEOUT", 0.3)  # the unreachable scheduler: a short wait
    monkeypatch.setattr(dyn, "PROBE_EVALS", 100)  # the work estimate after 100 evaluations (a fast case)
    before = sorted(p.name for p in box.iterdir())
    status, out, err = run(argv)
    assert "Traceback" not in err and "Exception ignored" not in err, err
    assert status == 2, f"exit {status}: {out[:300]!r} {err!r}"
    assert err.count("\n") == 1 and err.startswith("gearlever"), err
    for w in words:
        assert w in err, f"{w!r} not in {err!r}"
    assert out == ""
    assert sorted(p.name for p in box.iterdir()) == before


def test_a_path_csv_of_1e308_does_not_blame_a_flag_never_given(box):
    _, _, err = run([*SYN, "huge.csv", "--out", "m.toml"])
    assert "--length-range" not in err and "--coord-range" not in err


# ---------------------------------------------------------------------------
# what users type, accepted
# ---------------------------------------------------------------------------

BOM = "\ufeff"


def test_a_byte_order_mark_is_taken_in_toml_and_csv(box):
    """Spreadsheets write a UTF-8 BOM before CSV; the one reader of user files drops it."""
    (box / "bom.toml").write_text(BOM + ENGINE, encoding="utf-8")
    (box / "bom.csv").write_text(BOM + PLANETARY, encoding="utf-8")
    (box / "bom_path.csv").write_text(BOM + PATH, encoding="utf-8")
    status, out, err = run(["mechanism", "structure", "bom.toml"])
    assert status == 0 and err == "" and "dof" in out
    status, out, err = run(["network", "bom.csv", "--inputs", "sun"])
    assert status == 0 and err == "" and "rot_carrier" in out
    from gearlever.cli._synthesize_path import read_targets

    xy, angles = read_targets(str(box / "bom_path.csv"))
    assert xy.shape == (5, 2) and angles is None


def test_read_text_capped_drops_a_leading_bom_only(tmp_path):
    from gearlever._io import read_text_capped

    p = tmp_path / "f.csv"
    p.write_bytes(b"\xef\xbb\xbfx,y\n")
    assert read_text_capped(p, "FILE") == "x,y\n"
    p.write_bytes(b"x,\xef\xbb\xbfy\n")  # not leading: kept
    assert read_text_capped(p, "FILE") == "x,\ufeffy\n"


def test_budget_in_e_notation_is_the_integer_it_writes():
    from gearlever.cli import build_parser
    from gearlever.cli._common import capped_int

    args = build_parser().parse_args([*SYN, "p.csv", "--out", "m.toml", "--budget", "1e5"])
    assert args.budget == 100_000
    parse = capped_int(10**7)
    assert parse("2.5e3") == 2500
    for bad in ("1.5", "1e-3", "nan", "1e400"):
        with pytest.raises(Exception, match="must be"):
            parse(bad)


def test_length_range_from_zero_is_any_positive_length():
    from gearlever.synthesis.path_fourbar import ZERO_LENGTH_FRACTION, FourBarPathProblem

    pb = FourBarPathProblem([[0, 0], [1, 0], [2, 1]], length_range=(0, 50), coord_range=(-5, 5))
    lo, hi = pb.length_range
    assert hi == 50 and lo == pytest.approx(ZERO_LENGTH_FRACTION * 50) and lo > 0
    with pytest.raises(GearleverError, match="length_range must be 0 <= LO < HI"):
        FourBarPathProblem([[0, 0], [1, 0], [2, 1]], length_range=(-1, 50), coord_range=(-5, 5))


def test_draw_of_a_two_input_model_says_which_input_it_held(box):
    """Without --input the first input turns and the others stay at the sketch: the drawing's title says so."""
    from gearlever.cli.mechanism import held_note
    from gearlever.mechanism import Mechanism
    from gearlever.plotting.mechanism import draw_mechanism

    mech = Mechanism.load("fivebar.toml")
    note = held_note(mech)
    assert note == "paths: left turns, right held at 90 deg (sketch)"
    assert held_note(Mechanism.load("engine.toml")) is None
    import matplotlib.pyplot as plt

    ax = draw_mechanism(mech, mech.solve(np.array([[0.0, math.pi / 2]])), note=note)
    assert ax.get_title().endswith(note)
    plt.close(ax.figure)
    status, out, err = run(["mechanism", "draw", "fivebar.toml", "--out", "d.png", "--points", "3", "--dpi", "40"])
    assert status == 0 and err == "" and (box / "d.png").stat().st_size > 0


# ---------------------------------------------------------------------------
# library level: where each fix lives
# ---------------------------------------------------------------------------


def _crank(length=1e10):
    from gearlever.mechanism import Mechanism

    return Mechanism.from_dict(
        {
            "mechanism": {"units": "m"},
            "points": {"O": [0, 0], "A": [length, 0]},
            "links": {"ground": ["O"], "crank": ["O", "A"]},
            "inputs": [{"link": "crank"}],
        }
    )


def test_inverse_dynamics_refuses_overflowing_forces_naming_the_mass():
    """1e100 kg at 1e10 m turning at 1e100 rad/s: m w^2 r = 1e310 N overflows; named, never NaN forces."""
    with pytest.raises(GearleverError, match=r"^masses\.crank\.mass = 1e\+100: the forces it gives overflow"):
        _crank().inverse_dynamics([0.0], [1e100], masses={"crank": {"mass": 1e100, "centre": "A"}})
    d = _crank().inverse_dynamics([0.0], [1e40], masses={"crank": {"mass": 1e100, "centre": "A"}})
    assert np.all(np.isfinite(d.input_force)) and np.all(np.isfinite(d.reaction["O"]))
    # equilibrium of the crank: the pin carries the centripetal force m w^2 r (1e190 N along -x)
    assert d.reaction["O"][0, 0] == pytest.approx(-1e100 * 1e80 * 1e10, rel=1e-12)


@pytest.mark.parametrize(
    ("masses", "loads", "gravity", "match"),
    [
        ({"crank": {"mass": 1e101, "centre": "A"}}, None, None, r"masses\.crank\.mass must be at most 1e\+100"),
        ({"crank": {"mass": 1, "centre": "A", "inertia": 1e300}}, None, None, r"masses\.crank\.inertia"),
        (None, [{"link": "crank", "point": "A", "force": [0, -1e308]}], None, r"loads\[0\]\.force must be at most"),
        (None, [{"link": "crank", "torque": 1e200}], None, r"loads\[0\]\.torque must be at most"),
        (None, None, [0.0, -1e308], r"gravity\[1\] must be at most"),
    ],
)
def test_masses_loads_and_gravity_beyond_the_cap_are_refused_naming_them(masses, loads, gravity, match):
    with pytest.raises(GearleverError, match=match):
        _crank(1.0).inverse_dynamics([0.0], masses=masses, loads=loads, gravity=gravity)


def test_simulate_refuses_a_huge_torque_naming_the_input():
    m = _crank(1.0)
    with pytest.raises(GearleverError, match=r"^torque\['crank'\] must be at most 1e\+100"):
        m.simulate([0.0, 1.0], 0.0, 1.0, torque={"crank": 1e308}, masses={"crank": {"mass": 1, "centre": "A"}})


def test_simulate_estimates_its_work_and_refuses_early(monkeypatch):
    """A motion whose first evaluations project past the cap is refused at the probe, not at the cap."""
    import gearlever.mechanism.dynamics as dyn

    monkeypatch.setattr(dyn, "PROBE_EVALS", 50)
    mech = _fivebar()
    with pytest.raises(dyn.WorkCapError) as info:
        mech.simulate(np.linspace(0, 1, 3), mech.sketch_inputs, [2 * np.pi, np.pi], max_evals=2000)
    e = info.value
    assert e.count == 50 and e.cap == 2000 and e.need > 2000 and 0 < e.reached < 1
    assert "needs about" in str(e) and "max_evals = 2000" in str(e)


def test_the_work_check_projects_from_the_time_reached():
    from gearlever.mechanism.dynamics import PROBE_EVALS, WorkCapError, _check_work

    _check_work(PROBE_EVALS, 0.5, 0.0, 1.0, 4 * PROBE_EVALS, "max_evals")  # needs 2 x probe: fine
    _check_work(PROBE_EVALS + 1, 0.0, 0.0, 1.0, 4 * PROBE_EVALS, "max_evals")  # not a checkpoint
    with pytest.raises(WorkCapError, match="needs about 4e"):
        _check_work(2 * PROBE_EVALS, 0.25, 0.0, 1.0, 4 * PROBE_EVALS, "max_evals")
    with pytest.raises(WorkCapError, match="more than max_evals = 10"):
        _check_work(11, 0.9, 0.0, 1.0, 10, "max_evals")


def _fivebar():
    from gearlever.mechanism import Mechanism

    return Mechanism.load(EXAMPLES / "fivebar_two_inputs.toml")


def test_network_result_beyond_float_is_refused_with_its_size():
    from fractions import Fraction

    from gearlever.gears.torques import _float, _magnitude

    assert _magnitude(Fraction(-35, 1) * Fraction(10) ** 307) == "-3.5e+308"
    assert _magnitude(Fraction(1, 3)) == "3.33e-1"
    assert _float(Fraction(7, 2), "x") == 3.5
    with pytest.raises(GearleverError, match=r"^speeds: the speed of sun comes to 2e\+400"):
        _float(Fraction(2) * Fraction(10) ** 400, "the speed of sun", "speeds")


def test_lengths_beyond_the_coordinate_cap_are_refused():
    from gearlever.mechanism.model import MAX_COORDINATE, parse_lengths

    links = {"crank": ["O", "A"]}
    assert parse_lengths({"crank": MAX_COORDINATE}, links)["crank"][3] == MAX_COORDINATE
    with pytest.raises(GearleverError, match=r"^lengths\.crank must be at most 1e\+12"):
        parse_lengths({"crank": 1e308}, links)


@pytest.mark.parametrize(
    ("address", "match"),
    [
        ("nonsense", "must be an address"),
        ("", "must be an address"),
        ("file:///tmp/x", "must be an address"),
        ("udp://host:1", "unknown scheme 'udp'"),
        ("tcp://h:0", "port must be 1..65535"),
        (None, "must be an address"),
    ],
)
def test_scheduler_address_form_is_checked_before_connecting(address, match):
    from gearlever.synthesis._dask import check_address

    with pytest.raises(GearleverError, match=f"^scheduler .*{match}"):
        check_address(address)


def test_scheduler_address_forms_accepted():
    from gearlever.synthesis._dask import check_address

    assert check_address("127.0.0.1:8786") == ("tcp", "127.0.0.1", 8786)
    assert check_address("tls://[::1]:8786") == ("tls", "::1", 8786)
    assert check_address("inproc://10.0.0.1/77/1")[0] == "inproc"


def test_search_never_evaluates_more_than_its_budget():
    """The budget is a cap: the initial population is drawn within it (it used to draw twice the population)."""
    from gearlever.synthesis._search import cma_es, differential_evolution

    def f(Z):
        out = np.sum(Z**2, axis=1)
        out[Z[:, 0] > 0.5] = np.inf  # a quarter infeasible
        return out

    lo, hi = -np.ones(3), np.ones(3)
    for budget in (10, 60, 61, 500):
        for search in (differential_evolution, cma_es):
            calls = []

            def counted(Z, calls=calls):
                calls.append(len(Z))
                return f(Z)

            _, _, evals = search(
                counted,
                lo,
                hi,
                np.random.default_rng(1),
                budget=budget,
                pop=30,
                init=lambda r, m: lo + r.random((m, 3)) * (hi - lo),
            )
            assert sum(calls) == evals <= budget, (search.__name__, budget, evals)


def test_path_budget_below_the_minimum_is_refused_naming_it():
    from gearlever.synthesis.path import min_budget, synthesize_path

    T = [[0.0, 0.0], [1.0, 0.2], [2.0, 1.0]]
    with pytest.raises(GearleverError, match=r"^budget must be a whole number from 480 to 10000000 .* got 100$"):
        synthesize_path(T, budget=100)
    assert min_budget(10) == 480


def test_one_start_evaluates_at_most_its_share_of_the_budget():
    """A start's search is capped by its evaluations (the polish after it is not counted)."""
    from gearlever.synthesis.driver import search_start
    from gearlever.synthesis.path import population, search_problem

    spec = {"targets": [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5]], "length_range": (0.2, 5)}
    spec["coord_range"] = (-5, 5)
    for evals in (population(10), 200):
        start = search_start(search_problem(spec), 0, 0, evals)
        assert 0 < start.evaluations <= evals


@pytest.mark.parametrize(
    ("targets", "match"),
    [
        ([[0, 0], [1, 1e308]], r"targets\[1\] must be finite and at most 1e\+11 .* y = 1e\+308"),
        ([[0, 0], [np.nan, 1]], r"targets\[1\] .* x = nan"),
    ],
)
def test_path_targets_out_of_range_are_named(targets, match):
    from gearlever.synthesis.path import synthesize_path

    with pytest.raises(GearleverError, match=match):
        synthesize_path(targets, budget=1000)


def test_timed_targets_out_of_order_name_the_angle():
    from gearlever.synthesis.path import FourBarPathProblem

    with pytest.raises(GearleverError, match=r"angle 3 \(30 deg\) is not greater than angle 2 \(30 deg\)"):
        FourBarPathProblem([[0, 0], [1, 0], [2, 1]], "relative", np.radians([0, 30, 30]), coord_range=(-5, 5))


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("0,0\n1,1,5,6\n", "line 2: 4 values, but the columns are x, y"),
        ("x,y\n0,0\n\n# c\n1,1,2\n", "line 5: 3 values"),
        ("x,y\n0,0\n1,1\n0,0\n", None),  # a repeat that is not in a row: the path may cross itself
        ("x,y\n0,0\n1,1\n2,2\n0,0\n", None),  # the closing repeat of the first target
        ("x,y\n0,0,\n1,1,\n", None),  # trailing empty cells (a spreadsheet's extra commas)
    ],
)
def test_read_targets_names_the_line(tmp_path, text, match):
    from gearlever.cli._synthesize_path import read_targets

    p = tmp_path / "t.csv"
    p.write_text(text)
    if match is None:
        assert read_targets(str(p))[0].shape[1] == 2
    else:
        with pytest.raises(GearleverError, match=match):
            read_targets(str(p))


def test_no_helper_process_or_thread_is_left_by_a_failed_scheduler(box, monkeypatch):
    import threading

    import gearlever.synthesis._dask as dk

    monkeypatch.setattr(dk, "CONNECT_TIMEOUT", 0.3)
    before = threading.active_count()
    status, _, err = run([*SYN, "path.csv", "--out", "m.toml", "--budget", "1000", "--scheduler", "127.0.0.1:9"])
    assert status == 2 and "Traceback" not in err
    assert threading.active_count() <= before + 1  # at most dask's shared loop thread
    assert not (box / "m.toml").exists()
