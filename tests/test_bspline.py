"""gear3d.bspline against closed forms: a cubic spline reproduces cubic polynomials exactly,
the basis is a partition of unity, and the banded solver gives the dense solver's answer."""
import numpy as np

from gear3d import bspline


def test_interpolation_reproduces_a_cubic_and_its_knots_are_not_a_knot():
    x = np.array([0.0, 0.3, 0.5, 1.1, 1.7, 2.0, 2.6])
    y = np.stack([2 * x ** 3 - x ** 2 + 0.5, x - 1.0], axis=1)
    t, c = bspline.interpolate(x, y, 3)
    assert np.allclose(t, [0, 0, 0, 0, 0.5, 1.1, 1.7, 2.6, 2.6, 2.6, 2.6])
    q = np.linspace(0.0, 2.6, 101)
    exact = np.stack([2 * q ** 3 - q ** 2 + 0.5, q - 1.0], axis=1)
    assert np.abs(bspline.evaluate(t, c, 3, q) - exact).max() < 1e-12


def test_basis_is_a_partition_of_unity_and_linear_splines_are_broken_lines():
    t = np.array([0, 0, 0, 0, 0.2, 0.7, 1, 1, 1, 1.0])
    B = bspline.basis_matrix(t, 3, np.linspace(0, 1, 57))
    assert np.abs(B.sum(axis=1) - 1).max() < 1e-14 and B.min() >= 0
    tl = np.array([0, 0, 1, 2, 2.0])
    assert np.allclose(bspline.evaluate(tl, np.array([0.0, 1.0, 4.0]), 1, np.array([0, 0.5, 1, 1.5, 2])),
                       [0, 0.5, 1, 2.5, 4])


def test_banded_and_dense_solves_agree(monkeypatch):
    rng = np.random.default_rng(3)
    x = np.cumsum(rng.uniform(0.1, 1.0, 60))
    y = rng.normal(size=(60, 3))
    t, c = bspline.interpolate(x, y, 3)
    monkeypatch.setattr(bspline, "DENSE_MAX", 0)
    t2, c2 = bspline.interpolate(x, y, 3)
    assert np.abs(c - c2).max() < 1e-9
    assert np.abs(bspline.evaluate(t2, c2, 3, x) - y).max() < 1e-9     # it interpolates
