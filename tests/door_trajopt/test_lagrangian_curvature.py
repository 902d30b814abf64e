"""The SQP's block quasi-Newton curvature: secant equation, positive definiteness, skipped
negative curvature, and the block-diagonal matrix in the free vector's layout."""

import numpy as np
import scipy.sparse as sp

from door_trajopt.lagrangian_curvature import BlockCurvature, block_pattern


def test_an_update_meets_the_secant_equation_and_stays_positive_definite():
    rng = np.random.default_rng(0)
    curvature = BlockCurvature.start(3, 4, 1e-2)
    step = rng.normal(size=12)
    change = rng.normal(size=12)
    change[:4] = step[:4] * 2.0  # block 0: positive curvature along its step
    change[4:8] = -step[4:8]  # block 1: negative curvature, must be skipped
    change[8:] = 0.0  # block 2: none
    curvature.update(step, change)
    np.testing.assert_allclose(curvature.blocks[0] @ step[:4], change[:4], rtol=1e-10)
    np.testing.assert_array_equal(curvature.blocks[1], 1e-2 * np.eye(4))
    np.testing.assert_array_equal(curvature.blocks[2], 1e-2 * np.eye(4))
    for block in curvature.blocks:
        np.testing.assert_allclose(block, block.T, atol=1e-14)
        assert np.linalg.eigvalsh(block).min() > 0.0


def test_the_matrix_is_block_diagonal_in_the_waypoint_layout_and_fits_its_pattern():
    curvature = BlockCurvature(np.random.default_rng(1).normal(size=(5, 3, 3)))
    matrix = curvature.matrix()
    np.testing.assert_array_equal(matrix.toarray(), sp.block_diag(list(curvature.blocks)).toarray())
    outside = matrix.toarray() * ~block_pattern(5, 3).toarray()
    assert not outside.any()
