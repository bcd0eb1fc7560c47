"""relume.factor: equal to `relume factor` on the same matrix (float32 and float64, two solvers),
float64 results handed over without a copy, R = W F + E, and bad matrices refused."""
import numpy as np
import pytest

import relume
from conftest import run_relume


def planted(dtype):
    rng = np.random.default_rng(4)
    matrix = rng.standard_normal((60, 3)) @ rng.standard_normal((3, 20))
    matrix[rng.integers(0, 60, 30), rng.integers(0, 20, 30)] += 5.0  # sparse outliers
    return matrix.astype(dtype)


@pytest.mark.parametrize("dtype, solver", [(np.float64, "lp-dual"), (np.float32, "lp-dual"),
                                           (np.float64, "irls")])
def test_equals_the_command(tmp_path, dtype, solver):
    # One thread: with several, which rows each warm-started LP solves depends on timing, and
    # the command itself then differs from run to run by ~1e-9.
    matrix = planted(dtype)
    np.save(tmp_path / "R.npy", matrix)
    run_relume("factor", tmp_path / "R.npy", "-t", "3", "--solver", solver, "--seed", "2",
               "--threads", "1", "-o", tmp_path / "out")
    W, F, E = relume.factor(matrix, 3, solver=solver, seed=2, threads=1)
    for name, ours in zip("WFE", (W, F, E)):
        theirs = np.load(tmp_path / f"out_{name}.npy")
        assert ours.dtype == dtype, name
        np.testing.assert_array_equal(ours, theirs, err_msg=name)


def test_float64_results_are_handed_over_and_add_up():
    matrix = planted(np.float64)
    W, F, E = relume.factor(matrix, 3)
    assert W.shape == (60, 3) and F.shape == (3, 20) and E.shape == (60, 20)
    for result in (W, F, E):
        assert result.flags.f_contiguous and type(result.base).__name__ == "PyCapsule"
    np.testing.assert_allclose(W @ F + E, matrix, atol=1e-8)
    assert np.count_nonzero(E) < 0.1 * E.size, "the planted outliers make a sparse residual"


def test_progress_is_told_iterations():
    heard = []
    relume.factor(planted(np.float64), 3, progress=lambda *told: heard.append(told))
    assert heard[0] == ("factor: iterations", 0.0) and heard[-1] == ("factor: iterations", 1.0)


@pytest.mark.parametrize("matrix, terms, message", [
    (np.ones((4, 3), np.int64), 1, "matrix must hold float32 or float64, got dtype int64"),
    (np.ones(5), 1, r"matrix must have shape \(rows, columns\), got \(5,\)"),
    (np.zeros((0, 3)), 1, r"the matrix is empty \(0 x 3\)"),
    (np.array([[1.0, 2.0, 3.0], [4.0, 5.0, np.nan]]), 1, r"matrix\[1, 2\] is nan"),
    (np.ones((4, 3)), 0, "terms must be >= 1, got 0"),
])
def test_bad_matrices_are_refused(matrix, terms, message):
    with pytest.raises(relume.Error, match=message):
        relume.factor(matrix, terms)


def test_unknown_solver_is_refused():
    with pytest.raises(relume.Error, match="unknown L1 solver 'simplex'"):
        relume.factor(np.ones((4, 3)), 1, solver="simplex")
