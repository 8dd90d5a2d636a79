/* The CUDA build on a GPU: every kernel of src/cuda/loops.cu (every public float kernel of ggx_inline.h, the
 * registry's samplers and inverse maps included) runs its __global__ loop over a fixed set of inputs -- shapes from
 * isotropic to skewed by 0.5 rad and c I at 1e-30 and 1e30, every Fresnel kind, eta and 1 / eta, both transport
 * modes, views at n, near grazing and below the horizon, u at 0, 2^-24, 1 - 2^-24, outside [0, 1] and NaN -- and
 * is compared with the same per-element code run on the host.
 * The device contracts floating-point multiply-adds where the host does not (nvcc's default; division and square
 * root are correctly rounded on both), so results differ by rounding: evaluations within 1e-5 relative, directions
 * within 1e-4 per component (ggx_batch.h's bound for float against double), sample pdfs within 1e-4 relative and
 * weights within 2e-4 absolute. An inverse map's (u1, u2) agree when they do as points of the torus or when the
 * samples they give do (the double forward map, ggx_cuda_kernel.reference): u is not unique at the seams and poles
 * of a map, and the sample moves fast with u at its rim; within 1e-3, as float inverse maps resolve u near a pole
 * or the rim only to about the square root of the float epsilon (their u comes from a difference of nearly equal
 * terms, or the sample from a square root of one).
 * Where the float kernel is ill-conditioned -- a normal on the rim of the lune, a dot product that cancels, a value
 * that is 0 up to rounding -- two roundings cannot agree to these bounds, whichever is closer to the exact result.
 * Such an input is recognised by the float kernel itself: moving the inputs by a few ulps (2^-24 at least for u)
 * moves the host's result by more than 1/8 of the tolerance; so is a u clamped to 1 (outside the samplers' [0, 1),
 * the rim of the square, where the float result is decided by rounding). Those elements are counted
 * ("ill-conditioned"), the first ones printed with the double result beside, and checked for the contract only;
 * every other element must agree with the host.
 * The contract is checked on every device output: evaluations finite (and >= 0 but for ggx_lambda), sampled
 * normals unit or zero, above the horizon and facing the view, direction samples unit on the side their event
 * says or invalid and zero, disk points in the disk, (u1, u2) in [0, 1].
 * Prints one line per kernel (name, elements, largest difference from the host) and the inputs of the first
 * failures. Exits 77 (ctest SKIP_RETURN_CODE) when there is no CUDA device or driver, or 1 then if the environment
 * sets GGX_REQUIRE_GPU (for a run on a GPU machine, where a skip would hide a missing driver).
 * SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ggx_cuda.h"
#include "verify.h"

#define SKIP 77

#define TOL_EVAL 1e-5   /* evaluations: relative */
#define TOL_DIR 1e-4    /* vectors, points: absolute per component */
#define TOL_INV 1e-3    /* inverse maps: (u1, u2) or the sample they give, absolute per component */
#define TOL_PDF 1e-4    /* sample pdf: relative */
#define TOL_WEIGHT 2e-4 /* sample weight: absolute */
#define TOL_UNIT 1e-5   /* | ||m|| - 1 | of a sampled normal or direction */
#define MAX_REPORTS 8   /* failing elements printed per kernel */
#define MAX_NOTES 2     /* ill-conditioned elements printed per kernel */
#define ILL 0.125       /* an input is ill-conditioned where a few ulps move the result this many tolerances */

#define U_LO 0x1p-24f          /* the smallest u > 0 of a float generator with 24-bit resolution */
#define U_HI (1.0f - 0x1p-24f) /* the largest float below 1 */

/* ---- inputs ---- */

typedef struct shape_case {
    const char *what;
    double ax, ay, tx, ty, tz; /* ggx_shape_ellipsoid, or c I (ggx_shape_matrix) when c > 0 */
    double c;
} shape_case;

static const shape_case shapes[] = {
    {"iso 0.3", 0.3, 0.3, 0, 0, 0, 0},
    {"aniso (0.05, 0.5) rotated 30 deg", 0.05, 0.5, 0, 0, 0.5235987755982988, 0},
    {"(0.15, 0.5) skewed (10, -5) deg, rotated 30 deg", 0.15, 0.5, 0.17453292519943295, -0.08726646259971647,
     0.5235987755982988, 0},
    {"(0.3, 1) skewed (0.5, -0.5) rad, rotated 1 rad", 0.3, 1.0, 0.5, -0.5, 1.0, 0},
    {"(0.05, 0.08) skewed (0.5, 0.5) rad", 0.05, 0.08, 0.5, 0.5, 0, 0},
    {"iso 2", 2.0, 2.0, 0, 0, 0, 0},
    {"1e-30 I", 0, 0, 0, 0, 0, 1e-30},
    {"1e30 I", 0, 0, 0, 0, 0, 1e30},
};
#define NSHAPES (sizeof shapes / sizeof shapes[0])

/* Fresnel kind, eta and transport mode of each configuration; kernels that use none of them run in the first. */
typedef struct config {
    ggx_fresnel_kind kind;
    double fa, fb; /* eta (dielectric), eta + i k (conductor), f0 (Schlick) */
    float eta;
    ggx_transport mode;
} config;
static const config configs[] = {
    {GGX_FRESNEL_DIELECTRIC, 1.5, 0, 1.5f, GGX_RADIANCE},
    {GGX_FRESNEL_CONDUCTOR, 0.2, 3.9, 1 / 1.5f, GGX_IMPORTANCE},
    {GGX_FRESNEL_SCHLICK, 0.04, 0, 1.5f, GGX_IMPORTANCE},
    {GGX_FRESNEL_ONE, 0, 0, 1 / 1.5f, GGX_RADIANCE},
};
#define NCONFIGS (sizeof configs / sizeof configs[0])

/* Growable float columns. */
typedef struct columns {
    int ncols;
    size_t n, cap;
    float *c[GGX_CUDA_MAX_IN];
} columns;

static void *xrealloc(void *p, size_t bytes)
{
    void *q = realloc(p, bytes ? bytes : 1);
    if (!q) {
        fprintf(stderr, "test_cuda: out of memory\n");
        exit(1);
    }
    return q;
}

static void push(columns *t, const float *row)
{
    if (t->n == t->cap) {
        t->cap = t->cap ? 2 * t->cap : 1024;
        for (int k = 0; k < t->ncols; k++) t->c[k] = xrealloc(t->c[k], t->cap * sizeof(float));
    }
    for (int k = 0; k < t->ncols; k++) t->c[k][t->n] = row[k];
    t->n++;
}

static void columns_free(columns *t)
{
    for (int k = 0; k < t->ncols; k++) free(t->c[k]);
    memset(t, 0, sizeof *t);
}

/* Directions: n, polar angles from 20 deg to 0.05 deg above the horizon, the horizon, below it, and the zero and
 * NaN vectors of the contract. */
#define NDIRS 29
static void directions(float d[NDIRS][3])
{
    static const double theta_up[] = {20, 45, 70, 85, 89.5, 89.95}, phi_up[] = {0, 110, 250};
    static const double theta_down[] = {100, 135, 170}, phi_down[] = {40, 200};
    int n = 0;
    d[n][0] = 0, d[n][1] = 0, d[n][2] = 1, n++;
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 3; j++) {
            ggx_vec3 v = t_dir(theta_up[i] * GGX_PI / 180, phi_up[j] * GGX_PI / 180);
            d[n][0] = (float)v.x, d[n][1] = (float)v.y, d[n][2] = (float)v.z, n++;
        }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++) {
            ggx_vec3 v = t_dir(theta_down[i] * GGX_PI / 180, phi_down[j] * GGX_PI / 180);
            d[n][0] = (float)v.x, d[n][1] = (float)v.y, d[n][2] = (float)v.z, n++;
        }
    d[n][0] = 1, d[n][1] = 0, d[n][2] = 0, n++;
    d[n][0] = 0, d[n][1] = 0, d[n][2] = -1, n++;
    d[n][0] = 0, d[n][1] = 0, d[n][2] = 0, n++;
    d[n][0] = NAN, d[n][1] = 0, d[n][2] = 1, n++;
}

/* Random numbers: the ends of a float generator, inside, outside [0, 1] and NaN. */
#define NUS 12
static const float us[NUS] = {0.0f, U_LO, 0.1f, 0.3f, 0.5f, 0.7f, 0.9f, U_HI, 1.0f, -0.25f, 1.5f, NAN};
#define NRANDOM 32

static void set3(float *row, const float *v) { row[0] = v[0], row[1] = v[1], row[2] = v[2]; }

static ggx_vec3 dir_of(const float *v) { return t_vec(v[0], v[1], v[2]); }

/* (u1, u2) rows: the grid of us and NRANDOM uniform pairs. */
static int pairs(float (*p)[2], rng *r)
{
    int n = 0;
    for (int i = 0; i < NUS; i++)
        for (int j = 0; j < NUS; j++) p[n][0] = us[i], p[n][1] = us[j], n++;
    for (int k = 0; k < NRANDOM; k++) p[n][0] = (float)rng_uniform(r), p[n][1] = (float)rng_uniform(r), n++;
    return n;
}

static const ggx_cuda_kernel *find_kernel(const char *name)
{
    for (int k = 0; k < ggx_cuda_kernel_count; k++)
        if (strcmp(ggx_cuda_kernels[k].name, name) == 0) return &ggx_cuda_kernels[k];
    return NULL;
}

static void run_host(const ggx_cuda_kernel *k, const ggx_cuda_args *base, const columns *in, float **out)
{
    ggx_cuda_args a = *base;
    a.n = in->n;
    for (int c = 0; c < in->ncols; c++) a.in[c] = in->c[c];
    for (int c = 0; c < ggx_cuda_out_columns(k->out); c++) a.out[c] = out[c];
    k->host(&a);
}

/* The inputs of kernel k for one shape and configuration (base holds both). */
static void make_inputs(const ggx_cuda_kernel *k, const ggx_cuda_args *base, columns *t)
{
    float d[NDIRS][3], p[NUS * NUS + NRANDOM][2], row[GGX_CUDA_MAX_IN];
    rng r = {0x9e3779b97f4a7c15ull};
    directions(d);
    int np = pairs(p, &r);
    memset(t, 0, sizeof *t);
    t->ncols = ggx_cuda_in_columns(k->in);
    switch (k->in) {
    case GGX_CUDA_IN_DIR:
        for (int i = 0; i < NDIRS; i++) set3(row, d[i]), push(t, row);
        break;
    case GGX_CUDA_IN_DIR2:
        for (int i = 0; i < NDIRS; i++)
            for (int j = 0; j < NDIRS; j++) set3(row, d[i]), set3(row + 3, d[j]), push(t, row);
        break;
    case GGX_CUDA_IN_DIR3: /* (wi, wo) with m their reflection half vector, their refraction one, and n */
        for (int i = 0; i < NDIRS; i++)
            for (int j = 0; j < NDIRS; j++) {
                ggx_vec3 h[3] = {ggx_half_reflect(dir_of(d[i]), dir_of(d[j])),
                                 ggx_half_refract(dir_of(d[i]), dir_of(d[j]), 1, base->eta), t_vec(0, 0, 1)};
                for (int m = 0; m < 3; m++) {
                    set3(row, d[i]), set3(row + 3, d[j]);
                    row[6] = (float)h[m].x, row[7] = (float)h[m].y, row[8] = (float)h[m].z;
                    push(t, row);
                }
            }
        break;
    case GGX_CUDA_IN_SCALAR: { /* cosines: both signs, grazing, the dielectric's critical cosine for 1.5, NaN */
        static const float cs[] = {-1,   -0.7f,      -0.2f, 0,      1e-4f, 0.01f, 0.1f, 0.3f,
                                   0.5f, 0.7453560f, 0.9f,  0.999f, 1,     1.25f, NAN};
        for (size_t i = 0; i < sizeof cs / sizeof cs[0]; i++) row[0] = cs[i], push(t, row);
        for (int i = 0; i < 64; i++) row[0] = (float)rng_range(&r, -1, 1), push(t, row);
        break;
    }
    case GGX_CUDA_IN_PAIR:
        for (int i = 0; i < np; i++) row[0] = p[i][0], row[1] = p[i][1], push(t, row);
        break;
    case GGX_CUDA_IN_VIEW_U2:
    case GGX_CUDA_IN_VIEW_U3: {
        static const float u3s[] = {0.0f, 0.3f, 0.97f, U_HI, NAN};
        for (int i = 0; i < NDIRS; i++)
            for (int j = 0; j < np; j++) {
                set3(row, d[i]), row[3] = p[j][0], row[4] = p[j][1], row[5] = u3s[(i + j) % 5];
                push(t, row);
            }
        break;
    }
    case GGX_CUDA_IN_VIEW:
        for (int i = 0; i < NDIRS; i++)
            for (int j = 0; j < 32; j++) set3(row, d[i]), push(t, row);
        break;
    case GGX_CUDA_IN_POINT:
    case GGX_CUDA_IN_NORMAL:
    case GGX_CUDA_IN_VIEW_NORMAL: { /* the forward map's outputs (on the host) for its own inputs, after its view */
        const ggx_cuda_kernel *f = find_kernel(k->forward);
        columns fin;
        float *fout[GGX_CUDA_MAX_OUT];
        int nf = ggx_cuda_out_columns(f->out), has_view = k->in == GGX_CUDA_IN_VIEW_NORMAL;
        make_inputs(f, base, &fin);
        for (int c = 0; c < nf; c++) fout[c] = xrealloc(NULL, fin.n * sizeof(float));
        run_host(f, base, &fin, fout);
        for (size_t i = 0; i < fin.n; i++) {
            for (int c = 0; c < 3 * has_view; c++) row[c] = fin.c[c][i];
            for (int c = 0; c < nf; c++) row[3 * has_view + c] = fout[c][i];
            push(t, row);
        }
        for (int c = 0; c < nf; c++) free(fout[c]);
        columns_free(&fin);
        break;
    }
    }
}

/* ---- comparison ---- */

/* How far got is from want, in each measure of the output layout. */
typedef struct diff {
    double eval, dir, pdf, weight; /* relative, absolute per component, relative, absolute */
    int mismatch;                  /* an event, flag or trial count differs */
} diff;

/* Equal (NaN and NaN included) is 0; NaN on one side only is infinite. */
static double abs_diff(double got, double want)
{
    if (got == want || (got != got && want != want)) return 0;
    if (got != got || want != want) return INFINITY;
    return fabs(got - want);
}
static double rel_diff(double got, double want) { return abs_diff(got, want) / fmax(fabs(want), 1e-30); }

static double max_abs_diff(const double *got, const double *want, int n)
{
    double m = 0;
    for (int c = 0; c < n; c++) m = fmax(m, abs_diff(got[c], want[c]));
    return m;
}

static diff differ(ggx_cuda_out out, const double *got, const double *want)
{
    diff d = {0, 0, 0, 0, 0};
    switch (out) {
    case GGX_CUDA_OUT_EVAL: d.eval = rel_diff(got[0], want[0]); break;
    case GGX_CUDA_OUT_POINT:
    case GGX_CUDA_OUT_UV: d.dir = max_abs_diff(got, want, 2); break;
    case GGX_CUDA_OUT_VEC:
    case GGX_CUDA_OUT_NORMAL:
    case GGX_CUDA_OUT_VNORMAL: d.dir = max_abs_diff(got, want, 3); break;
    case GGX_CUDA_OUT_REJECT:
    case GGX_CUDA_OUT_REFRACT:
        d.dir = max_abs_diff(got, want, 3);
        d.mismatch = got[3] != want[3];
        break;
    case GGX_CUDA_OUT_SAMPLE:
        d.dir = max_abs_diff(got, want, 3);
        d.pdf = rel_diff(got[3], want[3]);
        d.weight = abs_diff(got[4], want[4]);
        d.mismatch = got[5] != want[5];
        break;
    }
    return d;
}

/* The largest measure in units of its tolerance: <= 1 is agreement. */
static double over(diff d)
{
    double r = fmax(fmax(d.eval / TOL_EVAL, d.dir / TOL_DIR), fmax(d.pdf / TOL_PDF, d.weight / TOL_WEIGHT));
    return d.mismatch ? INFINITY : r;
}

static int is_zero(const double *w) { return w[0] == 0 && w[1] == 0 && w[2] == 0; }

/* A sampled vector: the zero vector or unit. */
static int unit_or_zero(const double *w)
{
    return is_zero(w) || fabs(sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) - 1) <= TOL_UNIT;
}

/* The contract on one device output (in: the element's inputs); the broken promise or NULL. */
static const char *contract(const ggx_cuda_kernel *k, const double *in, const double *dv)
{
    switch (k->out) {
    case GGX_CUDA_OUT_EVAL:
        if (!(fabs(dv[0]) <= DBL_MAX)) return "device value not finite";
        return (k->uses & GGX_CUDA_SIGNED) || dv[0] >= 0 ? NULL : "device value negative";
    case GGX_CUDA_OUT_VEC: return NULL; /* plain formulas: NaN in, NaN out */
    case GGX_CUDA_OUT_REFRACT:
        if (dv[3] == 0) return is_zero(dv) ? NULL : "no refraction but a direction";
        return dv[3] == 1 && unit_or_zero(dv) && !is_zero(dv) ? NULL : "refracted direction not unit";
    case GGX_CUDA_OUT_POINT: return dv[0] * dv[0] + dv[1] * dv[1] <= 1 + 1e-6 ? NULL : "device point off the disk";
    case GGX_CUDA_OUT_UV: return dv[0] >= 0 && dv[0] <= 1 && dv[1] >= 0 && dv[1] <= 1 ? NULL : "device u off [0, 1]";
    case GGX_CUDA_OUT_NORMAL:
    case GGX_CUDA_OUT_VNORMAL:
    case GGX_CUDA_OUT_REJECT:
        if (!unit_or_zero(dv)) return "device normal not unit";
        if (!(dv[2] >= 0)) return "device normal below the horizon";
        if (k->out != GGX_CUDA_OUT_NORMAL && !is_zero(dv) && !(dv[0] * in[0] + dv[1] * in[1] + dv[2] * in[2] > 0))
            return "device normal faces away from the view";
        return NULL;
    case GGX_CUDA_OUT_SAMPLE: {
        if (dv[5] == GGX_EVENT_INVALID) return is_zero(dv) && dv[3] == 0 && dv[4] == 0 ? NULL : "invalid not zero";
        if (is_zero(dv) || !unit_or_zero(dv)) return "device direction not unit";
        if (!(dv[3] > 0 && dv[3] <= DBL_MAX && dv[4] >= 0 && dv[4] <= DBL_MAX)) return "device pdf or weight bad";
        int same_side = (dv[2] > 0) == (in[2] > 0);
        if (dv[5] == GGX_EVENT_REFLECT) return same_side && dv[2] != 0 ? NULL : "reflection on the wrong side";
        if (dv[5] == GGX_EVENT_TRANSMIT) return !same_side && dv[2] != 0 ? NULL : "transmission on the wrong side";
        return "unknown event";
    }
    }
    return "unknown output";
}

/* ---- one kernel ---- */

typedef struct stats {
    size_t n, bad, ill;
    diff worst;      /* device against host, over the well-conditioned elements */
    double ill_over; /* the largest device-against-host difference of the ill-conditioned ones, in tolerances */
    int reports, notes;
} stats;

static void report(const char *kernel, const char *what, const char *shape, const config *cf, int uses, size_t i,
                   const double *in, int nin, const double *hv, const double *dv, const double *rv, int nout)
{
    fprintf(stderr, "%s %s: %s; shape %s", strncmp(what, "ill-conditioned", 15) ? "FAIL" : "note:", kernel, what,
            shape);
    if (uses & (GGX_CUDA_USES_FRESNEL | GGX_CUDA_USES_ETA | GGX_CUDA_USES_MODE))
        fprintf(stderr, ", Fresnel kind %d, eta %.9g, mode %d", (int)cf->kind, cf->eta, (int)cf->mode);
    fprintf(stderr, "; element %zu\n  in    ", i);
    for (int c = 0; c < nin; c++) fprintf(stderr, " %.9g", in[c]);
    const double *v[3] = {hv, dv, rv};
    const char *names[3] = {"host  ", "device", "double"};
    for (int r = 0; r < 3; r++) {
        fprintf(stderr, "\n  %s", names[r]);
        for (int c = 0; c < nout; c++) fprintf(stderr, " %.9g", v[r][c]);
    }
    fprintf(stderr, "\n");
}

/* Column buffers of one run. */
typedef struct run_out {
    float *f[GGX_CUDA_MAX_OUT];
    double *d[GGX_CUDA_MAX_OUT];
} run_out;

static void alloc_out(run_out *o, int nout, size_t n)
{
    memset(o, 0, sizeof *o);
    for (int c = 0; c < nout; c++) {
        o->f[c] = xrealloc(NULL, n * sizeof(float));
        o->d[c] = xrealloc(NULL, n * sizeof(double));
    }
}
static void free_out(run_out *o)
{
    for (int c = 0; c < GGX_CUDA_MAX_OUT; c++) free(o->f[c]), free(o->d[c]);
}

/* An inverse map's result as compared: its (u1, u2), then the sample they give (the double forward map f at those
 * u, after the view). */
static void through_forward(const ggx_cuda_kernel *f, const ggx_cuda_args *base, const double *in, int has_view,
                            const double *u, double *out)
{
    float row[GGX_CUDA_MAX_IN];
    double *cols[GGX_CUDA_MAX_OUT] = {0};
    ggx_cuda_args a = *base;
    int k = 0;
    for (int c = 0; c < 3 * has_view; c++) row[k++] = (float)in[c];
    row[k++] = (float)u[0], row[k++] = (float)u[1];
    a.n = 1;
    for (int c = 0; c < k; c++) a.in[c] = &row[c];
    for (int c = 0; c < ggx_cuda_out_columns(f->out); c++) cols[c] = &out[2 + c];
    out[0] = u[0], out[1] = u[1];
    f->reference(&a, cols);
}

/* |a - b| on the circle of circumference 1 (a turn of 0 is a turn of 1). */
static double circle_diff(double a, double b)
{
    double d = abs_diff(a, b);
    return d <= 1 ? fmin(d, 1 - d) : d;
}

/* How far got is from want (both as compared), in tolerances: <= 1 is agreement. An inverse map agrees when its
 * (u1, u2) do, as points of the torus, or the samples they give do: the first fails at the seams and poles of a map,
 * where u is not unique, the second at its rim, where the sample moves fast with u. */
static double distance(const ggx_cuda_kernel *k, const ggx_cuda_kernel *fwd, const double *got, const double *want)
{
    if (!fwd) return over(differ(k->out, got, want));
    double du = fmax(circle_diff(got[0], want[0]), circle_diff(got[1], want[1])) / TOL_INV;
    return fmin(du, over(differ(fwd->out, got + 2, want + 2)) * TOL_DIR / TOL_INV);
}

/* The host's result for one row of inputs, as compared (through the forward map for an inverse map). */
static void host_row(const ggx_cuda_kernel *k, const ggx_cuda_kernel *fwd, const ggx_cuda_args *base, const float *row,
                     double *out)
{
    float o[GGX_CUDA_MAX_OUT];
    double u[GGX_CUDA_MAX_OUT], in[GGX_CUDA_MAX_IN];
    int nin = ggx_cuda_in_columns(k->in), nout = ggx_cuda_out_columns(k->out);
    ggx_cuda_args a = *base;
    a.n = 1;
    for (int c = 0; c < nin; c++) a.in[c] = &row[c], in[c] = row[c];
    for (int c = 0; c < nout; c++) a.out[c] = &o[c];
    k->host(&a);
    for (int c = 0; c < nout; c++) u[c] = o[c];
    if (fwd) through_forward(fwd, base, in, k->in == GGX_CUDA_IN_VIEW_NORMAL, u, out);
    else memcpy(out, u, sizeof u);
}

/* Whether input column c of kernel k is a random number u: the samplers and disk maps clamp it into [0, 1] (NaN
 * to 0) and its resolution is 2^-24, the step of a float generator. */
static int is_u(const ggx_cuda_kernel *k, int c)
{
    if (k->in == GGX_CUDA_IN_PAIR) return k->out != GGX_CUDA_OUT_EVAL; /* not ndf_spherical's angles, p22's slopes */
    return (k->in == GGX_CUDA_IN_VIEW_U2 || k->in == GGX_CUDA_IN_VIEW_U3) && c >= 3;
}

/* Whether some u of the element is clamped to 1: outside the samplers' [0, 1), on the rim of the square, where
 * several maps put the normal on the rim of the lune and the float result is decided by rounding. */
static int u_at_one(const ggx_cuda_kernel *k, const double *iv)
{
    for (int c = 0; c < ggx_cuda_in_columns(k->in); c++)
        if (is_u(k, c) && iv[c] >= 1) return 1;
    return 0;
}

/* How far the host's result (as compared, hc) moves, in tolerances, when the inputs move by a few units of their
 * resolution (one ulp; 2^-24 at least for u): the float kernel's own sensitivity to rounding at this input. Each
 * trial moves every input by -4 .. 4 units at random, so that the roundings inside the kernel change too (moving
 * u = 0 by one ulp would change nothing). A u is moved from the value the kernel uses (clamped into [0, 1]). */
#define SPREAD_TRIALS 24
static double spread(const ggx_cuda_kernel *k, const ggx_cuda_kernel *fwd, const ggx_cuda_args *base, const double *iv,
                     const double *hc)
{
    float row[GGX_CUDA_MAX_IN];
    double out[GGX_CUDA_MAX_OUT], worst = 0;
    int nin = ggx_cuda_in_columns(k->in);
    rng r = {0x2545f4914f6cdd1dull};
    for (int t = 0; t < SPREAD_TRIALS; t++) {
        for (int c = 0; c < nin; c++) {
            float x = (float)iv[c];
            int u = is_u(k, c);
            if (u) x = x > 0 ? (x < 1 ? x : 1) : 0;
            row[c] = x;
            if (!(fabsf(x) <= FLT_MAX)) continue;
            double unit = fabs((double)nextafterf(x, INFINITY) - x);
            if (u) unit = fmax(unit, 0x1p-24);
            row[c] = (float)(x + unit * (double)((int)(rng_uniform(&r) * 9) - 4));
        }
        host_row(k, fwd, base, row, out);
        worst = fmax(worst, distance(k, fwd, out, hc));
    }
    return worst;
}

/* Runs k on the device, the host and the double reference for every shape (and configuration, where it uses one);
 * 0 when every element passes. */
static int check_kernel(const ggx_cuda_kernel *k, const ggx_shape *ds, const unsigned *seeds)
{
    stats st;
    memset(&st, 0, sizeof st);
    int nin = ggx_cuda_in_columns(k->in), nout = ggx_cuda_out_columns(k->out);
    const ggx_cuda_kernel *fwd = k->out == GGX_CUDA_OUT_UV ? find_kernel(k->forward) : NULL;
    int ncmp = fwd ? 2 + ggx_cuda_out_columns(fwd->out) : nout; /* columns compared */
    size_t nconf = k->uses & (GGX_CUDA_USES_FRESNEL | GGX_CUDA_USES_ETA | GGX_CUDA_USES_MODE) ? NCONFIGS : 1;
    for (size_t si = 0; si < NSHAPES; si++)
        for (size_t ci = 0; ci < nconf; ci++) {
            const config *cf = &configs[ci];
            ggx_fresnel f;
            ggx_status fs = cf->kind == GGX_FRESNEL_DIELECTRIC  ? ggx_fresnel_dielectric(&f, cf->fa)
                            : cf->kind == GGX_FRESNEL_CONDUCTOR ? ggx_fresnel_conductor(&f, cf->fa, cf->fb)
                            : cf->kind == GGX_FRESNEL_SCHLICK   ? ggx_fresnel_schlick(&f, cf->fa)
                                                                : ggx_fresnel_one(&f);
            if (fs != GGX_OK) {
                fprintf(stderr, "FAIL: Fresnel setup %d: %s\n", (int)cf->kind, ggx_status_str(fs));
                return 1;
            }
            ggx_cuda_args a;
            memset(&a, 0, sizeof a);
            ggx_shapef_from(&a.s, &ds[si]);
            ggx_fresnelf_from(&a.f, &f);
            a.eta = cf->eta, a.mode = (int)cf->mode, a.seed = seeds[si];
            columns in;
            make_inputs(k, &a, &in);
            run_out host, dev, ref;
            alloc_out(&host, nout, in.n), alloc_out(&dev, nout, in.n), alloc_out(&ref, nout, in.n);
            for (int c = 0; c < nout; c++)
                for (size_t i = 0; i < in.n; i++) dev.f[c][i] = -12345.0f; /* a value no kernel writes */
            run_host(k, &a, &in, host.f);
            a.n = in.n;
            for (int c = 0; c < nin; c++) a.in[c] = in.c[c];
            k->reference(&a, ref.d);
            for (int c = 0; c < nout; c++) a.out[c] = dev.f[c];
            char why[512];
            if (ggx_cuda_run_device(k, &a, why, sizeof why) != 0) {
                fprintf(stderr, "FAIL %s: %s\n", k->name, why);
                return 1;
            }
            for (size_t i = 0; i < in.n; i++) {
                double iv[GGX_CUDA_MAX_IN], hv[GGX_CUDA_MAX_OUT], dv[GGX_CUDA_MAX_OUT], rv[GGX_CUDA_MAX_OUT];
                double hc[GGX_CUDA_MAX_OUT], dc[GGX_CUDA_MAX_OUT], rc[GGX_CUDA_MAX_OUT]; /* as compared */
                for (int c = 0; c < nin; c++) iv[c] = in.c[c][i];
                for (int c = 0; c < nout; c++) hv[c] = host.f[c][i], dv[c] = dev.f[c][i], rv[c] = ref.d[c][i];
                if (fwd) {
                    int has_view = k->in == GGX_CUDA_IN_VIEW_NORMAL;
                    through_forward(fwd, &a, iv, has_view, hv, hc);
                    through_forward(fwd, &a, iv, has_view, dv, dc);
                    through_forward(fwd, &a, iv, has_view, rv, rc);
                } else {
                    memcpy(hc, hv, sizeof hv), memcpy(dc, dv, sizeof dv), memcpy(rc, rv, sizeof rv);
                }
                double dev_host = distance(k, fwd, dc, hc);
                diff dh = differ(k->out, dc, hc);
                if (fwd) dh.dir = dev_host * TOL_INV; /* as compared */
                const char *what = contract(k, iv, dv);
                st.n++;
                /* the spread is needed only where the device and the host disagree */
                if (dev_host > 1 && (u_at_one(k, iv) || spread(k, fwd, &a, iv, hc) > ILL)) {
                    st.ill++;
                    st.ill_over = fmax(st.ill_over, dev_host);
                    if (!what && st.notes++ < MAX_NOTES)
                        report(k->name,
                               u_at_one(k, iv) ? "ill-conditioned: u = 1, the rim"
                                               : "ill-conditioned: a few ulps of the inputs move the host's "
                                                 "result by more than 1/8 of the tolerance",
                               shapes[si].what, cf, k->uses, i, iv, nin, fwd ? hc : hv, fwd ? dc : dv, fwd ? rc : rv,
                               fwd ? ncmp : nout);
                } else {
                    st.worst.eval = fmax(st.worst.eval, dh.eval), st.worst.dir = fmax(st.worst.dir, dh.dir);
                    st.worst.pdf = fmax(st.worst.pdf, dh.pdf), st.worst.weight = fmax(st.worst.weight, dh.weight);
                    st.worst.mismatch |= dh.mismatch;
                    if (!what && dev_host > 1)
                        what = fwd ? "the device's sample differs from the host's" : "device differs from the host";
                }
                if (what) st.bad++;
                if (what && st.reports++ < MAX_REPORTS)
                    report(k->name, what, shapes[si].what, cf, k->uses, i, iv, nin, fwd ? hc : hv, fwd ? dc : dv,
                           fwd ? rc : rv, fwd ? ncmp : nout);
            }
            free_out(&host), free_out(&dev), free_out(&ref);
            columns_free(&in);
        }
    printf("cuda %-30s n %6zu  max diff vs host ", k->name, st.n);
    switch (k->out) {
    case GGX_CUDA_OUT_EVAL: printf("%.2e rel (tol %.0e)", st.worst.eval, TOL_EVAL); break;
    case GGX_CUDA_OUT_SAMPLE:
        printf("%.2e abs (tol %.0e), pdf %.2e rel (tol %.0e), weight %.2e abs (tol %.0e)", st.worst.dir, TOL_DIR,
               st.worst.pdf, TOL_PDF, st.worst.weight, TOL_WEIGHT);
        break;
    default:
        if (fwd) printf("%.2e abs (tol %.0e) as u or as samples", st.worst.dir, TOL_INV);
        else printf("%.2e abs (tol %.0e)", st.worst.dir, TOL_DIR);
        break;
    }
    if (st.worst.mismatch) printf(", events/flags/trials differ");
    if (st.ill) printf("; ill-conditioned %zu (up to %.3g tol)", st.ill, st.ill_over);
    printf("  %s", st.bad ? "FAIL" : "ok");
    if (st.bad) printf(" (%zu of %zu)", st.bad, st.n);
    printf("\n");
    return st.bad != 0;
}

int main(void)
{
    char why[512];
    setvbuf(stdout, NULL, _IOLBF, 0); /* the per-kernel lines and the notes on stderr stay in order */
    int dev = ggx_cuda_device_check(why, sizeof why);
    const char *require = getenv("GGX_REQUIRE_GPU");
    if (dev == 0 && require && *require) {
        fprintf(stderr, "test_cuda: FAIL: GGX_REQUIRE_GPU is set but %s\n", why);
        return 1;
    }
    if (dev == 0) {
        printf("test_cuda: skipped: %s\n", why);
        return SKIP;
    }
    if (dev < 0) {
        fprintf(stderr, "test_cuda: FAIL: %s\n", why);
        return 1;
    }
    printf("test_cuda: %s; %d kernels\n", why, ggx_cuda_kernel_count);

    ggx_shape ds[NSHAPES];
    unsigned seeds[NSHAPES];
    for (size_t i = 0; i < NSHAPES; i++) {
        const shape_case *c = &shapes[i];
        const double A[3][3] = {{c->c, 0, 0}, {0, c->c, 0}, {0, 0, c->c}};
        ggx_status s = c->c > 0 ? ggx_shape_matrix(&ds[i], A)
                                : ggx_shape_ellipsoid(&ds[i], c->ax, c->ay, c->tx, c->ty, c->tz);
        if (s != GGX_OK) {
            fprintf(stderr, "test_cuda: FAIL: shape %s: %s\n", c->what, ggx_status_str(s));
            return 1;
        }
        seeds[i] = 1000u + (unsigned)i;
    }

    /* Every sampler of the registry, and its inverse where it has one, has a kernel in the table. */
    int failed = 0;
#define STEM_CHECK(ID, name, stem, family, domain, inverse, batch, help)                                               \
    if (!find_kernel(#stem) || (inverse && !find_kernel(#stem "_inv"))) {                                              \
        fprintf(stderr, "FAIL: sampler %s (ggx_%s_f) has no CUDA kernel\n", name, #stem);                              \
        failed++;                                                                                                      \
    }
    GGX_SAMPLER_LIST(STEM_CHECK)
#undef STEM_CHECK

    for (int k = 0; k < ggx_cuda_kernel_count; k++) failed += check_kernel(&ggx_cuda_kernels[k], ds, seeds);
    printf("test_cuda: %d of %d kernels %s\n", failed ? failed : ggx_cuda_kernel_count, ggx_cuda_kernel_count,
           failed ? "FAILED" : "agree with the host");
    return failed ? 1 : 0;
}
