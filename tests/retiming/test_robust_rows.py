"""The closed-form worst vertex of each row against vertex enumeration."""

import itertools

import numpy as np
import pytest

from rt_drake.retiming._robust_rows import (
    BOX_SHIFT,
    Layout,
    key,
    vertex_weights,
    worst_rows,
)


def _random_set(rng, boxes=2, com=3, inertia=4, dims=6):
    """Columns per box: unit, com generators, centre, inertia generators."""
    columns, layout, masses = 0, [], []
    for _ in range(boxes):
        unit = columns
        center = unit + 1 + com
        end = center + 1 + inertia
        layout.append([unit, unit + 1, center, center, center + 1, end])
        masses.append(sorted(rng.uniform(0.2, 2.0, 2)))
        columns = end
    return Layout(np.array(layout), np.array(masses)), columns


def _vertices(layout, columns):
    """Every vertex key of the layout."""
    for box, row in enumerate(layout.columns):
        count = 1 + (row[2] - row[1]) + (row[5] - row[4])
        for bits in range(2**count):
            yield (box << BOX_SHIFT) | bits


@pytest.mark.parametrize("dims", [6, 4])
def test_worst_rows_equal_brute_force(dims):
    rng = np.random.default_rng(0)
    layout, columns = _random_set(rng, dims=dims)
    places, points, rows = 5, 40, 50
    table = tuple(rng.normal(size=(places, columns, dims)) for _ in range(3))
    index = rng.integers(0, places, points)
    u, x = rng.normal(size=points), rng.uniform(0, 3, points)
    normals = rng.normal(size=(dims, rows))
    worst = worst_rows(table, index, u, x, normals, layout)
    keys = np.array(list(_vertices(layout, columns)))
    weights = vertex_weights(layout, keys, columns)  # (V, P)
    vectors = (
        table[0][index] * u[:, None, None]
        + table[1][index] * x[:, None, None]
        + table[2][index]
    )  # (M, P, D)
    values = np.einsum("vp,mpd,dr->mvr", weights, vectors, normals)
    expected = values.max(axis=(1, 2))
    np.testing.assert_allclose(worst.ratio, expected, rtol=1e-12, atol=1e-12)
    for m in range(points):
        v = np.flatnonzero(keys == worst.key[m])[0]
        assert values[m, v, worst.row[m]] == pytest.approx(expected[m], rel=1e-12)
    assert np.all(worst.bound_max >= values.max(axis=(0, 1)) - 1e-12)


def test_vertex_keys_round_trip():
    layout = Layout(np.array([[0, 1, 3, 3, 4, 6]]), np.array([[1.0, 2.0]]))
    k = key(0, True, np.array([True, False]), np.array([False, True]))
    weights = vertex_weights(layout, np.array([k]), 6)[0]
    np.testing.assert_array_equal(weights, [2.0, 2.0, -2.0, 1.0, -1.0, 1.0])
    assert len(set(itertools.islice(_vertices(layout, 6), 100))) == 2**5


def test_ranked_rows_are_the_largest_worst_values():
    rng = np.random.default_rng(1)
    layout, columns = _random_set(rng, boxes=1)
    table = tuple(rng.normal(size=(3, columns, 6)) for _ in range(3))
    index = rng.integers(0, 3, 20)
    u, x = rng.normal(size=20), rng.uniform(0, 3, 20)
    normals = rng.normal(size=(6, 30))
    ranked = worst_rows(table, index, u, x, normals, layout, ranks=3).ranked
    assert ranked is not None
    keys = np.array(list(_vertices(layout, columns)))
    weights = vertex_weights(layout, keys, columns)
    vectors = (
        table[0][index] * u[:, None, None]
        + table[1][index] * x[:, None, None]
        + table[2][index]
    )
    per_row = np.einsum("vp,mpd,dr->mvr", weights, vectors, normals).max(axis=1)
    expected = -np.sort(-per_row, axis=1)[:, :3]
    np.testing.assert_allclose(ranked[0], expected, rtol=1e-12)
    np.testing.assert_array_equal(np.argsort(-per_row, axis=1)[:, :3], ranked[1])
