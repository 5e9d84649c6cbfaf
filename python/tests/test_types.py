# SPDX-License-Identifier: MIT
"""The result types are the named tuples the stub (_ttd.pyi) and the README say they are; the
package's namespace holds what it documents; the README's and docs' examples type-check against
the stub with mypy (Debian's python3-mypy; skipped, saying so, where it is not installed)."""
import copy
import os
import pathlib
import pickle
import re
import subprocess
import sys

import numpy as np
import pytest

import ttd
from meshes import icosphere, torus

REPO = pathlib.Path(__file__).resolve().parents[2]
RESULT_TYPES = ("PairResult", "MeshDistance", "MeshContacts", "MeshCollision", "MeshClosest", "ClosestPartners",
                "SceneCollision", "SceneContacts", "SceneDistance", "SceneManifold")


def _results():
    S = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    A, B = ttd.Mesh(*icosphere(1)), ttd.Mesh(*torus())
    P = np.tile(np.eye(4), (3, 1, 1))
    P[:, 0, 3] = [0.0, 1.5, 4.0]
    closest = ttd.mesh_closest(A, B, P, 0.5)
    scene = ttd.Scene([A, B, A], P)
    return {"SceneCollision": scene.collide(0.5),
            "SceneContacts": scene.contacts(0.5),
            "SceneDistance": scene.distance(nearest=True),
            "SceneManifold": scene.manifold(0.5),
            "PairResult": ttd.distance(S, S + 2, points=True),
            "MeshDistance": ttd.mesh_distance(A, B, P),
            "MeshContacts": ttd.mesh_contacts(A, B, P, 0.1),
            "MeshCollision": ttd.mesh_collide(A, B, P),
            "MeshClosest": closest,
            "ClosestPartners": closest.for_a}


@pytest.mark.parametrize("name", RESULT_TYPES)
def test_results_are_named_tuples(name):
    r = _results()[name]
    cls = getattr(ttd, name)
    assert type(r) is cls and isinstance(r, tuple)
    assert cls.__module__ == "ttd" and cls.__name__ == name
    fields = cls._fields
    assert len(fields) == len(r) and all(isinstance(f, str) for f in fields)
    d = r._asdict()
    assert list(d) == list(fields)
    for i, f in enumerate(fields):
        assert d[f] is r[i] is getattr(r, f)
        assert getattr(cls, f).__doc__ and "Alias for field" not in getattr(cls, f).__doc__
    assert cls.__doc__ and cls.__doc__.startswith(f"{name}(") is False and len(cls.__doc__) > 40
    r2 = r._replace(**{fields[0]: "x"})
    assert type(r2) is cls and r2[0] == "x" and r2[1:] == r[1:]
    assert cls._make(list(r)) == r and cls(*r) == r
    # Pickling goes through ttd.<name>; the arrays come back equal.
    back = pickle.loads(pickle.dumps(r))
    assert type(back) is cls
    for x, y in zip(back, r):
        if isinstance(x, tuple):
            for u, v in zip(x, y):
                np.testing.assert_array_equal(u, v)
        else:
            np.testing.assert_array_equal(x, y)
    assert type(copy.copy(r)) is cls


def test_the_package_namespace():
    assert not hasattr(ttd, "enum")
    public = {n for n in dir(ttd) if not n.startswith("_")}
    # the submodules ttd.dask and ttd.cuda appear once another test has imported them
    assert public <= set(ttd.__all__) | {"dask", "cuda"}, sorted(public - set(ttd.__all__))


@pytest.mark.parametrize("args", [(None, None), (np.zeros(9), None), (None, np.zeros(9))])
def test_none_is_a_type_error(args):
    with pytest.raises(TypeError, match="(S|T) must be an array of coordinates, not None"):
        ttd.distance(*args)
    with pytest.raises(TypeError, match="vertices must be an array of coordinates, not None"):
        ttd.Mesh(None, [[0, 1, 2]])
    A = ttd.Mesh(*icosphere(0))
    # The extension's queries take poses; the package's make None the identity (test_poses.py).
    with pytest.raises(TypeError, match="poses must be an array of coordinates, not None"):
        ttd._ttd.mesh_distance(A, A, None)


# ---- the documentation's examples against the stub --------------------------------------------

# The examples define every name they use (python/tests/test_readme.py runs the README's); the
# preamble only makes numpy's typing names available.
PREAMBLE = """\
import numpy as np
import numpy.typing as npt
"""

# What the examples claim of the result types, said as code that mypy checks too.
CLAIMS = """\
import numpy as np
import ttd
S = np.zeros((4, 3, 3))
r = ttd.distance(S, S + 2, points=True)
fields: tuple[str, ...] = r._fields
as_dict: dict[str, object] = r._asdict()
r2: ttd.PairResult = r._replace(distance=r.distance * 2)
A = ttd.Mesh(np.zeros((3, 3)), [[0, 1, 2]])
m: ttd.MeshDistance = ttd.mesh_distance(A, A, np.eye(4))
m2: ttd.MeshDistance = m._replace(distance=m.distance)
col: ttd.MeshCollision = ttd.mesh_collide(A, A, np.eye(4))
con: ttd.MeshContacts = ttd.mesh_contacts(A, A, np.eye(4), 0.1)
clo: ttd.MeshClosest = ttd.mesh_closest(A, A, np.eye(4), 0.1)
part: ttd.ClosestPartners | None = clo.for_a
T: np.ndarray = ttd.pose(quat=[1, 0, 0, 0], t=[1, 2, 3], order="wxyz")
T2: np.ndarray = ttd.orthonormalize(T)
w: ttd.MeshDistance = ttd.mesh_distance(A, A, pose_a=T, pose_b=T2)
wc: ttd.MeshContacts = ttd.mesh_contacts(A, A, margin=0.1, pose_b=T)
hit = ttd.mesh_collide(A, A).hit
scene = ttd.Scene([A, A], np.stack([np.eye(4), np.eye(4)]), precision="float64")
body: int = scene.add(A, np.eye(4))
scene.set_poses(np.tile(np.eye(4), (3, 1, 1)))
scene.set_filter(body, 1, 0xFFFFFFFF)
scene.exclude(0, body)
sc: ttd.SceneCollision = scene.collide(0.0)
sd: ttd.SceneDistance = scene.distance(nearest=True)
near: ttd.SceneContacts | None = sd.nearest
scc: ttd.SceneContacts = scene.contacts(0.1)
sm: ttd.SceneManifold = scene.manifold(0.1, max_points=4)
n_bodies: int = len(scene)
A.set_vertices(np.ones((3, 3)), threads=1)
gen: int = A.generation + A.rebuilds
ss: ttd.SelfContacts = ttd.mesh_self_contacts(A, 0.1, shared_vertex=True)
sco: ttd.SelfCollision = ttd.mesh_self_collide(A)
self_hit: bool = sco.hit
"""

DOCS = ("README.md", "python/README.md", "docs/python.md")


def _examples(doc):
    """The ```python blocks of a document, joined (later blocks use earlier blocks' names)."""
    blocks = re.findall(r"^```python\n(.*?)^```", (REPO / doc).read_text(), flags=re.S | re.M)
    return "\n".join(blocks)


def test_docs_examples_type_check():
    try:
        import mypy.api  # noqa: F401
    except ImportError:
        pytest.skip("mypy is not installed: the docs' examples were not type-checked "
                    "(apt-get install python3-mypy; scripts/test-python.sh installs it when run as root)")
    build = os.environ.get("TTD_TEST_BUILD_DIR")
    work = (pathlib.Path(build).resolve() if build else REPO / "build") / "python-mypy"
    work.mkdir(parents=True, exist_ok=True)
    files = []
    for doc in DOCS:
        code = _examples(doc)
        if not code:
            continue
        path = work / ("example_" + re.sub(r"\W", "_", doc) + ".py")
        path.write_text(PREAMBLE + code)
        files.append(path)
    assert len(files) >= 2, "the README and python/README.md have Python examples"
    claims = work / "claims.py"
    claims.write_text(CLAIMS)
    files.append(claims)
    # Later blocks of a document reuse earlier blocks' names with other types (dask arrays for
    # numpy ones), as a reader's session would: --allow-redefinition.
    # Run in this interpreter (the venv with the installed package and its py.typed stub);
    # dask and distributed have no stubs on Debian: their imports are not checked.
    cmd = [sys.executable, "-m", "mypy", "--no-incremental", "--ignore-missing-imports", "--allow-redefinition", "--python-version",
           f"{sys.version_info.major}.{sys.version_info.minor}", "--cache-dir", str(work / "cache")]
    done = subprocess.run(cmd + [str(p) for p in files], capture_output=True, text=True, cwd=work)
    assert done.returncode == 0, f"mypy on the examples of {', '.join(DOCS)}:\n{done.stdout}{done.stderr}"
