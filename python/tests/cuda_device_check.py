# SPDX-License-Identifier: MIT
"""ttd.cuda on a machine with a GPU: CuPy arrays, PyTorch tensors and a DLPack-only object
through ttd.cuda.distance, against the CPU's bits (ttd_batch_d/f of libttd.so through ctypes,
tests' c_reference), and the call's throughput on device-resident pairs. Run by
scripts/test-gpu-device.sh:

    python3 python/tests/cuda_device_check.py BUILD_DIR

It loads python/ttd/cuda.py by its path, so it runs under any Python 3 with numpy (such as a GPU
machine's own interpreter, for which ttd's extension is not built). Exits 1 on any differing
bit; prints what it skips (no CuPy, no PyTorch)."""
import importlib.util
import pathlib
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import c_reference  # noqa: E402


def load_cuda_module(build):
    import os
    found = sorted((build / "src" / "gpu").glob("libttd_gpu.so*"))
    if found:
        os.environ.setdefault("TTD_GPU_LIBRARY", str(found[0]))
    spec = importlib.util.spec_from_file_location("ttd_cuda", HERE.parent / "ttd" / "cuda.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def pairs(n, dtype, seed=3):
    rng = np.random.default_rng(seed)
    S = rng.standard_normal((n, 3, 3))
    T = rng.standard_normal((n, 3, 3)) + rng.uniform(-1, 1, (n, 1, 3))
    S[1::97, 2] = S[1::97, 1]             # segments
    T[2::89] = T[2::89, :1]               # points
    T[3::83] = S[3::83] + 1e-12           # near-touching copies
    S[5] = np.nan                         # a NaN pair
    return S.astype(dtype), T.astype(dtype)


class DLPackOnly:
    """Exposes only the DLPack protocol of a tensor."""

    def __init__(self, a):
        self._a = a

    def __dlpack__(self, *args, **kwargs):
        return self._a.__dlpack__(*args, **kwargs)

    def __dlpack_device__(self):
        return self._a.__dlpack_device__()


def bits_equal(a, b):
    a = np.ascontiguousarray(a)
    b = np.ascontiguousarray(b)
    u = np.uint64 if a.dtype == np.float64 else np.uint32
    return int(np.count_nonzero(a.view(u) != b.view(u)))


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "build").resolve()
    cuda = load_cuda_module(build)
    info = cuda.info()
    print(f"ttd.cuda.info(): {info}")
    if not info["usable"]:
        print("cuda_device_check: no usable GPU")
        return 1
    lib = c_reference.Library(sorted((build / "src").glob("libttd.so*"))[0])
    n = 1 << 20
    failures = 0
    for dtype in (np.float64, np.float32):
        S, T = pairs(n, dtype)
        _, rec = lib.batch(S, T, isa=1)     # the scalar row
        want = rec["distance"]
        try:
            import cupy as cp
            s, t = cp.asarray(S), cp.asarray(T.reshape(n, 9))
            d = cuda.distance(s, t)
            diff = bits_equal(cp.asnumpy(d), want)
            print(f"cupy  {np.dtype(dtype).name}: {n} pairs, differing bits {diff}")
            failures += diff
            out = cp.empty(n, dtype)
            cuda.distance(DLPackOnly(s), t, out=out)
            diff = bits_equal(cp.asnumpy(out), want)
            print(f"dlpack-only object {np.dtype(dtype).name}: differing bits {diff}")
            failures += diff
            cp.cuda.get_current_stream().synchronize()
            best = 1e30
            for _ in range(5):
                t0 = time.perf_counter()
                cuda.distance(s, t, out=out)
                cp.cuda.get_current_stream().synchronize()
                best = min(best, time.perf_counter() - t0)
            print(f"cupy  {np.dtype(dtype).name}: ttd.cuda.distance {n / best:.3g} pairs/s (device-resident, "
                  f"wall clock with the Python call)")
        except ImportError:
            print("cupy: not installed, skipped")
        try:
            import torch
            if torch.cuda.is_available():
                s = torch.from_numpy(S).cuda()
                t = torch.from_numpy(T).cuda()
                d = cuda.distance(s, t)
                assert d.dtype == s.dtype and d.device == s.device
                diff = bits_equal(d.cpu().numpy(), want)
                print(f"torch {np.dtype(dtype).name}: {n} pairs, differing bits {diff}")
                failures += diff
            else:
                print("torch: no CUDA device, skipped")
        except ImportError:
            print("torch: not installed, skipped")
    print(f"cuda_device_check: {'FAILED' if failures else 'passed'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
