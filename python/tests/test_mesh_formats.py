# SPDX-License-Identifier: MIT
"""3MF through ttd.load_mesh with deflated zip entries written by Python's zipfile (so the
reader's inflate is checked against zlib's deflate): objects, components and build items with
transforms placed as constructed; the triangle count equals assimp's (`assimp info`, Debian
assimp-utils) where it is installed, skipped otherwise."""
import re
import shutil
import subprocess
import zipfile

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus

RELS = ('<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/'
        'relationships"><Relationship Target="/3D/3dmodel.model" Id="rel0" '
        'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')


def mesh_object(oid, v, f):
    s = [f'<object id="{oid}" type="model"><mesh><vertices>']
    s += [f'<vertex x="{x!r}" y="{y!r}" z="{z!r}"/>' for x, y, z in np.asarray(v).tolist()]
    s += ['</vertices><triangles>']
    s += [f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in np.asarray(f).tolist()]
    s += ['</triangles></mesh></object>']
    return "".join(s)


def write_3mf(path, resources, items):
    model = ('<?xml version="1.0" encoding="UTF-8"?>\n<model unit="millimeter" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>' + resources +
             '</resources><build>' + items + '</build></model>')
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("[Content_Types].xml", '<?xml version="1.0"?><Types/>')
        z.writestr("_rels/.rels", RELS)
        z.writestr("3D/3dmodel.model", model)


def test_3mf_deflated_components_and_items(tmp_path):
    v, f = icosphere(2)
    v = np.asarray(v)
    path = tmp_path / "parts.3mf"
    # object 1: the sphere; object 2: two components of it (shifted by x + 3, and scaled by 2 and
    # shifted by y + 10); the build: object 1 as is, object 2 shifted by z + 5
    res = mesh_object(1, v, f) + ('<object id="2"><components><component objectid="1" transform="1 0 0 0 1 0 0 0 1 3 0 0"/>'
                                  '<component objectid="1" transform="2 0 0 0 2 0 0 0 2 0 10 0"/></components></object>')
    write_3mf(path, res, '<item objectid="1"/><item objectid="2" transform="1 0 0 0 1 0 0 0 1 0 0 5"/>')
    got, faces = ttd.load_mesh(path)
    n = len(v)
    assert len(got) == 3 * n and len(faces) == 3 * len(f)
    np.testing.assert_array_equal(got[:n], v)
    np.testing.assert_array_equal(got[n:2 * n], v + [3, 0, 5])
    np.testing.assert_array_equal(got[2 * n:], 2 * v + [0, 10, 5])
    np.testing.assert_array_equal(faces[len(f):2 * len(f)], np.asarray(f) + n)
    mesh = ttd.Mesh.from_file(path)
    assert mesh.triangle_count == 3 * len(f)


@pytest.mark.skipif(shutil.which("assimp") is None, reason="assimp (Debian assimp-utils) not installed: no independent count")
@pytest.mark.parametrize("shape", ["icosphere", "torus"])
def test_3mf_count_equals_assimp(tmp_path, shape):
    v, f = icosphere(3) if shape == "icosphere" else torus(1.0, 0.3, 30, 12)
    path = tmp_path / f"{shape}.3mf"
    write_3mf(path, mesh_object(1, v, f), '<item objectid="1"/>')
    _, faces = ttd.load_mesh(path)
    info = subprocess.run(["assimp", "info", str(path)], capture_output=True, text=True, timeout=120).stdout
    m = re.search(r"Faces:\s+(\d+)", info)
    assert m, info
    assert len(faces) == int(m.group(1)) == len(f)


def test_3mf_malformed(tmp_path):
    v, f = icosphere(1)
    good = tmp_path / "good.3mf"
    write_3mf(good, mesh_object(1, v, f), '<item objectid="1"/>')
    data = good.read_bytes()
    for cut in range(0, len(data), max(1, len(data) // 50)):
        p = tmp_path / "cut.3mf"
        p.write_bytes(data[:cut])
        with pytest.raises(ValueError):
            ttd.load_mesh(p)
    # a damaged deflate stream: the model entry's bytes flipped (its sizes kept)
    z = zipfile.ZipFile(good)
    info = z.getinfo("3D/3dmodel.model")
    start = info.header_offset + 30 + len(info.filename.encode()) + len(info.extra)
    bad = bytearray(data)
    for k in range(start + 10, start + 40):
        bad[k] ^= 0x5A
    p = tmp_path / "flipped.3mf"
    p.write_bytes(bytes(bad))
    with pytest.raises(ValueError, match="3MF"):
        ttd.load_mesh(p)
