#!/usr/bin/env python3
"""How a measured scan's traced G1 and BRDF depend on box-averaging (docs/design/microsurface.md, "Measured
patches"): ggx microsurface measure --downsample K for K = 1, 2, 4, 8 at views 60, 75 and 85 degrees, printing the
facets' G1, the traced G1 (visible over front-facing area), Smith's G1 for Beckmann slopes of the facets'
covariance, the facets' slope variance, and the relative L2 over the 8 x 16 outgoing bins of the BRDF of all
bounces against K = 1's. The noise floor of that L2: K = 1 traced with a second, different grid of rays (RAYS + 1
rounds up to another grid side). Usage: patch_resolution.py GGX SCAN.x3p [RAYS [THREADS]]
SPDX-License-Identifier: MIT"""
import json
import math
import subprocess
import sys


def measure(ggx, scan, k, theta, rays, threads):
    out = subprocess.run([ggx, "microsurface", "measure", "--heightfield", scan, "--downsample", str(k), "--view",
                          "%g,0" % theta, "-n", str(rays), "--threads", str(threads), "--format", "json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def l2(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / sum(y * y for y in b))


def main():
    ggx, scan = sys.argv[1], sys.argv[2]
    rays = int(sys.argv[3]) if len(sys.argv) > 3 else 1000000
    threads = int(sys.argv[4]) if len(sys.argv) > 4 else 2
    print("| view | K | size | slope var (xx + yy) | G1 facets | G1 traced | Smith (Beckmann) | BRDF rays left |"
          " BRDF L2 vs K = 1 |")
    print("|---|---|---|---|---|---|---|---|---|")
    for theta in (60, 75, 85):
        ref = None
        for k in (1, 2, 4, 8):
            d = measure(ggx, scan, k, theta, rays, threads)
            p, g, b = d["patch"], d["g1"], d["brdf"]
            traced = sum(x["g1"] * x["area"] for x in d["bins"]) / sum(x["area"] for x in d["bins"])
            if b is None:
                dist = "(no BRDF window)"
            elif ref is None:
                ref = b["all"]
                again = measure(ggx, scan, 1, theta, rays + 2 * int(math.sqrt(rays)) + 1, threads)["brdf"]["all"]
                dist = "%.4f (noise: another grid)" % l2(again, ref)
            else:
                dist = "%.4f" % l2(b["all"], ref)
            print("| %g | %d | %d x %d | %.5f | %.5f | %.5f | %.5f | %s | %s |" %
                  (theta, k, p["nx"], p["ny"], d["slope_cov"][0] + d["slope_cov"][2], g["facets"], traced,
                   g["smith_beckmann"], "%.2g" % (p["brdf_left"] / b["rays"]) if b else "-", dist))


if __name__ == "__main__":
    main()
