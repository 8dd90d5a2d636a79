/* The batch API: shape conversion to float, run-time instruction-set dispatch, and threads for large batches.
 * SPDX-License-Identifier: MIT */
#include <pthread.h>
#include <string.h>

#include "batch_internal.h"
#include "ggx/ggx_batch.h"

static const batch_kernels *table_of(ggx_batch_isa isa)
{
    switch (isa) {
    case GGX_ISA_SCALAR: return &ggx_kernels_scalar;
#if defined(GGX_HAVE_AVX2)
    case GGX_ISA_AVX2: return &ggx_kernels_avx2;
#endif
#if defined(GGX_HAVE_AVX512)
    case GGX_ISA_AVX512: return &ggx_kernels_avx512;
#endif
    default: return NULL;
    }
}

int ggx_batch_isa_available(ggx_batch_isa isa)
{
    if (isa == GGX_ISA_AUTO || isa == GGX_ISA_SCALAR) return 1;
    if (!table_of(isa)) return 0;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    __builtin_cpu_init();
    if (isa == GGX_ISA_AVX2) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (isa == GGX_ISA_AVX512) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#endif
    return 0;
}

static ggx_batch_isa current; /* 0 = not chosen yet */
static int nthreads = 1;

static ggx_batch_isa best(void)
{
    if (ggx_batch_isa_available(GGX_ISA_AVX512)) return GGX_ISA_AVX512;
    if (ggx_batch_isa_available(GGX_ISA_AVX2)) return GGX_ISA_AVX2;
    return GGX_ISA_SCALAR;
}

ggx_status ggx_batch_set_isa(ggx_batch_isa isa)
{
    if (isa == GGX_ISA_AUTO) {
        current = best();
        return GGX_OK;
    }
    if (!ggx_batch_isa_available(isa) || !table_of(isa)) return GGX_ERR_RANGE;
    current = isa;
    return GGX_OK;
}

ggx_batch_isa ggx_batch_get_isa(void)
{
    if (current == GGX_ISA_AUTO) current = best();
    return current;
}

const char *ggx_batch_isa_name(ggx_batch_isa isa)
{
    switch (isa) {
    case GGX_ISA_AUTO: return "auto";
    case GGX_ISA_SCALAR: return "scalar";
    case GGX_ISA_AVX2: return "avx2";
    case GGX_ISA_AVX512: return "avx512";
    }
    return "unknown";
}

ggx_status ggx_batch_set_threads(int threads)
{
    if (threads < 1 || threads > 256) return GGX_ERR_RANGE;
    nthreads = threads;
    return GGX_OK;
}

static const batch_kernels *K(void) { return table_of(ggx_batch_get_isa()); }

static void to_float(fshape *f, const ggx_shape *s, const ggx_fresnel *fr)
{
    memset(f, 0, sizeof *f);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) f->a[i][j] = (float)s->a[i][j], f->ait[i][j] = (float)s->ainv_t[i][j];
    f->an_len = (float)s->an_len;
    f->ndf_scale = (float)s->ndf_scale;
    f->diagonal = s->kind == GGX_SHAPE_DIAGONAL;
    f->fkind = fr ? (int)fr->kind : GGX_FRESNEL_ONE;
    f->feta = fr ? (float)fr->eta : 1.0f;
    f->fk = fr ? (float)fr->k : 0.0f;
    f->ff0 = fr ? (float)fr->f0 : 1.0f;
}

/* A batch call: up to 5 outputs and 7 inputs of floats, offset per chunk, and the kernel call as a switch. */
enum { OP_NDF, OP_G1, OP_PDF_VNDF, OP_SAMPLE_VNDF, OP_SAMPLE_VNDF_ANISO, OP_SAMPLE_NDF, OP_BRDF, OP_SAMPLE_BRDF };
typedef struct job {
    int op;
    const batch_kernels *k;
    const fshape *s;
    float *out[5];
    const float *in[7];
    size_t begin, end;
} job;

static void run(const job *j)
{
    size_t b = j->begin, n = j->end - j->begin;
    float *o[5];
    const float *x[7];
    for (int i = 0; i < 5; i++) o[i] = j->out[i] ? j->out[i] + b : NULL;
    for (int i = 0; i < 7; i++) x[i] = j->in[i] ? j->in[i] + b : NULL;
    switch (j->op) {
    case OP_NDF: j->k->ndf(o[0], n, j->s, x[0], x[1], x[2]); break;
    case OP_G1: j->k->g1(o[0], n, j->s, x[0], x[1], x[2], x[3], x[4], x[5]); break;
    case OP_PDF_VNDF: j->k->pdf_vndf(o[0], n, j->s, x[0], x[1], x[2], x[3], x[4], x[5]); break;
    case OP_SAMPLE_VNDF: j->k->sample_vndf(o[0], o[1], o[2], n, j->s, x[0], x[1], x[2], x[3], x[4]); break;
    case OP_SAMPLE_VNDF_ANISO:
        j->k->sample_vndf_aniso(o[0], o[1], o[2], n, x[5], x[6], x[0], x[1], x[2], x[3], x[4]);
        break;
    case OP_SAMPLE_NDF: j->k->sample_ndf(o[0], o[1], o[2], n, j->s, x[0], x[1]); break;
    case OP_BRDF: j->k->brdf(o[0], n, j->s, x[0], x[1], x[2], x[3], x[4], x[5]); break;
    case OP_SAMPLE_BRDF: j->k->sample_brdf(o[0], o[1], o[2], o[3], o[4], n, j->s, x[0], x[1], x[2], x[3], x[4]); break;
    }
}

static void *thread_main(void *p)
{
    run(p);
    return NULL;
}

enum { THREAD_MIN = 65536 };

/* Runs the job on [0, n): on this thread, or split over nthreads POSIX threads for large n (the calling thread
 * takes the first chunk; a thread that cannot be created is replaced by running its chunk here). */
static void dispatch(job j, size_t n)
{
    int t = nthreads;
    if (t <= 1 || n < THREAD_MIN) {
        j.begin = 0, j.end = n;
        run(&j);
        return;
    }
    job jobs[256];
    pthread_t tid[256];
    int started[256] = {0};
    size_t chunk = (n + (size_t)t - 1) / (size_t)t;
    for (int i = 0; i < t; i++) {
        jobs[i] = j;
        jobs[i].begin = (size_t)i * chunk < n ? (size_t)i * chunk : n;
        jobs[i].end = jobs[i].begin + chunk < n ? jobs[i].begin + chunk : n;
    }
    for (int i = 1; i < t; i++) started[i] = pthread_create(&tid[i], NULL, thread_main, &jobs[i]) == 0;
    run(&jobs[0]);
    for (int i = 1; i < t; i++) {
        if (started[i]) pthread_join(tid[i], NULL);
        else run(&jobs[i]);
    }
}

static job make_job(int op, const fshape *s)
{
    job j;
    memset(&j, 0, sizeof j);
    j.op = op;
    j.k = K();
    j.s = s;
    return j;
}

void ggx_batch_ndf(float *d, size_t n, const ggx_shape *s, const float *mx, const float *my, const float *mz)
{
    fshape f;
    to_float(&f, s, NULL);
    job j = make_job(OP_NDF, &f);
    j.out[0] = d, j.in[0] = mx, j.in[1] = my, j.in[2] = mz;
    dispatch(j, n);
}

void ggx_batch_g1(float *g1, size_t n, const ggx_shape *s, const float *ux, const float *uy, const float *uz,
                  const float *mx, const float *my, const float *mz)
{
    fshape f;
    to_float(&f, s, NULL);
    job j = make_job(OP_G1, &f);
    j.out[0] = g1, j.in[0] = ux, j.in[1] = uy, j.in[2] = uz, j.in[3] = mx, j.in[4] = my, j.in[5] = mz;
    dispatch(j, n);
}

void ggx_batch_pdf_vndf(float *pdf, size_t n, const ggx_shape *s, const float *vx, const float *vy, const float *vz,
                        const float *mx, const float *my, const float *mz)
{
    fshape f;
    to_float(&f, s, NULL);
    job j = make_job(OP_PDF_VNDF, &f);
    j.out[0] = pdf, j.in[0] = vx, j.in[1] = vy, j.in[2] = vz, j.in[3] = mx, j.in[4] = my, j.in[5] = mz;
    dispatch(j, n);
}

void ggx_batch_sample_vndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *vx,
                           const float *vy, const float *vz, const float *u1, const float *u2)
{
    fshape f;
    to_float(&f, s, NULL);
    job j = make_job(OP_SAMPLE_VNDF, &f);
    j.out[0] = mx, j.out[1] = my, j.out[2] = mz, j.in[0] = vx, j.in[1] = vy, j.in[2] = vz, j.in[3] = u1, j.in[4] = u2;
    dispatch(j, n);
}

void ggx_batch_sample_vndf_aniso(float *mx, float *my, float *mz, size_t n, const float *alpha_x,
                                 const float *alpha_y, const float *vx, const float *vy, const float *vz,
                                 const float *u1, const float *u2)
{
    job j = make_job(OP_SAMPLE_VNDF_ANISO, NULL);
    j.out[0] = mx, j.out[1] = my, j.out[2] = mz, j.in[0] = vx, j.in[1] = vy, j.in[2] = vz, j.in[3] = u1, j.in[4] = u2;
    j.in[5] = alpha_x, j.in[6] = alpha_y;
    dispatch(j, n);
}

void ggx_batch_sample_ndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *u1,
                          const float *u2)
{
    fshape f;
    to_float(&f, s, NULL);
    job j = make_job(OP_SAMPLE_NDF, &f);
    j.out[0] = mx, j.out[1] = my, j.out[2] = mz, j.in[0] = u1, j.in[1] = u2;
    dispatch(j, n);
}

void ggx_batch_brdf(float *f_r, size_t n, const ggx_shape *s, const ggx_fresnel *fr, const float *wix,
                    const float *wiy, const float *wiz, const float *wox, const float *woy, const float *woz)
{
    fshape f;
    to_float(&f, s, fr);
    job j = make_job(OP_BRDF, &f);
    j.out[0] = f_r, j.in[0] = wix, j.in[1] = wiy, j.in[2] = wiz, j.in[3] = wox, j.in[4] = woy, j.in[5] = woz;
    dispatch(j, n);
}

void ggx_batch_sample_brdf(float *wox, float *woy, float *woz, float *pdf, float *weight, size_t n,
                           const ggx_shape *s, const ggx_fresnel *fr, const float *wix, const float *wiy,
                           const float *wiz, const float *u1, const float *u2)
{
    fshape f;
    to_float(&f, s, fr);
    job j = make_job(OP_SAMPLE_BRDF, &f);
    j.out[0] = wox, j.out[1] = woy, j.out[2] = woz, j.out[3] = pdf, j.out[4] = weight;
    j.in[0] = wix, j.in[1] = wiy, j.in[2] = wiz, j.in[3] = u1, j.in[4] = u2;
    dispatch(j, n);
}
