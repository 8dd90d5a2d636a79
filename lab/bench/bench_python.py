"""Python package overhead (make bench-python): ns per sample on 1e6-element arrays for the package's functions in
float64 (float64 inputs, the native loops over the double API) and float32 (float32 inputs, the float batch API
through the package's float32 path), with new result arrays and with out=, against the C batch API called in the same
process through ctypes on ready struct-of-arrays float inputs and outputs (the same work, no Python layer); then a
renderer's step (sample + eval + pdf) as separate calls, as one sample_eval call, and as the C batch API's calls; and
microseconds per call on one element. Median of 7 runs; one thread (set_batch_threads) unless --threads N. Never
part of the test suite."""
import ctypes
import statistics
import sys
import time

import numpy as np

import ggx
from ggx._native import _lib

N = 1_000_000


def median_time(f, reps):
    runs = []
    for _ in range(7):
        t = time.perf_counter()
        for _ in range(reps):
            f()
        runs.append((time.perf_counter() - t) / reps)
    return statistics.median(runs)


def ns(f, reps=3):
    return median_time(f, reps) / N * 1e9


def main():
    threads = int(sys.argv[sys.argv.index("--threads") + 1]) if "--threads" in sys.argv else 1
    ggx.set_batch_threads(threads)
    r = np.random.default_rng(1)
    s = ggx.Shape.ellipsoid(0.3, 0.6, 0.4, -0.3, 0.5)
    fr = ggx.Fresnel.conductor(0.2, 3.9)
    d = r.normal(size=(N, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    v = d[::-1].copy()
    u1, u2 = r.random(N), r.random(N)
    d32, v32, u132, u232 = (x.astype(np.float32) for x in (d, v, u1, u2))
    o32, o64 = {k: np.empty(k, np.float32) for k in ((N,), (N, 3))}, {k: np.empty(k) for k in ((N,), (N, 3))}

    # the C batch API on struct-of-arrays floats, through ctypes (pointers ready, outputs allocated once)
    P = ctypes.c_void_p
    soa = {k: [np.ascontiguousarray(a[:, c]) for c in range(3)] for k, a in (("d", d32), ("v", v32))}
    cout = [np.empty(N, np.float32) for _ in range(6)]
    p = {k: [P(a.ctypes.data) for a in cols] for k, cols in soa.items()}
    po = [P(a.ctypes.data) for a in cout]
    pu1, pu2 = P(u132.ctypes.data), P(u232.ctypes.data)
    sb, fb = ctypes.cast(s._buf, P), ctypes.cast(fr._buf, P)
    brdf_id = next(e.id for e in ggx.samplers() if e.name == "brdf")
    caps_id = next(e.id for e in ggx.samplers() if e.name == "caps")
    c_ndf = lambda: _lib.ggx_batch_ndf(po[0], ctypes.c_size_t(N), sb, *p["d"])
    c_g1 = lambda: _lib.ggx_batch_g1(po[0], ctypes.c_size_t(N), sb, *p["v"], *p["d"])
    c_pdf = lambda: _lib.ggx_batch_pdf_vndf(po[0], ctypes.c_size_t(N), sb, *p["v"], *p["d"])
    c_brdf = lambda: _lib.ggx_batch_brdf(po[0], ctypes.c_size_t(N), sb, fb, *p["v"], *p["d"])
    c_vndf = lambda: _lib.ggx_batch_sample_normals(caps_id, *po[:3], ctypes.c_size_t(N), sb, *p["v"], pu1, pu2)
    c_sbrdf = lambda: _lib.ggx_batch_sample_directions(brdf_id, *po[:5], ctypes.c_size_t(N), sb, fb, *p["v"], pu1, pu2)

    def c_step():  # sample, then the BRDF of the sampled directions (the sample gives its pdf)
        c_sbrdf()
        _lib.ggx_batch_brdf(po[5], ctypes.c_size_t(N), sb, fb, *p["v"], *po[:3])

    t32, t64 = np.float32, np.float64
    w3, w1 = (N, 3), (N,)
    cases = [
        ("ndf", lambda: ggx.ndf(s, d), lambda: ggx.ndf(s, d32, dtype=t32),
         lambda: ggx.ndf(s, d32, dtype=t32, out=o32[w1]), c_ndf),
        ("g1", lambda: ggx.g1(s, v, d), lambda: ggx.g1(s, v32, d32, dtype=t32),
         lambda: ggx.g1(s, v32, d32, dtype=t32, out=o32[w1]), c_g1),
        ("pdf_vndf", lambda: ggx.pdf_vndf(s, v, d), lambda: ggx.pdf_vndf(s, v32, d32, dtype=t32),
         lambda: ggx.pdf_vndf(s, v32, d32, dtype=t32, out=o32[w1]), c_pdf),
        ("brdf", lambda: ggx.brdf(s, v, d, fr), lambda: ggx.brdf(s, v32, d32, fr, dtype=t32),
         lambda: ggx.brdf(s, v32, d32, fr, dtype=t32, out=o32[w1]), c_brdf),
        ("pdf_brdf", lambda: ggx.pdf_brdf(s, v, d), lambda: ggx.pdf_brdf(s, v32, d32, dtype=t32),
         lambda: ggx.pdf_brdf(s, v32, d32, dtype=t32, out=o32[w1]), None),
        ("sample_vndf", lambda: ggx.sample_vndf(s, v, u1, u2), lambda: ggx.sample_vndf(s, v32, u132, u232, dtype=t32),
         lambda: ggx.sample_vndf(s, v32, u132, u232, dtype=t32, out=o32[w3]), c_vndf),
        ("sample_ndf", lambda: ggx.sample_ndf(s, u1, u2), lambda: ggx.sample_ndf(s, u132, u232, dtype=t32),
         lambda: ggx.sample_ndf(s, u132, u232, dtype=t32, out=o32[w3]), None),
        ("sample_brdf", lambda: ggx.sample_brdf(s, v, u1, u2, fr), lambda: ggx.sample_brdf(s, v32, u132, u232, fr,
                                                                                          dtype=t32),
         lambda: ggx.sample_brdf(s, v32, u132, u232, fr, dtype=t32, out=(o32[w3], cout[0], cout[1])), c_sbrdf),
    ]
    out4 = (np.empty(w3, np.float32), np.empty(N, np.float32), np.empty(N, np.float32), np.empty(N, np.float32))

    def separate32():
        b = ggx.sample_brdf(s, v32, u132, u232, fr, dtype=t32)
        ggx.brdf(s, v32, b.w, fr, dtype=t32)
        ggx.pdf_brdf(s, v32, b.w, dtype=t32)

    print(f"libggx Python package, {sys.version.split()[0]}, numpy {np.__version__}, batch ISA {ggx.batch_isa()}, "
          f"{threads} thread(s), N = {N}: ns per sample")
    print(f"{'function':<14}{'f64':>9}{'f32':>9}{'f32 out=':>10}{'C batch':>9}{'f32/f64':>9}{'out=/C':>8}"
          f"{'f64 us/call':>12}{'f32 us/call':>12}")
    for name, f64, f32, f32o, cf in cases:
        a, b, c = ns(f64), ns(f32), ns(f32o)
        cb = ns(cf) if cf else float("nan")
        print(f"{name:<14}{a:9.2f}{b:9.2f}{c:9.2f}{cb:10.2f}{b / a:9.2f}{c / cb:8.2f}"
              f"{median_time(lambda: f64_one(name, s, fr, d, u1, u2, t64), 2000) * 1e6:12.2f}"
              f"{median_time(lambda: f64_one(name, s, fr, d32, u132, u232, t32), 2000) * 1e6:12.2f}")
    print("a renderer's step, sample + eval + pdf, float32:")
    sep, fused, fused64 = ns(separate32), ns(lambda: ggx.sample_eval(s, v32, u132, u232, fr, dtype=t32, out=out4)), \
        ns(lambda: ggx.sample_eval(s, v, u1, u2, fr))
    cstep = ns(c_step)
    print(f"  separate calls (sample_brdf, brdf, pdf_brdf) {sep:8.2f}   ({sep / cstep:.2f} x C)")
    print(f"  sample_eval, out=                            {fused:8.2f}   ({fused / cstep:.2f} x C)")
    print(f"  C batch (sample_directions + brdf)           {cstep:8.2f}")
    print(f"  sample_eval in float64                       {fused64:8.2f}")


def f64_one(name, s, fr, d, u1, u2, dt):
    """One element of the case's function (per-call overhead)."""
    x, a, b = d[:1], u1[:1], u2[:1]
    if name in ("ndf",):
        return ggx.ndf(s, x, dtype=dt)
    if name in ("g1", "pdf_vndf"):
        return getattr(ggx, name)(s, x, x, dtype=dt)
    if name == "brdf":
        return ggx.brdf(s, x, x, fr, dtype=dt)
    if name == "pdf_brdf":
        return ggx.pdf_brdf(s, x, x, dtype=dt)
    if name == "sample_ndf":
        return ggx.sample_ndf(s, a, b, dtype=dt)
    if name == "sample_vndf":
        return ggx.sample_vndf(s, x, a, b, dtype=dt)
    return ggx.sample_brdf(s, x, a, b, fr, dtype=dt)


if __name__ == "__main__":
    main()
