"""Brent's bracketed root (recipsim.physics.bracketed_root) against closed-form roots and
scipy's brentq.

Tolerances: the stopping rule is brentq's, so the root is within ``xtol + rtol |x|`` of
the true one (checked at 1e-15 relative, the motor's request); on smooth functions the
two implementations stop within a few evaluations of each other.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from recipsim.physics.bracketed_root import bracketed_root


@pytest.mark.parametrize(
    ("f", "low", "high", "root"),
    [
        (lambda x: x * x - 2.0, 0.0, 2.0, math.sqrt(2.0)),
        (lambda x: math.cos(x) - x, 0.0, 1.0, 0.7390851332151607),
        (lambda x: math.exp(x) - 10.0, 3.0, -5.0, math.log(10.0)),  # ends reversed
        (lambda x: (x - 1e-3) ** 3, -1.0, 1.0, 1e-3),  # a triple root: bisection's pace
        (lambda x: math.tanh(50.0 * (x - 0.3)), 0.0, 1.0, 0.3),  # a step-like function
    ],
)
def test_closed_form_roots(f, low, high, root):
    x = bracketed_root(f, low, high, xtol=1e-15, rtol=1e-15)
    assert abs(x - root) <= 2e-15 * max(1.0, abs(root)) + 1e-15


def test_counts_evaluations_like_brentq():
    """Superlinear: on a smooth function about as many evaluations as scipy's brentq,
    far fewer than the 50 halvings bisection needs for 1e-15."""
    calls = {"ours": 0, "scipy": 0}

    def counted(key):
        def f(x):
            calls[key] += 1
            return x**3 - 2.0 * x - 5.0

        return f

    ours = bracketed_root(counted("ours"), 2.0, 3.0, xtol=1e-15, rtol=1e-15)
    theirs = brentq(counted("scipy"), 2.0, 3.0, xtol=1e-15, rtol=1e-15)
    assert ours == pytest.approx(theirs, rel=2e-15)
    assert calls["ours"] <= calls["scipy"] + 2
    assert calls["ours"] < 15


@settings(max_examples=200, deadline=None)
@given(
    root=st.floats(-1e3, 1e3),
    scale=st.floats(1e-3, 1e3),
    curvature=st.floats(-0.9, 0.9),
    left=st.floats(1e-6, 1e3),
    right=st.floats(1e-6, 1e3),
)
def test_agrees_with_brentq(root, scale, curvature, left, right):
    """Monotonic smooth functions with a root anywhere inside a random bracket."""

    def f(x):
        u = (x - root) / scale
        return u + curvature * math.tanh(u) ** 2 * math.copysign(1.0, u)

    low, high = root - left, root + right
    ours = bracketed_root(f, low, high, xtol=1e-13, rtol=1e-15)
    theirs = brentq(f, low, high, xtol=1e-13, rtol=1e-15)
    tol = 1e-13 + 1e-15 * abs(root)
    assert abs(ours - root) <= 2.0 * tol + 4.0 * abs(root) * 2.2e-16
    assert abs(ours - theirs) <= 4.0 * tol + 8.0 * abs(root) * 2.2e-16


def test_refuses_a_bracket_without_a_sign_change():
    with pytest.raises(ValueError, match="no sign change"):
        bracketed_root(lambda x: x * x + 1.0, -1.0, 1.0)


def test_an_end_that_is_a_root():
    assert bracketed_root(lambda x: x - 1.0, 1.0, 5.0) == 1.0
    assert bracketed_root(lambda x: x - 5.0, 1.0, 5.0) == 5.0
