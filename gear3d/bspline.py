"""Clamped B-splines with numpy: basis values (Cox-de Boor), evaluation and interpolation.

The B-rep writer fits its flank curves and twist laws with these (no scipy import: it
costs about 0.5 s of CPU in a whole process) and measures its faces with them, from the
same poles and knots it hands to OpenCascade. Knot vectors are in "full" form (scipy's
``BSpline.t``): ``len(t) == n + k + 1`` for ``n`` coefficients of degree ``k``.

Example::

    >>> import numpy as np
    >>> from gear3d.bspline import interpolate, evaluate
    >>> x = np.linspace(0.0, 1.0, 7)
    >>> t, c = interpolate(x, np.stack([x ** 3, x], axis=1))     # a cubic reproduces x**3
    >>> bool(np.allclose(evaluate(t, c, 3, np.array([0.3])), [[0.027, 0.3]]))
    True
"""
from __future__ import annotations

import numpy as np


def nonzero_basis(t, k: int, x):
    """(span index i (m,), values (m, k+1)) of the k+1 basis functions of degree ``k`` that
    are non-zero at each ``x`` (m,): functions i-k .. i of the knot vector ``t``."""
    t = np.asarray(t, float)
    x = np.asarray(x, float)
    n = len(t) - k - 1
    i = np.clip(np.searchsorted(t, x, side="right") - 1, k, n - 1)
    m = len(x)
    N = np.zeros((m, k + 1))
    N[:, 0] = 1.0
    left = np.empty((m, k + 1))
    right = np.empty((m, k + 1))
    for j in range(1, k + 1):
        left[:, j] = x - t[i + 1 - j]
        right[:, j] = t[i + j] - x
        saved = np.zeros(m)
        for r in range(j):
            den = right[:, r + 1] + left[:, j - r]
            tmp = np.divide(N[:, r], den, out=np.zeros(m), where=den != 0)
            N[:, r] = saved + right[:, r + 1] * tmp
            saved = left[:, j - r] * tmp
        N[:, j] = saved
    return i, N


def basis_matrix(t, k: int, x):
    """Dense (m, n) matrix of all ``n`` basis functions of degree ``k`` at ``x`` (m,)."""
    i, N = nonzero_basis(t, k, x)
    n = len(t) - k - 1
    B = np.zeros((len(i), n))
    cols = i[:, None] - k + np.arange(k + 1)[None]
    B[np.arange(len(i))[:, None], cols] = N
    return B


def evaluate(t, c, k: int, x):
    """The spline with knots ``t``, coefficients ``c`` (n, ...) and degree ``k`` at ``x``."""
    i, N = nonzero_basis(t, k, x)
    c = np.asarray(c, float)
    cols = i[:, None] - k + np.arange(k + 1)[None]
    return np.einsum("mj,mj...->m...", N, c[cols])


def interpolate(x, y, k: int = 3):
    """Interpolating spline of odd degree ``k`` through (x, y) with not-a-knot end
    conditions (the interior knots are x[(k+1)/2 : -(k+1)/2]): returns (t, c).
    ``x`` (n,) strictly increasing, n >= k + 1; ``y`` (n, ...)."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    h = (k + 1) // 2
    t = np.concatenate([np.full(k + 1, x[0]), x[h:len(x) - h], np.full(k + 1, x[-1])])
    rhs = y.reshape(len(x), -1)
    if len(x) <= DENSE_MAX:
        c = np.linalg.solve(basis_matrix(t, k, x), rhs)
    else:
        c = _banded_solve(*nonzero_basis(t, k, x), k, rhs)
    return t, c.reshape(y.shape)


#: systems up to this size are solved dense; larger ones in band storage
DENSE_MAX = 400


def _banded_solve(i, N, k: int, rhs):
    """Solve the collocation system (row r: values N[r] in columns i[r]-k .. i[r]) by
    Gaussian elimination in band storage without pivoting (collocation matrices that meet
    the Schoenberg-Whitney condition are totally positive: no pivoting is needed)."""
    n = len(i)
    w = 2 * k + 1
    A = np.zeros((n, w))                      # A[r, c - r + k] = B[r, c]
    cols = i[:, None] - k + np.arange(k + 1)[None]
    A[np.arange(n)[:, None], cols - np.arange(n)[:, None] + k] = N
    b = np.array(rhs, float)
    for j in range(n - 1):
        hi = min(j + k, n - 1)
        for r in range(j + 1, hi + 1):
            f = A[r, j - r + k] / A[j, k]
            if f:
                A[r, j - r + k:j - r + w] -= f * A[j, k:w]
                b[r] -= f * b[j]
    c = np.empty_like(b)
    for j in range(n - 1, -1, -1):
        hi = min(j + k, n - 1)
        c[j] = (b[j] - A[j, k + 1:k + 1 + hi - j] @ c[j + 1:hi + 1]) / A[j, k]
    return c
