/* ggx microsurface wave: the Kirchhoff (scalar wave optics) BRDF of a measured height field, binned as the tracer's
 * BRDF, beside the geometric-optics BRDF of the same slopes (libs/microsurface/kirchhoff.h,
 * docs/design/kirchhoff.md). SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_microsurface.h"
#include "kirchhoff.h"
#include "output.h"

static const double PI = 3.14159265358979323846;
enum { RINGS = 8, SECTORS = 16, BINS = RINGS * SECTORS };

static void microsurface_wave_help(void)
{
    printf("usage: ggx microsurface wave --heightfield FILE --view THETA,PHI [--wavelength UM | --rgb]\n"
           "                             [--spacing D] [--z-scale Z] [--keep-tilt] [--threads N]\n"
           "                             [--format md|csv|json] [--out FILE]\n\n"
           "The scalar Kirchhoff BRDF (F = 1, single scattering, no masking) of a measured height field lit\n"
           "from --view, by FFT of the windowed field exp(-i k (wi.z + wo.z) h) (docs/design/kirchhoff.md), at\n"
           "--wavelength UM micrometres (default 0.532) or with --rgb at 0.630, 0.532 and 0.465. Lengths: a\n"
           "file's own spacing is read as metres (x3p, gsf) and converted to micrometres; --spacing D is in\n"
           "micrometres and heights times --z-scale Z are then micrometres too. Missing points are filled from\n"
           "their neighbours; the least-squares plane is removed unless --keep-tilt. Prints the total and\n"
           "specular (coherent) shares, the grid used (heights interpolated finer where the phase between\n"
           "neighbours would pass pi; the share beyond that is 'aliased'), and per bin of 8 rings of equal\n"
           "sin^2(theta_o) x 16 sectors (the tracer's bins) the share of the power leaving into it, its mean\n"
           "BRDF (share x 128 / pi) and the geometric-optics share of the same slopes.\n");
}

static const command_spec MICROSURFACE_WAVE_SPEC = {
    "heightfield,view,wavelength,rgb,spacing,z-scale,keep-tilt,threads,format,out", microsurface_wave_help, 0};

int microsurface_wave(int argc, char **argv)
{
    options o;
    if (!command_options(&MICROSURFACE_WAVE_SPEC, argc, argv, 3, &o)) return 0;
    if (!o.heightfield) die("--heightfield FILE is required");
    if (!o.have_view) die("--view THETA,PHI is required");
    if (o.rgb && o.wavelength > 0) die("--wavelength and --rgb: give one");
    const char *fmt = o.format ? o.format : "md";
    int json = strcmp(fmt, "json") == 0, csv = strcmp(fmt, "csv") == 0;
    if (!json && !csv && strcmp(fmt, "md") != 0) die("--format: '%s' is not md, csv or json", fmt);
    if (!(o.view.z >= 1e-3)) die("--view: theta must be below 89.94 degrees (the light must reach the surface)");
    size_t nx, ny, missing;
    double dx;
    double *h = microsurface_heights_um(&o, &nx, &ny, &dx, &missing);
    char err[512];
    ms_kirchhoff_spec sp = {.h = h,
                            .nx = nx,
                            .ny = ny,
                            .dx = dx,
                            .wavelength = o.wavelength > 0 ? o.wavelength : 0.532,
                            .wi = {o.view.x, o.view.y, o.view.z},
                            .keep_tilt = o.keep_tilt,
                            .threads = o.threads > 0 ? o.threads : 2};
    double share[3 * BINS], geo[BINS], total[3], coherent[3];
    ms_kirchhoff k;
    int nc = o.rgb ? 3 : 1;
    const double *lams = o.rgb ? ms_kirchhoff_rgb_um : &sp.wavelength;
    if (ms_kirchhoff_setup(&sp, &k, err, sizeof err) != 0) {
        free(h);
        die("%s: %s", o.heightfield, err);
    }
    double gtot = ms_kirchhoff_geometric(&k, RINGS, SECTORS, geo);
    if (o.rgb) {
        ms_kirchhoff_free(&k);
        if (ms_kirchhoff_rgb(&sp, 1.0, RINGS, SECTORS, share, total, coherent, err, sizeof err) != 0) {
            free(h);
            die("%s: %s", o.heightfield, err);
        }
        sp.wavelength = ms_kirchhoff_rgb_um[2]; /* the grid's report: the shortest wavelength's, the finest */
        if (ms_kirchhoff_setup(&sp, &k, err, sizeof err) != 0) {
            free(h);
            die("%s: %s", o.heightfield, err);
        }
    } else {
        total[0] = ms_kirchhoff_bin(&k, RINGS, SECTORS, share);
        coherent[0] = k.coherent;
    }
    free(h);
    if (k.aliased > 0.01)
        fprintf(stderr,
                "ggx: warning: %.1f %% of the windowed points step by more than pi of phase even on the grid "
                "interpolated %d times finer: their light is misplaced\n",
                100.0 * k.aliased, k.upsample);
    double theta = acos(o.view.z) * 180.0 / PI, phi = atan2(o.view.y, o.view.x) * 180.0 / PI;
    out_file f;
    out_open(&f, o.out ? o.out : "-");
    FILE *F = f.f;
    static const char *cname[3] = {"r", "g", "b"};
    if (json) {
        fprintf(F,
                "{\n  \"heightfield\": \"%s\",\n  \"points\": [%zu, %zu],\n  \"spacing_um\": %.9g,\n  \"view\": [%.9g, "
                "%.9g],\n  \"sigma_h_um\": %.9g,\n  \"missing_share\": %.9g,\n  \"upsample\": %d,\n  \"fft\": [%zu, "
                "%zu],\n  \"aliased_share\": %.9g,\n  \"geometric_total\": %.9g,\n  \"wavelengths_um\": [",
                o.heightfield, (k.nx - 1) / (size_t)k.upsample + 1, (k.ny - 1) / (size_t)k.upsample + 1, dx, theta, phi,
                k.sigma_h, k.missing, k.upsample, k.fft_nx, k.fft_ny, k.aliased, gtot);
        for (int c = 0; c < nc; c++) fprintf(F, "%s%.9g", c ? ", " : "", lams[c]);
        fprintf(F, "],\n  \"total\": [");
        for (int c = 0; c < nc; c++) fprintf(F, "%s%.9g", c ? ", " : "", total[c]);
        fprintf(F, "],\n  \"specular\": [");
        for (int c = 0; c < nc; c++) fprintf(F, "%s%.9g", c ? ", " : "", coherent[c]);
        fprintf(F, "],\n  \"rings\": %d,\n  \"sectors\": %d,\n  \"bins\": [\n", RINGS, SECTORS);
    } else if (csv) {
        fprintf(F, "ring,sector,sin2_lo,sin2_hi,phi_lo,phi_hi");
        for (int c = 0; c < nc; c++)
            fprintf(F, ",share%s%s,brdf%s%s", nc > 1 ? "_" : "", nc > 1 ? cname[c] : "", nc > 1 ? "_" : "",
                    nc > 1 ? cname[c] : "");
        fprintf(F, ",geometric_share\n");
    } else {
        fprintf(F, "# Kirchhoff BRDF of %s\n\n", o.heightfield);
        fprintf(F,
                "%zu x %zu heights, spacing %.6g um, sigma_h %.6g um (levelled%s), %.2f %% missing (filled); view "
                "theta %.4g, phi %.4g degrees\n\n",
                (k.nx - 1) / (size_t)k.upsample + 1, (k.ny - 1) / (size_t)k.upsample + 1, dx, k.sigma_h,
                o.keep_tilt ? ": no, --keep-tilt" : "", 100.0 * k.missing, theta, phi);
        fprintf(F, "grid: interpolated %d times finer (FFT %zu x %zu), aliased share %.4g\n\n", k.upsample, k.fft_nx,
                k.fft_ny, k.aliased);
        fprintf(F, "| wavelength (um) | total share | specular (coherent) share |\n|---|---|---|\n");
        for (int c = 0; c < nc; c++) fprintf(F, "| %.4g | %.6f | %.6g |\n", lams[c], total[c], coherent[c]);
        fprintf(F, "\ngeometric optics of the same slopes: total share %.6f\n\n", gtot);
        fprintf(F, "| ring | sector | sin^2 theta_o | phi_o (deg) |");
        for (int c = 0; c < nc; c++)
            fprintf(F, " share%s%s | BRDF%s%s |", nc > 1 ? " " : "", nc > 1 ? cname[c] : "", nc > 1 ? " " : "",
                    nc > 1 ? cname[c] : "");
        fprintf(F, " geometric share |\n|---|---|---|---|");
        for (int c = 0; c < nc; c++) fprintf(F, "---|---|");
        fprintf(F, "---|\n");
    }
    for (int b = 0; b < BINS; b++) {
        int r = b / SECTORS, sc = b % SECTORS;
        double s0 = (double)r / RINGS, s1 = (double)(r + 1) / RINGS, p0 = 360.0 * sc / SECTORS,
               p1 = 360.0 * (sc + 1) / SECTORS;
        if (json) fprintf(F, "    {\"ring\": %d, \"sector\": %d, \"share\": [", r, sc);
        else if (csv) fprintf(F, "%d,%d,%.6g,%.6g,%.6g,%.6g", r, sc, s0, s1, p0, p1);
        else fprintf(F, "| %d | %d | %.4g-%.4g | %.4g-%.4g |", r, sc, s0, s1, p0, p1);
        for (int c = 0; c < nc; c++) {
            double v = share[nc * b + c], fr = v * BINS / PI;
            if (json) fprintf(F, "%s%.9g", c ? ", " : "", v);
            else if (csv) fprintf(F, ",%.9g,%.9g", v, fr);
            else fprintf(F, " %.6g | %.6g |", v, fr);
        }
        if (json) fprintf(F, "], \"geometric_share\": %.9g}%s\n", geo[b], b + 1 < BINS ? "," : "");
        else if (csv) fprintf(F, ",%.9g\n", geo[b]);
        else fprintf(F, " %.6g |\n", geo[b]);
    }
    if (json) fprintf(F, "  ]\n}\n");
    out_close(&f);
    ms_kirchhoff_free(&k);
    return 0;
}
