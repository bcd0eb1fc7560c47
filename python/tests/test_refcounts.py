"""Reference counts: a view holds exactly one reference to its owner and keeps it alive after
the owner's last name is gone; compress, relight and factor leave the reference counts of their
arguments (arrays, fields, callbacks) as they were, also when they raise; results that own C++
memory are referenced only by their holder."""
import gc
import sys

import numpy as np
import pytest

import relume
from conftest import SMALL


def test_a_view_holds_one_reference_to_its_field(field):
    before = sys.getrefcount(field)
    view = field.values
    assert sys.getrefcount(field) == before + 1
    del view
    assert sys.getrefcount(field) == before


def test_views_keep_their_owner_alive(field):
    compressed = relume.compress(field, **SMALL)
    weights, expected = compressed.weights, np.array(compressed.weights)
    del compressed
    gc.collect()
    np.testing.assert_array_equal(weights, expected)
    assert type(weights.base).__name__ == "Compressed"
    values = relume.Field(np.array(field.values), field.directions).values
    gc.collect()
    np.testing.assert_array_equal(values, field.values)


def test_calls_leave_their_arguments_counts_alone(field):
    values, dirs = np.array(field.values), np.array(field.directions)
    heard = []
    def progress(phase, fraction):
        heard.append(fraction)
    counted = (field, values, dirs, progress)
    before = [sys.getrefcount(thing) for thing in counted]
    compressed = relume.compress(field, **SMALL, progress=progress)
    relume.compress(values, dirs, **SMALL, progress=progress)
    light = np.ones((40, 3))
    light_before = sys.getrefcount(light)
    for _ in range(3):
        compressed.relight(light, reference=True)
    assert sys.getrefcount(light) == light_before
    assert [sys.getrefcount(thing) for thing in counted] == before
    assert heard


def test_failed_calls_leave_counts_alone(field):
    bad = np.array(field.values)
    bad[0, 0, 0, 0] = np.nan
    dirs = np.array(field.directions)
    def progress(phase, fraction):
        raise RuntimeError("stop")
    before = [sys.getrefcount(thing) for thing in (bad, dirs, progress, field)]
    for _ in range(20):
        with pytest.raises(relume.Error):
            relume.compress(bad, dirs)
        with pytest.raises(RuntimeError):
            relume.compress(field, **SMALL, progress=progress)
    assert [sys.getrefcount(thing) for thing in (bad, dirs, progress, field)] == before


def test_results_are_referenced_by_their_holder_only(compressed):
    relit = compressed.relight(np.ones((40, 3)), reference=True)
    assert sys.getrefcount(relit) == 2  # the name and getrefcount's argument
    capsule = relit.base
    assert sys.getrefcount(capsule) == 3  # the array, the name and getrefcount's argument
    W, F, E = relume.factor(np.random.default_rng(0).standard_normal((20, 6)), 2)
    assert sys.getrefcount(W) == 2
