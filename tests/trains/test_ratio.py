"""Tests of gearlever.trains: exact ratio and sense of rotation of a train of wheels."""

from fractions import Fraction
from math import prod

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.trains import train_ratio

teeth = st.integers(min_value=6, max_value=200)


def test_ratio_is_product_of_drivers_over_followers():
    res = train_ratio([20, 30], [60, 45])
    assert res.magnitude == Fraction(600, 2700) == Fraction(2, 9)
    assert res.value == pytest.approx(2 / 9, rel=1e-15)


@pytest.mark.parametrize("meshes, sense", [(1, -1), (2, 1), (3, -1), (4, 1)])
def test_all_external_sense_alternates_with_number_of_axes(meshes, sense):
    # m axes, m - 1 external meshes: m odd keeps the sense (the classic text on trains of wheelwork, page marked (41)).
    res = train_ratio([20] * meshes, [40] * meshes)
    assert res.sense == sense
    assert res.external_meshes == meshes


def test_internal_mesh_keeps_sense():
    assert train_ratio([20], [80], internal=[1]).sense == 1
    assert train_ratio([20, 30], [60, 45], internal=[2]).sense == -1
    assert train_ratio([20, 30], [60, 45], internal=[2]).ratio == Fraction(-2, 9)


def test_idler_teeth_cancel_and_reverse_sense():
    inline = train_ratio([20, 37], [37, 60])  # the 37 wheel is an idler written into the chain
    separate = train_ratio([20], [60], idlers=[37])
    assert inline.magnitude == separate.magnitude == Fraction(1, 3)
    assert inline.sense == separate.sense == 1
    assert train_ratio([20], [60]).sense == -1


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(teeth, teeth), min_size=1, max_size=6))
def test_reversed_train_gives_reciprocal_ratio(pairs_):
    drivers = [d for d, _ in pairs_]
    followers = [f for _, f in pairs_]
    forward = train_ratio(drivers, followers)
    backward = train_ratio(followers[::-1], drivers[::-1])
    assert forward.magnitude == Fraction(prod(drivers), prod(followers))
    assert forward.magnitude * backward.magnitude == 1
    assert forward.sense == backward.sense


def test_as_dict_keys():
    rec = train_ratio([20, 30], [60, 45]).summary()
    assert rec["ratio"] == "2/9" and rec["sense"] == "same" and rec["external_meshes"] == 2


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(drivers=[20], followers=[60, 45]), "followers"),
        (dict(drivers=[], followers=[]), "drivers"),
        (dict(drivers=[0], followers=[60]), "drivers"),
        (dict(drivers=[20], followers=[-3]), "followers"),
        (dict(drivers=[20], followers=[60], internal=[2]), "internal"),
        (dict(drivers=[20, 30], followers=[60, 45], internal=[1, 1]), "internal"),
        (dict(drivers=[20], followers=[60], idlers=[0]), "idlers"),
        (dict(drivers=[20.5], followers=[60]), "drivers"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        train_ratio(**kwargs)
