"""Files: byte-identical to `ablmg remesh`; medit and VTU interchange with meshio."""
import subprocess

import meshio
import numpy as np
import pytest

import ablmg
from conftest import DATA


def remesh_with_both(tmp_path, ablmg_bin, mesh, sol, flags, **kwargs):
    cli_out = tmp_path / "cli.mesh"
    subprocess.run([str(ablmg_bin), "remesh", "-in", str(mesh), "-sol", str(sol), "-out", str(cli_out), "-v", "-1",
                    *flags], check=True)
    arrays = kwargs.pop("arrays", True)
    m = ablmg.read_mesh(str(mesh), str(sol))
    r = ablmg.remesh(m, **kwargs)
    if arrays:  # the arrays alone give the same mesh for files without corners or required entities
        a = ablmg.remesh(m.points, m.triangles, m.metric, m.boundary_edges, m.boundary_refs, **kwargs)
        np.testing.assert_array_equal(a.points, r.points)
    py_out = tmp_path / "py.mesh"
    ablmg.write_mesh(str(py_out), r)
    return cli_out, py_out, r


@pytest.mark.parametrize("flags, kwargs", [
    ([], {}),
    (["-hgrad", "-1", "--seed", "3"], {"hgrad": -1, "seed": 3}),
    (["-hmin", "0.02", "-hmax", "0.05", "--lattice", "short"], {"hmin": 0.02, "hmax": 0.05, "lattice": "short"}),
])
def test_byte_identical_to_ablmg_remesh(tmp_path, ablmg_bin, square_mesh, graded_metric, flags, kwargs):
    src = tmp_path / "in.mesh"
    ablmg.write_mesh(str(src), ablmg.Mesh(square_mesh.points, square_mesh.triangles, square_mesh.boundary_edges,
                                          square_mesh.boundary_refs, graded_metric))
    cli, py, r = remesh_with_both(tmp_path, ablmg_bin, src, src.with_suffix(".sol"), flags, **kwargs)
    assert r.num_vertices > 300
    assert py.read_bytes() == cli.read_bytes()
    assert py.with_suffix(".sol").read_bytes() == cli.with_suffix(".sol").read_bytes()


def test_byte_identical_on_a_freefem_file(tmp_path, ablmg_bin):
    src = DATA / "freefem_square.mesh"  # written by FreeFem++: its orientation, its refs
    m = ablmg.read_mesh(str(src))
    sol = tmp_path / "h.sol"
    ablmg.write_mesh(str(tmp_path / "h.mesh"), ablmg.Mesh(m.points, m.triangles, m.boundary_edges, m.boundary_refs,
                                                           np.full(m.num_vertices, 0.08)), sol=str(sol))
    cli, py, r = remesh_with_both(tmp_path, ablmg_bin, src, sol, [])
    assert r.num_vertices > 100
    assert py.read_bytes() == cli.read_bytes()


def test_byte_identical_with_corners_and_required_vertices(tmp_path, ablmg_bin):
    """square.mesh has Corners and RequiredVertices sections: remesh(Mesh) keeps them as the CLI does."""
    cli, py, r = remesh_with_both(tmp_path, ablmg_bin, DATA / "square.mesh", DATA / "square.sol", [], arrays=False)
    assert py.read_bytes() == cli.read_bytes()
    assert py.with_suffix(".sol").read_bytes() == cli.with_suffix(".sol").read_bytes()


def test_medit_round_trip(tmp_path, square_mesh):
    path = tmp_path / "m.mesh"
    ablmg.write_mesh(str(path), square_mesh)
    back = ablmg.read_mesh(str(path), str(path.with_suffix(".sol")))
    np.testing.assert_array_equal(back.points, square_mesh.points)  # shortest round-trip doubles
    np.testing.assert_array_equal(back.triangles, square_mesh.triangles)
    np.testing.assert_array_equal(back.boundary_refs, square_mesh.boundary_refs)
    np.testing.assert_array_equal(back.metric, square_mesh.metric)


def test_meshio_reads_our_medit_and_vtu(tmp_path, square_mesh):
    ablmg.write_mesh(str(tmp_path / "m.mesh"), square_mesh)
    mm = meshio.read(str(tmp_path / "m.mesh"))
    np.testing.assert_array_equal(mm.points[:, :2], square_mesh.points)
    np.testing.assert_array_equal(mm.cells_dict["triangle"], square_mesh.triangles)
    np.testing.assert_array_equal(mm.cells_dict["line"], square_mesh.boundary_edges)
    line_refs = [d for c, d in zip(mm.cells, mm.cell_data["medit:ref"]) if c.type == "line"][0]
    np.testing.assert_array_equal(line_refs, square_mesh.boundary_refs)

    u = np.sin(square_mesh.points[:, 0])
    q = np.arange(square_mesh.num_triangles, dtype=float)
    ablmg.write_vtu(str(tmp_path / "m.vtu"), square_mesh, point_data={"u": u}, cell_data={"q": q})
    vm = meshio.read(str(tmp_path / "m.vtu"))
    np.testing.assert_array_equal(vm.points[:, :2], square_mesh.points)
    np.testing.assert_array_equal(vm.cells_dict["triangle"], square_mesh.triangles)
    np.testing.assert_array_equal(vm.point_data["u"], u)
    np.testing.assert_array_equal(vm.point_data["metric"], square_mesh.metric)
    np.testing.assert_array_equal(vm.cell_data["q"][0], q)


def test_we_read_a_mesh_meshio_wrote(tmp_path, square_mesh):
    # a meshio mesh numbered differently: triangles reversed (clockwise), vertex order shuffled
    perm = np.random.default_rng(1).permutation(square_mesh.num_vertices)
    inv = np.argsort(perm)
    tri = inv[np.array(square_mesh.triangles)][:, ::-1]
    lines = inv[np.array(square_mesh.boundary_edges)]
    out = meshio.Mesh(np.array(square_mesh.points)[perm], [("triangle", tri), ("line", lines)],
                      cell_data={"medit:ref": [np.zeros(len(tri), int), np.array(square_mesh.boundary_refs)]})
    meshio.write(str(tmp_path / "mio.mesh"), out)
    m = ablmg.read_mesh(str(tmp_path / "mio.mesh"))
    assert (m.num_vertices, m.num_triangles) == (square_mesh.num_vertices, square_mesh.num_triangles)
    assert m.area == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_array_equal(sorted(m.boundary_refs), sorted(square_mesh.boundary_refs))
    r = ablmg.remesh(m.points, m.triangles, np.full(m.num_vertices, 0.1), m.boundary_edges, m.boundary_refs)
    assert set(r.boundary_refs) == {1, 2, 3, 4}
