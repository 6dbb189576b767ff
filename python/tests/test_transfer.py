"""ablmg.transfer: exact on linear fields, conservative projection, errors named."""
import numpy as np
import pytest

import ablmg


def area_integral(points, triangles, u):
    a, b, c = points[triangles[:, 0]], points[triangles[:, 1]], points[triangles[:, 2]]
    area = 0.5 * np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    return float((area * u[triangles].mean(axis=1)).sum())


@pytest.fixture(scope="module")
def two_meshes():
    square = ablmg.Domain.rectangle(0, 0, 1, 1)
    return ablmg.uniform_mesh(square, 300), ablmg.uniform_mesh(square, 500)


def test_projection_keeps_the_integral_and_linear_fields(two_meshes):
    old, new = two_meshes
    linear = 1 + 2 * old.points[:, 0] - 3 * old.points[:, 1]
    peak = np.exp(-50 * ((old.points - 0.4) ** 2).sum(axis=1))
    out = ablmg.transfer(old.points, old.triangles, new.points, new.triangles, [linear, peak])
    assert isinstance(out, list) and len(out) == 2 and out[0].shape == (new.num_vertices,)
    np.testing.assert_allclose(out[0], 1 + 2 * new.points[:, 0] - 3 * new.points[:, 1], atol=1e-12)
    before = area_integral(old.points, old.triangles, peak)
    assert area_integral(new.points, new.triangles, out[1]) == pytest.approx(before, rel=1e-12)


def test_interpolation_of_one_field(two_meshes):
    old, new = two_meshes
    u = 0.5 - old.points[:, 0] + 4 * old.points[:, 1]
    out = ablmg.transfer(old.points, old.triangles, new.points, new.triangles, u, method="interpolation")
    np.testing.assert_allclose(out, 0.5 - new.points[:, 0] + 4 * new.points[:, 1], atol=1e-12)


def test_bad_input_is_a_value_error(two_meshes):
    old, new = two_meshes
    with pytest.raises(ValueError, match="fields"):
        ablmg.transfer(old.points, old.triangles, new.points, new.triangles, np.zeros(3))
    with pytest.raises(ValueError, match="unknown transfer method 'nearest'"):
        ablmg.transfer(old.points, old.triangles, new.points, new.triangles, np.zeros(old.num_vertices),
                       method="nearest")
