"""Shapes, dtypes, views and the invariants of every result."""
import numpy as np
import pytest

import ablmg


def check_mesh(m, area):
    assert m.points.dtype == np.float64 and m.points.shape == (m.num_vertices, 2)
    assert m.triangles.dtype == np.int32 and m.triangles.shape == (m.num_triangles, 3)
    assert m.boundary_edges.shape == (len(m.boundary_refs), 2)
    assert m.triangles.min() == 0 and m.triangles.max() == m.num_vertices - 1
    p = m.points
    a, b, c = p[m.triangles[:, 0]], p[m.triangles[:, 1]], p[m.triangles[:, 2]]
    signed = 0.5 * ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    assert (signed > 0).all()  # counter-clockwise, none inverted
    assert signed.sum() == pytest.approx(area, rel=1e-9)
    # every boundary edge lies in exactly one triangle, with the mesh on its left
    directed = {(int(t[k]), int(t[(k + 1) % 3])) for t in m.triangles for k in range(3)}
    for a_, b_ in m.boundary_edges:
        assert (a_, b_) in directed and (b_, a_) not in directed
    assert ablmg.quality(m.points, m.triangles)["valid"]


def test_mesh_of_a_rectangle(square_mesh):
    check_mesh(square_mesh, 1.0)
    assert set(square_mesh.boundary_refs) == {1, 2, 3, 4}
    assert square_mesh.metric.shape == (square_mesh.num_vertices, 3)
    np.testing.assert_allclose(square_mesh.metric, [[400, 0, 400]] * square_mesh.num_vertices)
    # about (2/sqrt3) area / h^2 + boundary/2 vertices
    assert 450 < square_mesh.num_vertices < 560
    assert square_mesh.stats["vertices"] == square_mesh.num_vertices


def test_result_arrays_are_read_only_views(square_mesh):
    p = square_mesh.points
    assert not p.flags.writeable and not p.flags.owndata
    assert p.base is not None
    with pytest.raises(ValueError):
        p[0, 0] = 5.0
    # the same memory each time: a view, not a copy
    assert square_mesh.points.__array_interface__["data"][0] == p.__array_interface__["data"][0]
    refs = square_mesh.boundary_refs
    assert refs.strides == (12,)  # inside the C++ BoundaryEdge {a, b, ref}
    del square_mesh  # the view keeps the mesh alive
    assert p.sum() > 0


def test_remesh_to_a_graded_metric(square_mesh, graded_metric):
    r = ablmg.remesh(square_mesh.points, square_mesh.triangles, graded_metric, square_mesh.boundary_edges,
                     square_mesh.boundary_refs, hgrad=-1)
    check_mesh(r, 1.0)
    assert set(r.boundary_refs) == {1, 2, 3, 4}
    q = ablmg.quality(r.points, r.triangles, r.metric)
    assert q["edge_length"]["in_sqrt2"] > 0.95
    assert q["element_quality"]["mean"] > 0.9
    # the layer is refined: more vertices near x = 0.5
    near = np.abs(r.points[:, 0] - 0.5) < 0.1
    assert near.sum() > 0.3 * r.num_vertices


@pytest.mark.parametrize("points_dtype", [np.float64, np.float32, np.int64])
@pytest.mark.parametrize("index_dtype", [np.int32, np.int64, np.uint32, np.intp])
def test_input_dtypes_are_accepted(points_dtype, index_dtype):
    pts = np.array([[0, 0], [2, 0], [2, 2], [0, 2], [1, 1]], dtype=points_dtype)
    tri = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]], dtype=index_dtype)
    r = ablmg.remesh(pts, tri, np.full(5, 0.25))
    check_mesh(r, 4.0)
    assert set(r.boundary_refs) == {1}


def test_non_contiguous_and_clockwise_input(square_mesh):
    big = np.zeros((square_mesh.num_vertices, 4))
    big[:, ::2] = square_mesh.points  # strided view
    tri = np.array(square_mesh.triangles)[:, ::-1]  # clockwise
    r = ablmg.remesh(big[:, ::2], tri, np.full(square_mesh.num_vertices, 0.1), hgrad=-1)
    check_mesh(r, 1.0)


def test_sizes_and_tensors_give_the_same_mesh(square_mesh):
    n = square_mesh.num_vertices
    h = 0.05 + 0.05 * square_mesh.points[:, 0]
    a = ablmg.remesh(square_mesh.points, square_mesh.triangles, h, square_mesh.boundary_edges, square_mesh.boundary_refs)
    t = np.stack([1 / h**2, np.zeros(n), 1 / h**2], axis=1)
    b = ablmg.remesh(square_mesh.points, square_mesh.triangles, t, square_mesh.boundary_edges, square_mesh.boundary_refs)
    np.testing.assert_array_equal(a.points, b.points)
    np.testing.assert_array_equal(a.triangles, b.triangles)


def test_deterministic_and_seeded(square_mesh, graded_metric):
    args = (square_mesh.points, square_mesh.triangles, graded_metric, square_mesh.boundary_edges,
            square_mesh.boundary_refs)
    a, b = ablmg.remesh(*args), ablmg.remesh(*args)
    np.testing.assert_array_equal(a.points, b.points)
    one = ablmg.remesh(*args, options=ablmg.MeshOptions("remesh", threads=1))
    two = ablmg.remesh(*args, options=ablmg.MeshOptions("remesh", threads=2))
    np.testing.assert_array_equal(one.points, two.points)
    np.testing.assert_array_equal(one.triangles, two.triangles)
    np.testing.assert_array_equal(a.points, one.points)


def test_callable_metric_is_called_on_batches():
    calls = []

    def metric(x, y):
        assert x.dtype == np.float64 and x.shape == y.shape and x.ndim == 1
        calls.append(len(x))
        return 0.03 + 0.1 * np.abs(x - 0.5)

    m = ablmg.mesh(ablmg.Domain.rectangle(0, 0, 1, 1), metric)
    check_mesh(m, 1.0)
    assert max(calls) > 100  # vectorised: whole batches, not point by point
    h = 0.03 + 0.1 * np.abs(m.points[:, 0] - 0.5)
    np.testing.assert_allclose(m.metric[:, 0], 1 / h**2, rtol=1e-12)


def test_callable_metric_forms_agree():
    d = ablmg.Domain.rectangle(0, 0, 1, 1)
    tensor = ablmg.mesh(d, lambda x, y: np.stack([400 + 0 * x, 0 * x, 2500 + 0 * x], axis=1))
    tup = ablmg.mesh(d, lambda x, y: (400.0, 0.0, 2500.0))
    const = ablmg.mesh(d, (400.0, 0.0, 2500.0))
    np.testing.assert_array_equal(tensor.points, tup.points)
    assert abs(const.num_vertices - tup.num_vertices) < 0.02 * const.num_vertices


def test_domain_with_hole_and_tags():
    outer = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], float)
    hole = np.array([[0.8, 0.3], [1.2, 0.3], [1.2, 0.7], [0.8, 0.7]])
    d = ablmg.Domain(outer, [hole], outer_tags=[5, 6, 7, 8], hole_tags=[[9, 9, 9, 9]])
    assert d.area == pytest.approx(2 - 0.16)
    m = ablmg.mesh(d, 0.05)
    check_mesh(m, 2 - 0.16)
    assert set(m.boundary_refs) == {5, 6, 7, 8, 9}


def test_uniform_mesh_is_the_adaptive_loops_first_mesh():
    d = ablmg.Domain.problem("lshape")
    assert d.area == pytest.approx(3.0)
    m = ablmg.uniform_mesh(d, 1000)
    check_mesh(m, 3.0)
    assert set(m.boundary_refs) == {1, 2, 3, 4, 5, 6}
    assert 900 < m.num_vertices < 1100


def test_hessian_metric_of_a_quadratic(square_mesh):
    x, y = square_mesh.points.T
    u = 3 * x**2 + y**2  # H = diag(6, 2): sizes along x smaller by sqrt(3)
    M = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000)
    assert M.shape == (square_mesh.num_vertices, 3) and M.dtype == np.float64 and M.flags.writeable
    # the loop's shape (|H|/sqrt(det|H|))^1.05 (shape blend 0.05); shape_blend=0: the Lp shape |H|
    np.testing.assert_allclose(M[:, 0] / M[:, 2], 3.0**1.05, rtol=1e-6)
    M0 = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000, shape_blend=0)
    np.testing.assert_allclose(M0[:, 0] / M0[:, 2], 3.0, rtol=1e-6)
    np.testing.assert_allclose(M[:, 1], 0.0, atol=1e-6 * M[:, 0].max())
    # complexity (sqrt3/2) N: the unit mesh has about N vertices
    r = ablmg.remesh(square_mesh.points, square_mesh.triangles, M, square_mesh.boundary_edges, square_mesh.boundary_refs)
    assert 1800 < r.num_vertices < 2300
    h1 = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000, norm="h1", hgrad=1.5,
                              method="double")
    assert set(ablmg.ADAPT_DEFAULTS) >= {"p", "hgrad", "norm", "method", "shape_blend"}
    # norm 'h1' without p is the H1 seminorm (p = 2), not W^{1,inf}
    h1p2 = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000, norm="h1", p=2, hgrad=1.5,
                                method="double")
    np.testing.assert_array_equal(h1, h1p2)
    h1inf = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000, norm="h1", p=np.inf,
                                 hgrad=1.5, method="double")
    assert not np.array_equal(h1, h1inf)
    Md = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 2000,
                              shape_blend=ablmg.ADAPT_DEFAULTS["shape_blend"])
    np.testing.assert_array_equal(Md, M)  # the listed default is the one the call uses
    assert np.isfinite(h1).all()


def test_hessian_metric_takes_any_vertex_order(square_mesh):
    """A solver's own numbering (DOLFINx reorders): permuted input, permuted output."""
    n = square_mesh.num_vertices
    perm = np.random.default_rng(0).permutation(n)
    inv = np.argsort(perm)
    x, y = square_mesh.points.T
    u = np.sin(4 * x) * np.cos(3 * y)
    # without gradation: its sweeps run in edge order, so they see a renumbered mesh differently
    # (within their tolerance)
    M = ablmg.hessian_metric(square_mesh.points, square_mesh.triangles, u, 3000, hgrad=-1)
    Mp = ablmg.hessian_metric(square_mesh.points[perm], inv[square_mesh.triangles], u[perm], 3000, hgrad=-1)
    np.testing.assert_allclose(Mp, M[perm], rtol=1e-9)


def test_quality_matches_identity_and_metric(square_mesh):
    q = ablmg.quality(square_mesh.points, square_mesh.triangles, square_mesh.metric)
    assert q["vertices"] == square_mesh.num_vertices and q["triangles"] == square_mesh.num_triangles
    assert 0.9 < q["edge_length"]["mean"] < 1.1
    e = ablmg.quality(square_mesh.points, square_mesh.triangles)  # identity: Euclidean lengths
    assert e["edge_length"]["mean"] == pytest.approx(0.05 * q["edge_length"]["mean"], rel=1e-9)
    # q is scale-invariant: the same up to round-off (the metric 400 I scales every length by 20)
    assert e["element_quality"].keys() == q["element_quality"].keys()
    for key, value in q["element_quality"].items():
        assert e["element_quality"][key] == pytest.approx(value, rel=1e-12, abs=1e-15), key


def test_mesh_from_arrays_and_options(square_mesh):
    m = ablmg.Mesh(np.array(square_mesh.points), square_mesh.triangles, square_mesh.boundary_edges,
                   square_mesh.boundary_refs, square_mesh.metric)
    np.testing.assert_array_equal(m.boundary_refs, square_mesh.boundary_refs)
    o = ablmg.MeshOptions("adapt", seed=7)
    assert (o.seed, o.lattice, o.defect_passes, o.plateau_steps) == (7, "short", 0, 10)
    assert ablmg.MeshOptions().defect_passes == 6
    assert "remesh(points, triangles, metric" in ablmg.remesh.__doc__
    for f in (ablmg.mesh, ablmg.remesh, ablmg.hessian_metric, ablmg.quality, ablmg.read_mesh, ablmg.write_mesh,
              ablmg.write_vtu, ablmg.uniform_mesh, ablmg.Mesh, ablmg.Domain, ablmg.MeshOptions):
        assert f.__doc__ and len(f.__doc__) > 100, f
