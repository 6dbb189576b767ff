"""Bad input raises ValueError/TypeError with a message naming the argument, never crashes.

The hostile-input rows of docs/hostile_inputs.md that apply to arrays, one test each (the row
in the docstring), then argument checks.
"""
import math

import numpy as np
import pytest

import ablmg
from conftest import DATA

SQUARE = ablmg.Domain.rectangle(0, 0, 1, 1)
PTS = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]])
TRI = np.array([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]])
H = np.full(5, 0.2)


def valid(m):
    assert ablmg.quality(m.points, m.triangles)["valid"]
    return m


# --- docs/hostile_inputs.md rows -------------------------------------------------------------

def test_tiny_size_refused_before_allocating():
    """metric size 1e-6 on the unit square (~10^12 nodes)"""
    with pytest.raises(ValueError, match="more than maxNodes"):
        ablmg.mesh(SQUARE, 1e-6)


def test_max_nodes_limit():
    """same with --max-nodes 1000"""
    with pytest.raises(ValueError, match="maxNodes = 1000"):
        ablmg.mesh(SQUARE, 0.01, options=ablmg.MeshOptions(max_nodes=1000))


def test_huge_size():
    """metric size 1e6 on the unit square: 4 vertices, 2 triangles"""
    m = valid(ablmg.mesh(SQUARE, 1e6))
    assert (m.num_vertices, m.num_triangles) == (4, 2)


def test_crowded_hole_corners():
    """a hole whose polygon sides are 5x shorter than the metric size: valid, every point kept"""
    hole = np.array([[0.5, 0.5], [0.52, 0.5], [0.52, 0.52], [0.5, 0.52]])
    m = valid(ablmg.mesh(ablmg.Domain(PTS[:4], [hole]), 0.1))
    for p in hole:
        assert np.min(np.hypot(*(m.points - p).T)) == 0


def test_anisotropy_1e5():
    """anisotropy 1e5 (h1 = 100, h2 = 1e-3): a valid mesh"""
    c, s = math.cos(0.3), math.sin(0.3)
    l1, l2 = 1 / 100**2, 1 / 1e-3**2
    m = valid(ablmg.mesh(SQUARE, (l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c)))
    assert m.num_vertices > 100


def test_near_singular_metrics():
    """near-singular SPD tensors (1e4, 0.99999999e4, 1e4) and (1, 1 - 1e-13, 1): valid meshes"""
    valid(ablmg.mesh(SQUARE, (1e4, 0.99999999e4, 1e4)))
    m = valid(ablmg.mesh(SQUARE, (1.0, 1 - 1e-13, 1.0)))
    assert (m.num_vertices, m.num_triangles) == (4, 2)


def test_metric_jumping_along_a_thin_layer():
    """a metric jumping 16x every 0.075 along a layer 2e-4 thin (boundary nodes pushed into a corner)"""
    def metric(x, y):
        h1 = 0.1 * 4 ** np.sin(2 * np.pi * x / 0.15)
        h2 = 2e-4 + 0.05 * np.abs(y - 0.5)
        return np.stack([1 / h1**2, 0 * x, 1 / h2**2], axis=1)
    # sampled on a 5e4-vertex background: the direct callable spends minutes in single-point
    # calls from the quality post-pass (most triangles here are repaired ones)
    valid(ablmg.mesh(SQUARE, metric, background_vertices=5e4))


def test_nan_metric_names_the_point():
    """NaN metric (sqrt(x - 0.5))"""
    with pytest.raises(ValueError, match=r"metric\(x, y\) at \(.*\): size -?nan"):
        with np.errstate(invalid="ignore"):
            ablmg.mesh(SQUARE, lambda x, y: np.sqrt(x - 0.5))
    with pytest.raises(ValueError, match=r"metric\[2\]: size -?nan"):
        ablmg.remesh(PTS, TRI, np.array([0.2, 0.2, np.nan, 0.2, 0.2]))


def test_non_spd_metric():
    """non-SPD tensor (m12 = 2, m11 = m22 = 1)"""
    with pytest.raises(ValueError, match=r"tensor \(1, 2, 1\) is not positive definite"):
        ablmg.mesh(SQUARE, (1.0, 2.0, 1.0))
    with pytest.raises(ValueError, match=r"metric\(x, y\) at .*not positive definite"):
        ablmg.mesh(SQUARE, lambda x, y: (1.0, 2.0, 1.0))
    bad = np.tile([1.0, 0.0, 1.0], (5, 1))
    bad[3] = [1, 2, 1]
    with pytest.raises(ValueError, match=r"metric\[3\].*not positive definite"):
        ablmg.remesh(PTS, TRI, bad)


def test_infinite_coordinate():
    """coordinate overflowing to inf (1e400)"""
    pts = PTS.copy()
    pts[2, 1] = float("1e400")
    with pytest.raises(ValueError, match=r"points\[2, 1\] is not finite \(inf\)"):
        ablmg.remesh(pts, TRI, H)
    with pytest.raises(ValueError, match=r"outer\[2, 1\] is not finite"):
        ablmg.Domain(pts[:4])


def test_self_intersecting_outer_loop():
    """self-intersecting outer loop (bow tie)"""
    with pytest.raises(ValueError, match="intersects outer loop 0 segment 2"):
        ablmg.Domain([[0, 0], [1, 1], [1, 0], [0, 1]])


def test_hole_touching_the_outer_loop():
    """hole touching the outer loop"""
    with pytest.raises(ValueError, match="intersects hole 1"):
        ablmg.Domain(PTS[:4], [[[0.5, 0.0], [0.7, 0.3], [0.3, 0.3]]])


def test_duplicate_consecutive_vertex():
    """duplicate consecutive vertex"""
    with pytest.raises(ValueError, match=r"segment 1 has zero length \(point \(1, 0\) repeated\)"):
        ablmg.Domain([[0, 0], [1, 0], [1, 0], [1, 1], [0, 1]])


def test_empty_input():
    """empty config file: empty arrays"""
    with pytest.raises(ValueError, match="points: expected shape"):
        ablmg.remesh([], TRI, H)
    with pytest.raises(ValueError, match="triangles: no triangles"):
        ablmg.remesh(PTS, np.zeros((0, 3), int), H)


def test_wrong_type():
    """wrong JSON type: wrong dtypes"""
    with pytest.raises(TypeError, match="points: expected a real"):
        ablmg.remesh(PTS.astype(complex), TRI, H)
    with pytest.raises(TypeError, match="triangles: expected an integer array, got dtype float64"):
        ablmg.remesh(PTS, TRI.astype(float), H)
    with pytest.raises(TypeError, match="metric: expected a real"):
        ablmg.remesh(PTS, TRI, np.array(["a"] * 5))
    with pytest.raises(TypeError):
        ablmg.remesh(PTS, TRI, None)
    with pytest.raises(TypeError, match=r"metric\(x, y\): expected a real array"):
        ablmg.mesh(SQUARE, lambda x, y: "small")


def test_option_out_of_range():
    """option out of range (improve qThreshold 1.5)"""
    with pytest.raises(ValueError, match="qThreshold must be in"):
        ablmg.mesh(SQUARE, 0.2, options=ablmg.MeshOptions(quality_threshold=1.5))
    with pytest.raises(ValueError, match="hgrad"):
        ablmg.remesh(PTS, TRI, H, hgrad=0.5)
    with pytest.raises(ValueError, match="hmin"):
        ablmg.remesh(PTS, TRI, H, hmin=0.5, hmax=0.1)


def test_unknown_lattice():
    """unknown lattice orientation"""
    with pytest.raises(ValueError, match="expected axes, short, long or auto, got 'diagonal'"):
        ablmg.remesh(PTS, TRI, H, lattice="diagonal")
    with pytest.raises(ValueError, match="'diagonal'"):
        ablmg.MeshOptions(lattice="diagonal")


def test_open_boundary():
    """open .poly boundary: boundary edges that are not the mesh's boundary"""
    edges = np.array([[0, 1], [1, 2], [2, 3]])  # (3, 0) missing
    with pytest.raises(ValueError, match="remesh: invalid mesh"):
        ablmg.remesh(PTS, TRI, H, edges)


@pytest.mark.parametrize("name, message", [
    ("truncated.mesh", r"truncated\.mesh:\d+"), ("garbage.mesh", r"garbage\.mesh:\d+"),
    ("empty.mesh", r"empty\.mesh"), ("nan.mesh", r"nan\.mesh:\d+"), ("bad_index.mesh", r"bad_index\.mesh:\d+")])
def test_bad_mesh_files(name, message):
    """remesh: truncated / garbage / empty .mesh, NaN coordinate, vertex index out of range"""
    with pytest.raises(ValueError, match=message):
        ablmg.read_mesh(str(DATA / name))


def test_index_out_of_range_in_arrays():
    """vertex index out of range, in arrays"""
    tri = TRI.copy()
    tri[1, 2] = 5
    with pytest.raises(ValueError, match=r"triangles\[1, 2\] = 5 is not a vertex id in \[0, 5\)"):
        ablmg.remesh(PTS, tri, H)
    with pytest.raises(ValueError, match=r"triangles\[0, 0\] = -1"):
        ablmg.remesh(PTS, -np.ones_like(TRI), H)


def test_non_spd_sol_file():
    """remesh: non-SPD tensor in .sol"""
    with pytest.raises(ValueError, match=r"nonspd\.sol:\d+: tensor of vertex 5 .* not positive definite"):
        ablmg.read_mesh(str(DATA / "square.mesh"), str(DATA / "nonspd.sol"))


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf, float("1e400")])
def test_non_finite_metric_entries(value):
    """remesh: NaN, +-Inf or overflowing entries in a tensor or scalar metric"""
    bad = np.tile([1.0, 0.0, 1.0], (5, 1))
    bad[0, 0] = value
    with pytest.raises(ValueError, match=r"metric\[0\]"):
        ablmg.remesh(PTS, TRI, bad)
    with pytest.raises(ValueError, match=r"metric\[1\]"):
        ablmg.remesh(PTS, TRI, np.array([0.2, value, 0.2, 0.2, 0.2]))


def test_negative_size():
    """remesh: negative size"""
    with pytest.raises(ValueError, match=r"metric\[3\]: size -0.2 must be positive"):
        ablmg.remesh(PTS, TRI, np.array([0.2, 0.2, 0.2, -0.2, 0.2]))
    with pytest.raises(ValueError, match="size -0.2"):
        ablmg.mesh(SQUARE, -0.2)


def test_metric_count_mismatch():
    """remesh: .sol with a different vertex count"""
    with pytest.raises(ValueError, match=r"metric: expected shape \(5, 3\) .* or \(5,\) sizes, got \(3, 3\)"):
        ablmg.remesh(PTS, TRI, np.ones((3, 3)))
    with pytest.raises(ValueError, match=r"u: expected shape \(5,\), got \(4,\)"):
        ablmg.hessian_metric(PTS, TRI, np.zeros(4), 100)


def test_unknown_flag():
    """unknown flag: unknown keyword"""
    with pytest.raises(TypeError):
        ablmg.remesh(PTS, TRI, H, hgard=1.5)
    with pytest.raises(ValueError, match="unknown field 'platau_gain'"):
        ablmg.MeshOptions(platau_gain=0.1)


def test_failed_writer_leaves_the_old_file(tmp_path):
    """a writer failing half-way: the previous file is left intact, no temporary left behind"""
    m = ablmg.remesh(PTS, TRI, H)
    path = tmp_path / "m.mesh"
    ablmg.write_mesh(str(path), m, sol=False)
    before = path.read_bytes()
    with pytest.raises(ValueError, match="x.sol"):  # the .sol cannot be written: all or nothing
        ablmg.write_mesh(str(tmp_path / "n.mesh"), m, sol=str(tmp_path / "missing" / "x.sol"))
    assert not (tmp_path / "n.mesh").exists()
    (tmp_path / "d.mesh").mkdir()  # rename over a directory fails
    with pytest.raises(ValueError, match="d.mesh"):
        ablmg.write_mesh(str(tmp_path / "d.mesh"), m)
    assert (tmp_path / "d.mesh").is_dir()
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.mesh", "m.mesh"]
    with pytest.raises(ValueError, match="must end in .mesh"):
        ablmg.write_mesh(str(tmp_path / "m.txt"), m)


def test_same_result_on_one_and_two_threads():
    """same config with 1 and 2 threads: identical meshes"""
    f = lambda x, y: 0.02 + 0.2 * np.abs(x - 0.5)
    one = ablmg.mesh(SQUARE, f, options=ablmg.MeshOptions(threads=1))
    two = ablmg.mesh(SQUARE, f, options=ablmg.MeshOptions(threads=2))
    np.testing.assert_array_equal(one.points, two.points)
    np.testing.assert_array_equal(one.triangles, two.triangles)


def test_coincident_vertices():
    """coincident nodes: a duplicated, unused vertex makes the mesh invalid"""
    pts = np.vstack([PTS, PTS[4]])
    with pytest.raises(ValueError, match="invalid mesh"):
        ablmg.remesh(pts, TRI, np.full(6, 0.2))


def test_invalid_file_mesh_names_the_files_ids(tmp_path):
    """a mesh read from a medit file is judged in the file's own 1-based numbering"""
    path = tmp_path / "unused.mesh"
    path.write_text("MeshVersionFormatted 2\nDimension 2\nVertices\n5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n5 5 0\n"
                    "Triangles\n2\n1 2 3 1\n1 3 4 1\nEnd\n")
    with pytest.raises(ValueError, match=r"unused.mesh: invalid mesh \(ids from 1, as in the file\): vertex 5 is used"):
        ablmg.read_mesh(str(path))
    # The same mesh as arrays: ids from 0, as in the arrays.
    pts = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [5, 5]], dtype=float)
    with pytest.raises(ValueError, match=r"invalid mesh: vertex 4 is used"):
        ablmg.remesh(pts, np.array([[0, 1, 2], [0, 2, 3]]), np.full(5, 0.2))


# --- other argument checks -------------------------------------------------------------------

def test_inverted_and_degenerate_triangles():
    flat = PTS.copy()
    flat[4] = [0.5, 0.0]  # on the bottom side: a zero-area triangle
    with pytest.raises(ValueError, match="invalid mesh"):
        ablmg.remesh(flat, TRI, H)
    overlap = np.vstack([TRI, [[0, 1, 2]]])
    with pytest.raises(ValueError, match="invalid mesh"):
        ablmg.hessian_metric(PTS, overlap, np.zeros(5), 100)


def test_bad_shapes():
    with pytest.raises(ValueError, match=r"points: expected shape \(n, 2\), got \(5, 3\)"):
        ablmg.remesh(np.zeros((5, 3)), TRI, H)
    with pytest.raises(ValueError, match=r"triangles: expected shape \(m, 3\), got \(4, 2\)"):
        ablmg.remesh(PTS, TRI[:, :2], H)
    with pytest.raises(ValueError, match="boundary_refs given without boundary_edges"):
        ablmg.remesh(PTS, TRI, H, boundary_refs=[1, 2, 3, 4])
    with pytest.raises(ValueError, match=r"boundary_refs: expected shape \(4,\)"):
        ablmg.remesh(PTS, TRI, H, [[0, 1], [1, 2], [2, 3], [3, 0]], [1, 2])
    with pytest.raises(ValueError, match="tuple result must be"):
        ablmg.mesh(SQUARE, lambda x, y: (1.0, 0.0))


def test_bad_hessian_options():
    u = PTS[:, 0] ** 2
    with pytest.raises(ValueError, match="expected l2 or h1|valid|norm"):
        ablmg.hessian_metric(PTS, TRI, u, 100, norm="l3")
    with pytest.raises(ValueError, match="lsq"):
        ablmg.hessian_metric(PTS, TRI, u, 100, method="cubic")
    with pytest.raises(ValueError, match="targetVertices"):
        ablmg.hessian_metric(PTS, TRI, u, 1)
    with pytest.raises(ValueError, match=r"u\[2\] is not finite"):
        ablmg.hessian_metric(PTS, TRI, np.array([0, 0, np.nan, 0, 0.0]), 100)
    with pytest.raises(ValueError, match="hmin, hmax and hgrad must be None"):
        ablmg.remesh(PTS, TRI, H, domain=SQUARE, hmin=0.1)


def test_exception_from_the_metric_callable_propagates():
    class Boom(Exception):
        pass

    def metric(x, y):
        raise Boom("from the callable")

    with pytest.raises(Boom, match="from the callable"):
        ablmg.mesh(SQUARE, metric)
    assert ablmg.mesh(SQUARE, 0.25).num_vertices > 4  # the module still works
