"""Chains in R^n, plane polygons and implicit solids through the Python API:
closed forms, the same bits for an expression and a Python function, and the
errors with their positions."""

import math
import warnings

import numpy as np
import pytest

import polyvol


def cross_polytope(n):
    """The boundary of the n-dimensional cross-polytope |x|_1 <= 1, outward:
    volume 2^n / n!."""
    points = np.vstack([np.eye(n), -np.eye(n)])
    simplices = []
    for signs in range(2 ** n):
        s = [(signs >> k) & 1 for k in range(n)]
        simplex = [k + n * s[k] for k in range(n)]
        # orientation: det of the vertices times the sign product
        det = np.linalg.det(points[simplex])
        simplices.append(simplex if det > 0 else [simplex[1], simplex[0]] + simplex[2:])
    return points, np.array(simplices)


@pytest.mark.parametrize("n", [2, 3, 4, 5])
def test_cross_polytope_volumes(n):
    p, s = cross_polytope(n)
    r = polyvol.chain_volume(p, s)
    assert r.closed and r.components == 1
    want = 2 ** n / math.factorial(n)
    if n <= 3:
        assert r.correctly_rounded and r.volume == want
    else:
        assert abs(r.volume - want) <= r.error_bound
    assert np.allclose(r.centroid, 0, atol=1e-15)
    exact = polyvol.chain_volume(p, s, accuracy="exact")
    assert exact.volume == want and exact.correctly_rounded
    assert r.to_dict()["error_bound"] == r.error_bound


def test_chain_errors():
    p, s = cross_polytope(3)
    with pytest.raises(ValueError):
        polyvol.chain_volume(p, s[:, :2])
    with pytest.raises(ValueError):
        polyvol.chain_volume(p, s + 6)
    with pytest.raises(TypeError):
        polyvol.chain_volume(p, s.astype(float))
    assert not polyvol.chain_volume(p, s[:-1]).closed


def test_polygon_with_a_hole():
    outer = np.array([[0, 0], [4, 0], [4, 3], [0, 3]], float)
    hole = np.array([[1, 1], [1, 2], [2, 2], [2, 1]], float)  # clockwise
    r = polyvol.polygon_area([outer, hole])
    assert r.area == 11.0 and r.correctly_rounded
    assert r.centroid.tolist() == [(12 * 2 - 1.5) / 11, (12 * 1.5 - 1.5) / 11]


def test_chain_and_polygon_files(tmp_path):
    (tmp_path / "t.chain").write_text("# a triangle's boundary\n2 3 3\n0 0\n1 0\n0 1\n0 1\n1 2\n2 0\n")
    points, simplices = polyvol.load_chain(tmp_path / "t.chain")
    assert points.shape == (3, 2) and simplices.shape == (3, 2)
    assert polyvol.chain_volume(points, simplices).volume == 0.5
    (tmp_path / "p.txt").write_text("0 0 2 0 2 2 0 2\n")
    assert polyvol.polygon_area(polyvol.load_polygons(tmp_path / "p.txt")).area == 4.0
    (tmp_path / "bad.chain").write_text("2 3 3\n0 0\n1 0\n")
    with pytest.raises(polyvol.ReadError) as e:
        polyvol.load_chain(tmp_path / "bad.chain")
    assert e.value.line is not None


def test_implicit_ball_expression_and_function_give_the_same_bits():
    e = polyvol.implicit("x^2 + y^2 + z^2 - 1", 3, (-1.5, 1.5), h=0.1)
    calls = []

    def f(p):
        calls.append(len(p))
        return (p ** 2).sum(axis=1) - 1

    g = polyvol.implicit(f, 3, (-1.5, 1.5), h=0.1)
    assert e.volume == g.volume and e.volume_pl == g.volume_pl
    assert abs(e.volume - 4 / 3 * math.pi) < 3 * e.error_estimate
    assert sum(calls) == g.function_evaluations and len(calls) * 4 < sum(calls)  # many points per call
    assert not e.clipped


def test_implicit_in_4d_and_clipped():
    r = polyvol.implicit("x1^2+x2^2+x3^2+x4^2-1", 4, ([0, 0, 0, 0], [1.2] * 4), h=0.1)
    assert r.volume * 16 == pytest.approx(math.pi ** 2 / 2, rel=2e-3)
    c = polyvol.implicit("x^2+y^2-1", 2, (0.0, 2.0), h=0.01)
    assert c.clipped and c.volume == pytest.approx(math.pi / 4, rel=1e-4)


def test_implicit_errors():
    with pytest.raises(polyvol.ExpressionError) as e:
        polyvol.implicit("x^2 + + ", 3, (-1, 1))
    assert e.value.position >= 0
    with pytest.raises(polyvol.ImplicitError) as e:
        polyvol.implicit(lambda p: np.full(len(p), np.nan), 2, (-1, 1))
    assert e.value.code == "not_a_number" and len(e.value.point) == 2
    with pytest.raises(polyvol.ImplicitError) as e:
        polyvol.implicit("x^2+y^2-4", 2, (-1, 1), box_rule="error")
    assert e.value.code == "touches_box"
    with pytest.raises(ValueError):
        polyvol.implicit(lambda p: np.zeros(len(p) + 1), 2, (-1, 1))

    def broken(p):
        raise KeyError("from the user's function")

    with pytest.raises(KeyError):
        polyvol.implicit(broken, 2, (-1, 1))


def test_extrapolated_volume_carries_its_own_estimate():
    # The 4h lattice estimates the Richardson value's own error (#33 item 14):
    # far below V(h)'s estimate, and it covers the true error of the ball.
    r = polyvol.implicit("x^2+y^2+z^2-1", 3, (-1.5, 1.5))
    assert r.extrapolated_error_estimate is not None and r.volume_pl_4h is not None
    assert abs(r.volume - 4 / 3 * math.pi) <= r.extrapolated_error_estimate < r.error_estimate / 10
    square = polyvol.implicit("max(abs(x),abs(y))-1", 2, (-1.5, 1.5))  # sides between lattice planes
    assert square.extrapolated_error_estimate is None


def test_a_hole_wound_like_its_outer_loop_is_said():
    outer = np.array([(0, 0), (10, 0), (10, 10), (0, 10)], float)
    hole_ccw = np.array([(2, 2), (8, 2), (8, 8), (2, 8)], float)
    with pytest.warns(UserWarning, match="1 loop.s. wound like the loop around them"):
        assert polyvol.polygon_area([outer, hole_ccw]).area == 136.0  # counted as land, and said
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert polyvol.polygon_area([outer, hole_ccw[::-1]]).area == 64.0
