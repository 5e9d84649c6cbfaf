# SPDX-License-Identifier: MIT
"""Builds the ttd Python package: the C library of this repository first, then the extension.

The extension (ttd._ttd, from python/src/) uses only the public header include/ttd/ttd.h and
links the library's static archive (libttd.a, position-independent) into itself, so the
installed package needs no libttd.so at run time. The archive comes from CMake, run on the
repository the usual way, because the library's build compiles each instruction set's kernels
with their own flags (src/CMakeLists.txt) and this file should not learn how.

Where the library is built:
  - TTD_CMAKE_BUILD_DIR=DIR: an existing CMake build folder of this repository (configured
    there if it is not yet); only its ttd_static target is brought up to date. scripts/test.sh
    passes its own build folder, so the library is built once.
  - otherwise: a private Release build of the library alone in setuptools' temporary folder
    (python/build/temp.*/libttd), configured on the first build and reused after.
TTD_SOURCE_DIR may name the repository when this folder is not its python/ folder, and
TTD_PYTHON_BUILD_BASE moves setuptools' build folder (default python/build) elsewhere.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = Path(__file__).resolve().parent


def repository() -> Path:
    root = Path(os.environ.get("TTD_SOURCE_DIR", HERE.parent)).resolve()
    if not (root / "include" / "ttd" / "ttd.h").is_file() or not (root / "CMakeLists.txt").is_file():
        sys.exit(
            f"ttd: {root} is not the ttd repository (no include/ttd/ttd.h and CMakeLists.txt): "
            "the Python package is built from a checkout of the repository (pip install "
            "--no-build-isolation ./python from its root), or with TTD_SOURCE_DIR naming one"
        )
    return root


def version(root: Path) -> str:
    header = (root / "include" / "ttd" / "ttd.h").read_text()
    parts = [re.search(rf"#define TTD_VERSION_{p} (\d+)", header) for p in ("MAJOR", "MINOR", "PATCH")]
    if not all(parts):
        sys.exit("ttd: include/ttd/ttd.h has no TTD_VERSION_MAJOR/MINOR/PATCH")
    return ".".join(m.group(1) for m in parts)


class BuildWithLibrary(build_ext):
    """build_ext that first builds libttd.a with CMake and links it into every extension."""

    def run(self):
        archive = self.build_library()
        for ext in self.extensions:
            ext.extra_objects = [str(archive)]
            ext.depends = list(ext.depends) + [str(archive)]
        super().run()

    def build_library(self) -> Path:
        root = repository()
        cmake = shutil.which("cmake")
        if cmake is None:
            sys.exit("ttd: cmake is needed to build the C library (apt-get install cmake)")
        given = os.environ.get("TTD_CMAKE_BUILD_DIR")
        build = Path(given).resolve() if given else Path(self.build_temp).resolve() / "libttd"
        if not (build / "CMakeCache.txt").is_file():
            configure = [cmake, "-S", str(root), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"]
            if not given:
                configure += ["-DTTD_BUILD_TESTS=OFF", "-DTTD_BUILD_CLI=OFF"]
            self.announce("ttd: " + " ".join(configure), level=2)
            subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 2)
        subprocess.run([cmake, "--build", str(build), "--target", "ttd_static", "-j", jobs], check=True)
        archive = build / "src" / "libttd.a"
        if not archive.is_file():
            sys.exit(f"ttd: CMake did not produce {archive}")
        return archive


ROOT = repository()
# The project's warnings (TTD_WARNINGS in CMakeLists.txt) but -Wpedantic and -Wcast-qual, which
# numpy's own headers trip (function pointers from its API table, const casts in its inlines).
COMPILE_ARGS = ["-std=c11", "-Wall", "-Wextra", "-Wshadow", "-Wmissing-prototypes", "-Wstrict-prototypes",
                "-Wpointer-arith", "-Wvla", "-Wdouble-promotion"]
# Keep the archive's symbols out of the extension's dynamic symbol table (no clash with another
# copy of ttd loaded into the same process).
LINK_ARGS = ["-pthread"] + (["-Wl,--exclude-libs,ALL"] if sys.platform.startswith("linux") else [])


def extension(name: str, sources: list, numpy_api: bool) -> Extension:
    include_dirs = [str(ROOT / "include")]
    if numpy_api:
        import numpy

        include_dirs.append(numpy.get_include())
    return Extension(
        name,
        sources=[f"src/{s}" for s in sources],
        include_dirs=include_dirs,
        depends=["src/ttd_py.h", str(ROOT / "include" / "ttd" / "ttd.h")],
        libraries=["m"],
        extra_compile_args=COMPILE_ARGS,
        extra_link_args=LINK_ARGS,
    )


EXTENSIONS = [
    extension("ttd._ttd", ["ttd_module.c", "ttd_py_common.c", "ttd_pairs.c", "ttd_mesh.c", "ttd_scene.c", "ttd_points.c",
                          "ttd_ccd.c"],
              numpy_api=True),
]
# The benchmark's C-side timer (bench/python_overhead.py, and the tests that check it): not part
# of the API, so a wheel or an install leaves it out unless TTD_PYTHON_CTIMING=1 asks for it
# (scripts/test-python.sh does, for its own venv).
if os.environ.get("TTD_PYTHON_CTIMING") == "1":
    EXTENSIONS.append(extension("ttd._ctiming", ["ttd_ctiming.c"], numpy_api=False))

setup(
    version=version(ROOT),
    packages=["ttd"],
    package_data={"ttd": ["py.typed", "*.pyi"]},
    zip_safe=False,
    options={"build": {"build_base": os.environ.get("TTD_PYTHON_BUILD_BASE", "build")}},
    ext_modules=EXTENSIONS,
    cmdclass={"build_ext": BuildWithLibrary},
)
