"""Python package overhead (make bench-python): ns per element on 1e6-element arrays and microseconds per call on
one element, for the package's functions in float64 (the native loops over the double API) and float32 (the batch
API), against the bare native loop called with ready pointers (the C API's cost plus an indirect call). Median of 7
runs. Never part of the test suite."""
import statistics
import sys
import time

import numpy as np

import ggx
from ggx import _Args, _fn, _loop_s

N = 1_000_000


def median_time(f, reps):
    runs = []
    for _ in range(7):
        t = time.perf_counter()
        for _ in range(reps):
            f()
        runs.append((time.perf_counter() - t) / reps)
    return statistics.median(runs)


def main():
    r = np.random.default_rng(1)
    s = ggx.Shape.ellipsoid(0.3, 0.6, 0.4, -0.3, 0.5)
    d = r.normal(size=(N, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    v = d[::-1].copy()
    u1, u2 = r.random(N), r.random(N)
    one_d = d[:1]
    cases = [
        ("ndf", lambda x, dt: ggx.ndf(s, x, dtype=dt), "ggx_ndf", 1),
        ("g1", lambda x, dt: ggx.g1(s, v[: len(x)], x, dtype=dt), "ggx_g1", 2),
        ("pdf_vndf", lambda x, dt: ggx.pdf_vndf(s, v[: len(x)], x, dtype=dt), "ggx_pdf_vndf", 2),
        ("brdf", lambda x, dt: ggx.brdf(s, v[: len(x)], x, dtype=dt), None, 0),
        ("sample_vndf", lambda x, dt: ggx.sample_vndf(s, x, u1[: len(x)], u2[: len(x)], dtype=dt), None, 0),
        ("sample_brdf", lambda x, dt: ggx.sample_brdf(s, x, u1[: len(x)], u2[: len(x)], dtype=dt), None, 0),
    ]
    print(f"libggx Python package, {sys.version.split()[0]}, numpy {np.__version__}, batch ISA {ggx.batch_isa()}")
    print(f"{'function':<14}{'f64 ns/elem':>12}{'f32 ns/elem':>12}{'bare loop':>11}{'f64/bare':>9}"
          f"{'f64 us/call':>12}{'f32 us/call':>12}")
    for name, f, cname, k in cases:
        t64 = median_time(lambda: f(d, np.float64), 3) / N * 1e9
        t32 = median_time(lambda: f(d, np.float32), 3) / N * 1e9
        c64 = median_time(lambda: f(one_d, np.float64), 20000) * 1e6
        c32 = median_time(lambda: f(one_d, np.float32), 20000) * 1e6
        bare = ""
        ratio = ""
        if cname:
            a = _Args(*([(v, "v", 3)] if k == 2 else []), (d, "m", 3))
            out = np.empty(N)
            fp, loop, p = _fn(cname), _loop_s["vv" if k == 2 else "v"], out.ctypes.data
            tb = median_time(lambda: loop(fp, s._buf, N, a.ins, p), 3) / N * 1e9
            bare, ratio = f"{tb:11.2f}", f"{t64 / tb:9.2f}"
        print(f"{name:<14}{t64:12.2f}{t32:12.2f}{bare:>11}{ratio:>9}{c64:12.2f}{c32:12.2f}")


if __name__ == "__main__":
    main()
