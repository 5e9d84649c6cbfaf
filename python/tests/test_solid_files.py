# SPDX-License-Identifier: MIT
"""Solids (solid=True) and mesh files in Python (ttd.load_mesh, ttd.Mesh.from_file): the C
library's behaviour reaches Python unchanged, checked against answers known by construction."""
import numpy as np
import pytest

import ttd

CUBE_V = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
CUBE_F = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                   [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]], np.uint32)
TET_V = np.array([[0.4, 0.4, 0.4], [0.6, 0.4, 0.4], [0.4, 0.6, 0.4], [0.4, 0.4, 0.6]])
TET_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], np.uint32)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_solid_inside(dtype):
    cube, tet = ttd.Mesh(CUBE_V.astype(dtype), CUBE_F), ttd.Mesh(TET_V.astype(dtype), TET_F)
    surface = ttd.mesh_distance(cube, tet)
    assert surface.distance == pytest.approx(0.4, rel=1e-6) and not surface.flags & ttd.MeshFlag.CONTAINED
    solid = ttd.mesh_distance(cube, tet, solid=True)
    assert solid.distance == 0 and solid.flags & ttd.MeshFlag.CONTAINED and solid.flags & ttd.MeshFlag.INTERSECTING
    assert solid.tri_a == ttd.NO_TRIANGLE and solid.tri_b == 0
    np.testing.assert_array_equal(solid.p, solid.q)
    np.testing.assert_array_equal(solid.p, TET_V[0].astype(dtype))
    assert not ttd.mesh_collide(cube, tet).hit and ttd.mesh_collide(cube, tet, solid=True).hit
    far = ttd.pose(t=[5, 0, 0])
    assert ttd.mesh_distance(cube, tet, far, solid=True).distance == ttd.mesh_distance(cube, tet, far).distance
    # K poses: contained, apart, contained
    poses = np.stack([ttd.pose(), far, ttd.pose(t=[0.1, 0, 0])])
    r = ttd.mesh_distance(cube, tet, poses, solid=True)
    assert list(r.distance == 0) == [True, False, True]
    # an open mesh is refused in solid mode only
    open_tet = ttd.Mesh(TET_V.astype(dtype), TET_F[:3])
    with pytest.raises(ValueError, match="closed"):
        ttd.mesh_distance(cube, open_tet, solid=True)
    with pytest.raises(ValueError, match="closed"):
        ttd.mesh_collide(open_tet, cube, solid=True)
    assert ttd.mesh_distance(cube, open_tet).distance > 0


def test_load_mesh_and_from_file(tmp_path):
    obj = tmp_path / "cube.obj"
    lines = ["6540 2180  # a header of two counts, as FCL's env.obj has"]
    lines += [f"v {x:g} {y:g} {z:g}" for x, y, z in CUBE_V]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in CUBE_F]
    obj.write_text("\n".join(lines) + "\n")
    with pytest.warns(UserWarning, match="skipped 1 line"):
        v, f = ttd.load_mesh(obj)
    np.testing.assert_array_equal(v, CUBE_V)
    np.testing.assert_array_equal(f, CUBE_F)
    assert v.dtype == np.float64 and f.dtype == np.uint32
    with pytest.raises(ValueError, match=r"cube.obj:1"):
        ttd.load_mesh(str(obj), strict=True)
    with pytest.warns(UserWarning):
        v32, _ = ttd.load_mesh(obj, precision="float32")
    assert v32.dtype == np.float32
    m = ttd.Mesh.from_file(obj, precision="float32")
    assert m.dtype == np.float32 and m.triangle_count == 12
    np.testing.assert_array_equal(m.faces, CUBE_F)
    # the same file through the library and through arrays: the same answers
    a = ttd.Mesh(CUBE_V, CUBE_F)
    b = ttd.Mesh.from_file(obj)
    P = ttd.pose(t=[0.3, 2.5, 0.1])
    assert ttd.mesh_distance(a, b, P).distance == ttd.mesh_distance(a, a, P).distance
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nf 1 2 9\n")
    with pytest.raises(ValueError, match=r"bad.obj:3"):
        ttd.load_mesh(bad)
    with pytest.raises(FileNotFoundError):  # I/O errors are OSError subclasses
        ttd.load_mesh(tmp_path / "missing.stl")
    with pytest.raises(FileNotFoundError):
        ttd.Mesh.from_file(tmp_path / "missing.stl")
    with pytest.raises(IsADirectoryError):
        ttd.load_mesh(tmp_path)
    with pytest.raises(ValueError, match="precision"):
        ttd.load_mesh(obj, precision="float16")
    with pytest.raises(TypeError):
        ttd.load_mesh(None)
