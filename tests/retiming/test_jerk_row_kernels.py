"""The jerk LPs' compiled rows and sparse kernels against numpy, scipy, the jerk.

:mod:`rt_drake.retiming._jerk_row_kernels` through the row makers of
:mod:`rt_drake.retiming._jerk_rows`.
"""

import numpy as np


def _random_band(rng, points=12, segments=4):
    """A band of random points on interior segments of a random grid."""
    from rt_drake.retiming._jerk_rows import Band
    from rt_drake.retiming._jerk_timed_path import Piece

    s = np.sort(np.concatenate([[0.0, 1.0], rng.random(segments - 1)]))
    segment = rng.integers(0, segments, size=points)
    sigma = rng.random(points)
    sigma[:2] = 0.0, 1.0  # a segment's ends: some band entries are 0
    kinds = np.full(segments, Piece.INTERIOR)
    return s, Band.of(s, kinds, segment, sigma)


def _rows_at(block, z):
    """Each compressed row's value at z, (R,)."""
    from scipy import sparse

    indptr = np.concatenate([[0], np.cumsum(block.counts)])
    A = sparse.csr_matrix(
        (block.values, block.cols, indptr), shape=(len(indptr) - 1, len(z))
    )
    return A @ z


def test_jerk_rows_bound_the_joint_jerk_and_are_exact_at_the_iterate():
    """``row(z) - bound`` is ``(+-jerk_j - J_j) / sqrt(xbar)`` at ``x = xbar``.

    Reference: the joint jerk ``sqrt(x) (q' k + 3 q'' u + q''' x)`` of
    :func:`._jerk_rows.jerk_values` (numpy) at x, u, k of the band times z.
    The row is the tangent of the convex bound ``J / sqrt(x)`` at ``xbar``:
    at other x its right side lies below ``J / sqrt(x)`` (an inner row).
    """
    from rt_drake.retiming._jerk_rows import KIND_SHIFT, jerk_rows, jerk_values

    rng = np.random.default_rng(5)
    s, band = _random_band(rng)
    P, n = len(band.cols), 3
    z = np.concatenate([1.0 + rng.random(len(s)), rng.normal(size=len(s))])
    dq, ddq, dddq = (rng.normal(size=(P, n)) for _ in range(3))
    index = np.flatnonzero(rng.random(P) < 0.7)
    keep = rng.random((len(index), n)) < 0.6
    x = np.einsum("pe,pe->p", band.X, z[band.cols])
    u = np.einsum("pe,pe->p", band.U, z[band.cols])
    k = np.einsum("pe,pe->p", band.K, z[band.cols])
    jerk_limit = 1.0 + rng.random(n)
    rows = jerk_rows(band, index, 7, (dq, ddq, dddq), x[index], jerk_limit, keep)
    p, j = np.nonzero(keep)
    jerk = jerk_values(x, u, k, dq, ddq, dddq)[index[p], j]
    root = np.sqrt(x[index[p]])
    expected = np.concatenate([jerk - jerk_limit[j], -jerk - jerk_limit[j]])
    expected /= np.tile(root, 2)
    np.testing.assert_allclose(_rows_at(rows, z) - rows.bound, expected, atol=1e-12)
    assert np.all(rows.values != 0.0) and np.all(rows.counts <= 3)
    kinds = rows.keys >> KIND_SHIFT
    np.testing.assert_array_equal(kinds, np.repeat([7, 8], len(p)))
    np.testing.assert_array_equal(rows.keys & 0xFFFFFF, np.tile(j, 2))
    np.testing.assert_array_equal((rows.keys >> 24) & 0xFFFFFFF, np.tile(index[p], 2))
    # The tangent at xbar of J / sqrt(x) stays below it at any other x > 0.
    other = x[index[p]] * (0.2 + 3.0 * rng.random(len(p)))
    tangent = 1.5 / root - other / (2.0 * root**3)
    assert np.all(tangent <= 1.0 / np.sqrt(other) + 1e-12)


def test_affine_rows_evaluate_the_affine_limit_where_it_is_finite():
    """``alpha u + beta x`` at the band's (x, u) times z, for finite bounds only.

    Reference: x and u from the band's entries (numpy), the products
    formed directly; rows and keys in row-major (point, column) order.
    """
    from rt_drake.retiming._jerk_rows import KIND_SHIFT, affine_rows

    rng = np.random.default_rng(6)
    s, band = _random_band(rng)
    P, M = len(band.cols), 4
    z = np.concatenate([1.0 + rng.random(len(s)), rng.normal(size=len(s))])
    alpha, beta = rng.normal(size=(P, M)), rng.normal(size=(P, M))
    bound = np.where(rng.random((P, M)) < 0.6, rng.normal(size=(P, M)), np.inf)
    points = 100 + np.arange(P)
    rows = affine_rows(band, points, 2, alpha, beta, bound)
    x = np.einsum("pe,pe->p", band.X, z[band.cols])
    u = np.einsum("pe,pe->p", band.U, z[band.cols])
    p, m = np.nonzero(np.isfinite(bound))
    np.testing.assert_allclose(
        _rows_at(rows, z), alpha[p, m] * u[p] + beta[p, m] * x[p], atol=1e-12
    )
    np.testing.assert_array_equal(rows.bound, bound[p, m])
    np.testing.assert_array_equal(rows.keys >> KIND_SHIFT, np.full(len(p), 2))
    np.testing.assert_array_equal((rows.keys >> 24) & 0xFFFFFFF, points[p])
    np.testing.assert_array_equal(rows.keys & 0xFFFFFF, m)
    assert np.all(rows.values != 0.0)


def test_affine_rows_of_several_kinds_are_each_kinds_rows_one_after_the_other():
    """B kinds in one call: block b's rows, bounds and keys as numpy forms them.

    Reference: per kind, ``alpha u + beta x`` at the band's (x, u) times z
    (numpy), the finite bounds in row-major (point, column) order, the
    kinds' rows concatenated in their order; no entry is zero.
    """
    from rt_drake.retiming._jerk_rows import KIND_SHIFT, affine_rows

    rng = np.random.default_rng(8)
    s, band = _random_band(rng)
    P, M, kinds = len(band.cols), 3, [0, 1, 2, 9]
    z = np.concatenate([1.0 + rng.random(len(s)), rng.normal(size=len(s))])
    alpha, beta = rng.normal(size=(4, P, M)), rng.normal(size=(4, P, M))
    alpha[0] = 0.0  # rows in x alone
    bound = np.where(rng.random((4, P, M)) < 0.6, rng.normal(size=(4, P, M)), np.inf)
    points = 7 + np.arange(P)
    rows = affine_rows(band, points, kinds, alpha, beta, bound)
    x = np.einsum("pe,pe->p", band.X, z[band.cols])
    u = np.einsum("pe,pe->p", band.U, z[band.cols])
    b, p, m = np.nonzero(np.isfinite(bound))
    np.testing.assert_allclose(
        _rows_at(rows, z), alpha[b, p, m] * u[p] + beta[b, p, m] * x[p], atol=1e-12
    )
    np.testing.assert_array_equal(rows.bound, bound[b, p, m])
    np.testing.assert_array_equal(rows.keys >> KIND_SHIFT, np.array(kinds)[b])
    np.testing.assert_array_equal((rows.keys >> 24) & 0xFFFFFFF, points[p])
    np.testing.assert_array_equal(rows.keys & 0xFFFFFF, m)
    assert np.all(rows.values != 0.0)
    assert np.sum(rows.counts) == len(rows.values) < 3 * len(b)  # zeros dropped


def test_the_sparse_kernels_are_scipys_product_and_row_selection():
    """``csr_product`` is scipy's ``A @ z`` to the bit; ``csr_rows`` is ``A[rows]``.

    Reference: scipy's CSR product and row indexing on a random sparse
    matrix (rows with 0 to 6 entries), rows taken repeated and out of order.
    """
    from scipy import sparse

    from rt_drake.retiming._jerk_row_kernels import csr_product, csr_rows

    rng = np.random.default_rng(8)
    A = sparse.random(60, 30, density=0.1, random_state=9, format="csr")
    z = rng.normal(size=30)
    assert np.array_equal(csr_product(A.indptr, A.indices, A.data, z), A @ z)
    rows = np.array([5, 0, 59, 5, 17], dtype=np.int64)
    start, index, value = csr_rows(A.indptr, A.indices, A.data, rows)
    taken = A[rows]
    np.testing.assert_array_equal(start, taken.indptr)
    np.testing.assert_array_equal(index, taken.indices)
    np.testing.assert_array_equal(value, taken.data)


def test_stacked_is_scipys_matrix_of_the_blocks():
    """``stacked``'s RowMatrix has the CSR arrays scipy builds from the blocks.

    Reference: ``scipy.sparse.csr_matrix`` of the blocks' entries, and its
    product with z, to the bit (the compiled solver and HiGHS read the
    arrays; scipy's solvers take ``tocsr()``).
    """
    from scipy import sparse

    from rt_drake.retiming._jerk_row_kernels import csr_product
    from rt_drake.retiming._jerk_rows import affine_rows, stacked

    rng = np.random.default_rng(11)
    s, band = _random_band(rng)
    P, n = len(band.cols), 2 * len(s)
    points = np.arange(P)
    blocks = [
        affine_rows(band, points, kind, rng.normal(size=(P, 2)),
                    rng.normal(size=(P, 2)), rng.normal(size=(P, 2)))
        for kind in (2, 3)
    ]  # fmt: skip
    A, bound, keys = stacked(blocks, n)
    counts = np.concatenate([b.counts for b in blocks])
    reference = sparse.csr_matrix(
        (
            np.concatenate([b.values for b in blocks]),
            np.concatenate([b.cols for b in blocks]),
            np.concatenate([[0], np.cumsum(counts)]),
        ),
        shape=(len(counts), n),
    )
    assert A.shape == reference.shape
    for mine, theirs in zip(
        A[:3], (reference.indptr, reference.indices, reference.data), strict=True
    ):
        assert mine.dtype == theirs.dtype
        np.testing.assert_array_equal(mine, theirs)
    z = rng.normal(size=n)
    assert np.array_equal(csr_product(A.indptr, A.indices, A.data, z), reference @ z)
    assert np.array_equal(A.tocsr() @ z, reference @ z)
    np.testing.assert_array_equal(bound, np.concatenate([b.bound for b in blocks]))
    np.testing.assert_array_equal(keys, np.concatenate([b.keys for b in blocks]))
