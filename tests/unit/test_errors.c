/* Every status path of the setup functions, the documented clamps, and the hot functions' behaviour outside their
 * domain: exactly 0, never NaN or Inf. SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "ggx/ggx_batch.h"
#include "ggx/ggx_samplers.h"
#include "testlib.h"

static void shape_statuses(void **state)
{
    (void)state;
    ggx_shape s, before;
    CHECK(ggx_shape_iso(&s, 0.3) == GGX_OK, "ok");
    memcpy(&before, &s, sizeof s);
    /* Each failure leaves the output untouched. */
    const struct {
        ggx_status got, want;
        const char *what;
    } cases[] = {
        {ggx_shape_iso(NULL, 0.3), GGX_ERR_NULL, "iso NULL"},
        {ggx_shape_aniso(NULL, 0.3, 0.3), GGX_ERR_NULL, "aniso NULL"},
        {ggx_shape_ellipsoid(NULL, 0.3, 0.3, 0, 0, 0), GGX_ERR_NULL, "ellipsoid NULL"},
        {ggx_shape_matrix(NULL, NULL), GGX_ERR_NULL, "matrix NULL"},
        {ggx_shape_matrix(&s, NULL), GGX_ERR_NULL, "matrix NULL A"},
        {ggx_shape_iso(&s, NAN), GGX_ERR_NONFINITE, "alpha NaN"},
        {ggx_shape_iso(&s, INFINITY), GGX_ERR_NONFINITE, "alpha Inf"},
        {ggx_shape_aniso(&s, 0.3, -INFINITY), GGX_ERR_NONFINITE, "alpha_y -Inf"},
        {ggx_shape_iso(&s, 0.0), GGX_ERR_ALPHA, "alpha 0"},
        {ggx_shape_iso(&s, -0.1), GGX_ERR_ALPHA, "alpha < 0"},
        {ggx_shape_aniso(&s, 0.3, 2e4), GGX_ERR_ALPHA, "alpha > max"},
        {ggx_shape_ellipsoid(&s, 0.3, 0.3, NAN, 0, 0), GGX_ERR_NONFINITE, "theta_x NaN"},
        {ggx_shape_ellipsoid(&s, 0.3, 0.3, 0, 0, INFINITY), GGX_ERR_NONFINITE, "theta_z Inf"},
        {ggx_shape_ellipsoid(&s, 0.3, 0.3, 1.6, 0, 0), GGX_ERR_ANGLE, "theta_x > pi/2"},
        {ggx_shape_ellipsoid(&s, 0.3, 0.3, 0, -1.6, 0), GGX_ERR_ANGLE, "theta_y < -pi/2"},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        CHECK(cases[i].got == cases[i].want, "%s: got %d (%s)", cases[i].what, cases[i].got,
              ggx_status_str(cases[i].got));
        CHECK(memcmp(&s, &before, sizeof s) == 0, "%s modified the shape", cases[i].what);
    }
    const double sing[3][3] = {{1, 2, 3}, {2, 4, 6}, {0, 0, 1}};
    const double near[3][3] = {{1e-7, 0, 0}, {0, 1e-7, 0}, {0, 0, 1}};
    const double nanm[3][3] = {{1, 0, 0}, {0, NAN, 0}, {0, 0, 1}};
    const double zero[3][3] = {{0}};
    const double huge[3][3] = {{1e60, 0, 0}, {0, 1e60, 0}, {0, 0, 1e60}},
                 tiny[3][3] = {{1e-60, 0, 0}, {0, 1e-60, 0}, {0, 0, 1e-60}};
    CHECK(ggx_shape_matrix(&s, huge) == GGX_ERR_RANGE && ggx_shape_matrix(&s, tiny) == GGX_ERR_RANGE, "matrix scale");
    CHECK(ggx_shape_matrix(&s, sing) == GGX_ERR_SINGULAR, "rank 2");
    CHECK(ggx_shape_matrix(&s, near) == GGX_ERR_SINGULAR, "near singular");
    CHECK(ggx_shape_matrix(&s, zero) == GGX_ERR_SINGULAR, "zero");
    CHECK(ggx_shape_matrix(&s, nanm) == GGX_ERR_NONFINITE, "NaN entry");
    CHECK(memcmp(&s, &before, sizeof s) == 0, "failed matrix setup modified the shape");
    const double ok[3][3] = {{1e-4, 0, 0}, {0, 1e-4, 0}, {0, 0, 1}};
    CHECK(ggx_shape_matrix(&s, ok) == GGX_OK && s.kind == GGX_SHAPE_DIAGONAL, "alpha_min as a matrix is accepted");
    for (int st = GGX_OK; st <= GGX_ERR_DATA; st++)
        CHECK(ggx_status_str((ggx_status)st) && strlen(ggx_status_str((ggx_status)st)) > 1, "message %d", st);
    CHECK(strcmp(ggx_status_str((ggx_status)999), "unknown status") == 0, "unknown");
}

/* ggx_ellipsoid_matrix: S Rx Ry Rz multiplied out here from the three rotation matrices (Walter eq 3), the same
 * statuses as ggx_shape_ellipsoid with A untouched on error, and ggx_shape_matrix of it is ggx_shape_ellipsoid's shape
 * bit for bit. */
static void ellipsoid_matrix(void **state)
{
    (void)state;
    const double p[][5] = {{0.15, 0.5, 0, 0, 0}, {0.3, 0.6, 0.35, -0.26, 0.52}, {1e-5, 2.0, -1.5, 1.2, 7.0}};
    for (unsigned k = 0; k < sizeof p / sizeof p[0]; k++) {
        const double *q = p[k];
        double cx = cos(q[2]), sx = sin(q[2]), cy = cos(q[3]), sy = sin(q[3]), cz = cos(q[4]), sz = sin(q[4]);
        const double rx[3][3] = {{1, 0, 0}, {0, cx, -sx}, {0, sx, cx}};
        const double ry[3][3] = {{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}};
        const double rz[3][3] = {{cz, -sz, 0}, {sz, cz, 0}, {0, 0, 1}};
        double rxy[3][3] = {{0}}, want[3][3] = {{0}};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                for (int l = 0; l < 3; l++) rxy[i][j] += rx[i][l] * ry[l][j];
        const double scale[3] = {fmax(q[0], GGX_ALPHA_MIN), fmax(q[1], GGX_ALPHA_MIN), 1.0};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                for (int l = 0; l < 3; l++) want[i][j] += rxy[i][l] * rz[l][j];
                want[i][j] *= scale[i];
            }
        double A[3][3];
        CHECK(ggx_ellipsoid_matrix(A, q[0], q[1], q[2], q[3], q[4]) == GGX_OK, "case %u", k);
        /* entries up to alpha <= 2 in size: 1e-15 is about 2 ulp of the products of rounded sines and cosines */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                CHECK(fabs(A[i][j] - want[i][j]) <= 1e-15, "case %u A[%d][%d] = %.17g, want %.17g", k, i, j, A[i][j],
                      want[i][j]);
        ggx_shape from_matrix, direct;
        memset(&from_matrix, 0, sizeof from_matrix);
        memset(&direct, 0, sizeof direct);
        CHECK(ggx_shape_matrix(&from_matrix, (const double(*)[3])A) == GGX_OK, "case %u matrix", k);
        CHECK(ggx_shape_ellipsoid(&direct, q[0], q[1], q[2], q[3], q[4]) == GGX_OK, "case %u ellipsoid", k);
        CHECK(memcmp(&from_matrix, &direct, sizeof direct) == 0, "case %u: shapes differ", k);
    }
    double A[3][3] = {{7, 7, 7}, {7, 7, 7}, {7, 7, 7}};
    const struct {
        ggx_status got, want;
    } cases[] = {
        {ggx_ellipsoid_matrix(NULL, 0.3, 0.3, 0, 0, 0), GGX_ERR_NULL},
        {ggx_ellipsoid_matrix(A, NAN, 0.3, 0, 0, 0), GGX_ERR_NONFINITE},
        {ggx_ellipsoid_matrix(A, 0.3, 0.3, 0, 0, INFINITY), GGX_ERR_NONFINITE},
        {ggx_ellipsoid_matrix(A, 0.3, 0.0, 0, 0, 0), GGX_ERR_ALPHA},
        {ggx_ellipsoid_matrix(A, 2e4, 0.3, 0, 0, 0), GGX_ERR_ALPHA},
        {ggx_ellipsoid_matrix(A, 0.3, 0.3, 0, 1.6, 0), GGX_ERR_ANGLE},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; i++)
        CHECK(cases[i].got == cases[i].want, "status case %u: got %d", i, cases[i].got);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) CHECK(A[i][j] == 7, "A modified on error");
}

/* alpha below GGX_ALPHA_MIN is raised to it; a negative-determinant matrix is the same distribution. */
static void clamps_and_signs(void **state)
{
    (void)state;
    ggx_shape a, b;
    CHECK(ggx_shape_iso(&a, 1e-9) == GGX_OK && ggx_shape_iso(&b, GGX_ALPHA_MIN) == GGX_OK, "setup");
    CHECK(memcmp(&a, &b, sizeof a) == 0, "alpha clamped to GGX_ALPHA_MIN");
    CHECK(a.alpha_x == GGX_ALPHA_MIN, "alpha_x %g", a.alpha_x);
    const double neg[3][3] = {{-0.3, 0.1, 0.05}, {0.0, 0.6, -0.1}, {0.1, 0.0, 1.0}};
    double pos[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) pos[i][j] = -neg[i][j];
    ggx_shape sn, sp;
    CHECK(ggx_shape_matrix(&sn, neg) == GGX_OK && ggx_shape_matrix(&sp, (const double(*)[3])pos) == GGX_OK, "setup");
    CHECK(sn.det > 0 && sp.det > 0, "det > 0");
    rng r = {51};
    for (int i = 0; i < 100; i++) {
        ggx_vec3 m = random_view(&r), v = random_view(&r);
        CHECK(ggx_ndf(&sn, m) == ggx_ndf(&sp, m), "same D");
        CHECK(ggx_pdf_vndf(&sn, v, m) == ggx_pdf_vndf(&sp, v, m), "same vndf");
    }
    ggx_shape e;
    CHECK(ggx_shape_ellipsoid(&e, 0.3, 0.5, 0.2, 0, 0) == GGX_OK && e.kind == GGX_SHAPE_SKEWED, "skewed kind");
    CHECK(ggx_shape_ellipsoid(&e, 0.3, 0.5, 0, 0, 1.0) == GGX_OK && e.kind == GGX_SHAPE_UNSKEWED, "unskewed kind");
    CHECK(ggx_shape_ellipsoid(&e, 0.3, 0.5, GGX_SKEW_MAX, -GGX_SKEW_MAX, 7.0) == GGX_OK, "skew limit accepted");
}

/* Outside the domain: exactly 0. NaN directions: 0, never NaN. Zero vectors: 0, never Inf. */
static void hot_functions_outside_domain(void **state)
{
    (void)state;
    ggx_shape sh[2];
    CHECK(ggx_shape_aniso(&sh[0], 0.3, 0.6) == GGX_OK && ggx_shape_ellipsoid(&sh[1], 0.3, 0.6, 0.4, -0.3, 1) == GGX_OK,
          "setup");
    ggx_fresnel f;
    ggx_fresnel_conductor(&f, 0.2, 3.9);
    const ggx_vec3 up = {0.3, 0.2, 0.9327379053}, below = {0.3, 0.2, -0.9327379053}, horizon = {0.6, 0.8, 0};
    const ggx_vec3 zero = {0, 0, 0}, nanv = {NAN, 0, 1}, nanz = {0, 0, NAN}, infv = {INFINITY, 0, 1};
    const ggx_vec3 bad[] = {zero, nanv, nanz, infv};
    for (int k = 0; k < 2; k++) {
        const ggx_shape *s = &sh[k];
        CHECK(ggx_ndf(s, below) == 0.0, "D below");
        CHECK(ggx_ndf(s, horizon) > 0.0, "D on the horizon is inside (X+(0) = 1)");
        CHECK(ggx_g1(s, below, up) == 0.0 && ggx_g1(s, horizon, up) == 0.0, "G1 below / horizon");
        CHECK(ggx_lambda(s, below) == 0.0 && ggx_g1_smith(s, below) == 0.0, "Lambda below");
        CHECK(ggx_pdf_vndf(s, below, up) == 0.0 && ggx_pdf_vndf(s, horizon, up) == 0.0, "vndf below");
        CHECK(ggx_pdf_vndf(s, up, below) == 0.0, "vndf m below");
        CHECK(ggx_brdf_eval(s, &f, up, below) == 0.0 && ggx_brdf_eval(s, &f, horizon, up) == 0.0, "brdf below");
        CHECK(ggx_bsdf_eval(s, 1.5, horizon, up, GGX_RADIANCE) == 0.0, "bsdf horizon");
        CHECK(ggx_bsdf_eval(s, 0.0, up, up, GGX_RADIANCE) == 0.0 &&
                  ggx_bsdf_eval(s, NAN, up, below, GGX_RADIANCE) == 0.0,
              "bsdf bad eta");
        CHECK(ggx_ndf_spherical(s, -0.1, 0) == 0.0 && ggx_ndf_spherical(s, 2.0, 0) == 0.0, "spherical range");
        CHECK(ggx_lune_area(s, up, zero) == 0.0, "lune zero v");
        for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            ggx_vec3 b = bad[i];
            double vals[] = {ggx_ndf(s, b),
                             ggx_gaussian_curvature(s, b),
                             ggx_projected_area(s, b),
                             ggx_lune_area(s, b, up),
                             ggx_lune_area(s, up, b),
                             ggx_g1(s, b, up),
                             ggx_g1(s, up, b),
                             ggx_lambda(s, b),
                             ggx_g1_smith(s, b),
                             ggx_g1_tilted(s, b, up),
                             ggx_g1_tilted(s, up, b),
                             ggx_g1_risers(s, b, up),
                             ggx_g1_risers(s, up, b),
                             ggx_g2(s, b, up, up),
                             ggx_g2_height_correlated(s, up, b, up),
                             ggx_pdf_vndf(s, b, up),
                             ggx_pdf_vndf(s, up, b),
                             ggx_brdf_eval(s, &f, b, up),
                             ggx_brdf_eval(s, &f, up, b),
                             ggx_bsdf_eval(s, 1.5, b, up, GGX_RADIANCE),
                             ggx_bsdf_eval(s, 1.5, up, b, GGX_IMPORTANCE),
                             ggx_jacobian_reflect(b, up),
                             ggx_jacobian_refract(b, up, up, 1, 1.5),
                             ggx_p22(s, NAN, 0)};
            for (unsigned j = 0; j < sizeof vals / sizeof vals[0]; j++)
                CHECK(vals[j] == 0.0, "shape %d bad input %u: function %u gave %g", k, i, j, vals[j]);
        }
    }
    CHECK(ggx_fresnel_dielectric_eval(NAN, 1.5) == 0.0 && ggx_fresnel_dielectric_eval(0.5, -1) == 0.0, "F d");
    CHECK(ggx_fresnel_conductor_eval(NAN, 1, 1) == 0.0 && ggx_fresnel_conductor_eval(0.5, 1, -1) == 0.0, "F c");
    CHECK(ggx_fresnel_schlick_eval(NAN, 0.5) == 0.0 && ggx_fresnel_schlick_eval(0.5, 2) == 0.0, "F s");
    ggx_vec3 h = ggx_half_reflect(up, t_scale(up, -1));
    CHECK(h.x == 0 && h.y == 0 && h.z == 0, "half vector of opposite directions");
    ggx_vec3 o;
    CHECK(!ggx_refract(t_vec(0, 0, 1), t_vec(1, 0, 0), 1.5, &o) && !ggx_refract(nanv, up, 1.5, &o) &&
              !ggx_refract(up, up, -1, &o),
          "refract");
}

static void fresnel_statuses(void **state)
{
    (void)state;
    ggx_fresnel f;
    CHECK(ggx_fresnel_one(NULL) == GGX_ERR_NULL && ggx_fresnel_dielectric(NULL, 1.5) == GGX_ERR_NULL, "NULL");
    CHECK(ggx_fresnel_conductor(NULL, 1, 1) == GGX_ERR_NULL && ggx_fresnel_schlick(NULL, 0.5) == GGX_ERR_NULL, "NULL");
    CHECK(ggx_fresnel_dielectric(&f, NAN) == GGX_ERR_NONFINITE && ggx_fresnel_dielectric(&f, 0) == GGX_ERR_ETA, "d");
    CHECK(ggx_fresnel_conductor(&f, 1, INFINITY) == GGX_ERR_NONFINITE, "c inf");
    CHECK(ggx_fresnel_conductor(&f, -1, 1) == GGX_ERR_ETA && ggx_fresnel_conductor(&f, 1, -1) == GGX_ERR_ETA, "c");
    CHECK(ggx_fresnel_schlick(&f, NAN) == GGX_ERR_NONFINITE && ggx_fresnel_schlick(&f, 1.5) == GGX_ERR_RANGE, "s");
}

/* One rule for the whole API: a NULL Fresnel term is F = 1, bit for bit the result with ggx_fresnel_one, in every
 * exported and batch function that takes one (on 660888d ggx_fresnel_eval, ggx_brdf_eval and the reflection
 * samplers crashed). */
#define SAME_SAMPLE(a, b)                                                                                              \
    ((a).w.x == (b).w.x && (a).w.y == (b).w.y && (a).w.z == (b).w.z && (a).pdf == (b).pdf &&                           \
     (a).weight == (b).weight && (a).event == (b).event)
static void null_fresnel_is_one(void **state)
{
    (void)state;
    ggx_fresnel one;
    ggx_fresnel_one(&one);
    ggx_shape shapes[2];
    ggx_shape_iso(&shapes[0], 0.3);
    ggx_shape_ellipsoid(&shapes[1], 0.2, 0.5, 0.3, -0.2, 0.4);
    ggx_vec3 wi = t_vec(0.5, 0.1, 0.86), wo = t_vec(-0.3, 0.2, 0.93);
    wi = t_scale(wi, 1.0 / sqrt(t_dot(wi, wi)));
    wo = t_scale(wo, 1.0 / sqrt(t_dot(wo, wo)));
    for (double c = 0.0; c <= 1.0; c += 0.25)
        CHECK(ggx_fresnel_eval(NULL, c) == ggx_fresnel_eval(&one, c) && ggx_fresnel_eval(NULL, c) == 1.0, "F(%g)", c);
    CHECK(ggx_fresnel_avg(NULL) == ggx_fresnel_avg(&one), "F_avg");
    for (int k = 0; k < 2; k++) {
        const ggx_shape *s = &shapes[k];
        CHECK(ggx_brdf_eval(s, NULL, wi, wo) == ggx_brdf_eval(s, &one, wi, wo), "brdf_eval, shape %d", k);
        for (double u = 0.05; u < 1.0; u += 0.3) {
            ggx_sample a = ggx_sample_brdf(s, NULL, wi, u, 1 - u), b = ggx_sample_brdf(s, &one, wi, u, 1 - u);
            CHECK(SAME_SAMPLE(a, b), "sample_brdf, shape %d", k);
            a = ggx_sample_brdf_bounded(s, NULL, wi, u, 1 - u), b = ggx_sample_brdf_bounded(s, &one, wi, u, 1 - u);
            CHECK(SAME_SAMPLE(a, b), "sample_brdf_bounded, shape %d", k);
            a = ggx_sample_brdf_bounded_azimuth(s, NULL, wi, u, 1 - u);
            b = ggx_sample_brdf_bounded_azimuth(s, &one, wi, u, 1 - u);
            CHECK(SAME_SAMPLE(a, b), "sample_brdf_bounded_azimuth, shape %d", k);
        }
        for (int i = 0; i < GGX_SAMPLER_COUNT; i++) {
            const ggx_sampler_info *inf = ggx_sampler_get((ggx_sampler_id)i);
            if (inf->family != GGX_FAMILY_DIRECTION) continue;
            ggx_sample a = inf->sample_direction(s, NULL, 1.5, wi, 0.3, 0.6, 0.2, GGX_RADIANCE);
            ggx_sample b = inf->sample_direction(s, &one, 1.5, wi, 0.3, 0.6, 0.2, GGX_RADIANCE);
            CHECK(SAME_SAMPLE(a, b), "registry %s, shape %d", inf->name, k);
        }
        float x[1] = {(float)wi.x}, y[1] = {(float)wi.y}, z[1] = {(float)wi.z};
        float ox[1] = {(float)wo.x}, oy[1] = {(float)wo.y}, oz[1] = {(float)wo.z}, u1[1] = {0.3f}, u2[1] = {0.6f};
        float fa[1], fb[1], r[2][5];
        ggx_batch_brdf(fa, 1, s, NULL, x, y, z, ox, oy, oz);
        ggx_batch_brdf(fb, 1, s, &one, x, y, z, ox, oy, oz);
        CHECK(fa[0] == fb[0] && fa[0] > 0, "batch_brdf, shape %d", k);
        for (int j = 0; j < 2; j++)
            ggx_batch_sample_brdf(&r[j][0], &r[j][1], &r[j][2], &r[j][3], &r[j][4], 1, s, j ? &one : NULL, x, y, z, u1,
                                  u2);
        CHECK(memcmp(r[0], r[1], sizeof r[0]) == 0, "batch_sample_brdf, shape %d", k);
        for (int j = 0; j < 2; j++)
            ggx_batch_sample_directions(GGX_SAMPLER_BRDF_BOUNDED, &r[j][0], &r[j][1], &r[j][2], &r[j][3], &r[j][4], 1,
                                        s, j ? &one : NULL, x, y, z, u1, u2);
        CHECK(memcmp(r[0], r[1], sizeof r[0]) == 0, "batch_sample_directions, shape %d", k);
    }
    ggx_energy *e;
    CHECK(ggx_energy_create(&shapes[0], &e) == GGX_OK, "energy");
    CHECK(ggx_brdf_ms_eval(e, NULL, wi, wo) == ggx_brdf_ms_eval(e, &one, wi, wo), "ms_eval");
    CHECK(ggx_brdf_compensated_eval(e, NULL, wi, wo) == ggx_brdf_compensated_eval(e, &one, wi, wo), "comp eval");
    CHECK(ggx_pdf_brdf_compensated(e, NULL, wi, wo) == ggx_pdf_brdf_compensated(e, &one, wi, wo), "comp pdf");
    ggx_sample a = ggx_sample_brdf_ms(e, NULL, wi, 0.3, 0.6), b = ggx_sample_brdf_ms(e, &one, wi, 0.3, 0.6);
    CHECK(SAME_SAMPLE(a, b), "sample_brdf_ms");
    a = ggx_sample_brdf_compensated(e, NULL, wi, 0.3, 0.6, 0.9),
    b = ggx_sample_brdf_compensated(e, &one, wi, 0.3, 0.6, 0.9);
    CHECK(SAME_SAMPLE(a, b), "sample_brdf_compensated");
    ggx_energy_free(e);
}

/* The energy objects' create functions set *out to NULL on every error (the headers' promise). */
static void energy_create_null(void **state)
{
    (void)state;
    ggx_energy *e = (ggx_energy *)&e;
    CHECK(ggx_energy_create(NULL, &e) == GGX_ERR_NULL && e == NULL, "ggx_energy_create(NULL, &e)");
    ggx_bsdf_energy *b = (ggx_bsdf_energy *)&b;
    CHECK(ggx_bsdf_energy_create(NULL, 1.5, &b) == GGX_ERR_NULL && b == NULL, "ggx_bsdf_energy_create(NULL, ...)");
    ggx_shape s;
    ggx_shape_iso(&s, 0.3);
    b = (ggx_bsdf_energy *)&b;
    CHECK(ggx_bsdf_energy_create(&s, 1.0, &b) == GGX_ERR_ETA && b == NULL, "eta = 1");
    CHECK(strstr(ggx_status_str(GGX_ERR_ETA), "not exactly 1") != NULL, "GGX_ERR_ETA's message names eta = 1");
    CHECK(ggx_energy_create(&s, NULL) == GGX_ERR_NULL, "out NULL");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shape_statuses),     cmocka_unit_test(ellipsoid_matrix),
        cmocka_unit_test(clamps_and_signs),   cmocka_unit_test(hot_functions_outside_domain),
        cmocka_unit_test(fresnel_statuses),   cmocka_unit_test(null_fresnel_is_one),
        cmocka_unit_test(energy_create_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
