/* The batch API: shape conversion to float, run-time instruction-set dispatch resolved once, and threads for large
 * batches. Every function is a loop of batch/loops.inc over the float kernels. SPDX-License-Identifier: MIT */
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>

#include "api/internal.h"
#include "common/parallel.h"
#include "ggx/ggx_batch.h"
#include "internal.h"

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

GGX_API int ggx_batch_isa_available(ggx_batch_isa isa)
{
    if (isa == GGX_ISA_AUTO || isa == GGX_ISA_SCALAR) return 1;
    if (!table_of(isa)) return 0;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    /* __builtin_cpu_supports reads data the loader initialised (GCC's constructor), so it is safe from any thread. */
    if (isa == GGX_ISA_AVX2) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (isa == GGX_ISA_AVX512) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#endif
    return 0;
}

/* The path in use and the thread count: atomics, set once by pthread_once (the best path) and by the setters, so
 * that batch calls from many threads, and setters running beside them, are free of data races. */
static atomic_int current = GGX_ISA_AUTO;
static atomic_int nthreads = 1;
static pthread_once_t chosen = PTHREAD_ONCE_INIT;

static void choose_best(void)
{
    ggx_batch_isa best = GGX_ISA_SCALAR;
    if (ggx_batch_isa_available(GGX_ISA_AVX2)) best = GGX_ISA_AVX2;
    if (ggx_batch_isa_available(GGX_ISA_AVX512)) best = GGX_ISA_AVX512;
    atomic_store(&current, (int)best);
}

GGX_API ggx_status ggx_batch_set_isa(ggx_batch_isa isa)
{
    pthread_once(&chosen, choose_best);
    if (isa == GGX_ISA_AUTO) {
        choose_best();
        return GGX_OK;
    }
    if (!ggx_batch_isa_available(isa) || !table_of(isa)) return GGX_ERR_RANGE;
    atomic_store(&current, (int)isa);
    return GGX_OK;
}

GGX_API ggx_batch_isa ggx_batch_get_isa(void)
{
    pthread_once(&chosen, choose_best);
    return (ggx_batch_isa)atomic_load(&current);
}

GGX_API const char *ggx_batch_isa_name(ggx_batch_isa isa)
{
    switch (isa) {
    case GGX_ISA_AUTO: return "auto";
    case GGX_ISA_SCALAR: return "scalar";
    case GGX_ISA_AVX2: return "avx2";
    case GGX_ISA_AVX512: return "avx512";
    }
    return "unknown";
}

GGX_API ggx_status ggx_batch_set_threads(int threads)
{
    if (threads < 1 || threads > 256) return GGX_ERR_RANGE;
    atomic_store(&nthreads, threads);
    return GGX_OK;
}

typedef struct job {
    batch_loop loop;
    const batch_args *a;
    size_t n, chunk;
} job;

/* chunk k of [0, n) */
static void run_chunk(void *ctx, int k)
{
    const job *j = ctx;
    size_t begin = (size_t)k * j->chunk < j->n ? (size_t)k * j->chunk : j->n;
    size_t end = begin + j->chunk < j->n ? begin + j->chunk : j->n;
    j->loop(j->a, begin, end);
}

enum { THREAD_MIN = 65536 };

/* Runs the loop chosen from the path read once at the start, on [0, n): on this thread, or split into one chunk a
 * thread for large n (the calling thread takes the first chunk). */
static void run(batch_loop loop, const batch_args *a, size_t n)
{
    int t = atomic_load(&nthreads);
    if (t <= 1 || n < THREAD_MIN) {
        loop(a, 0, n);
        return;
    }
    job j = {loop, a, n, (n + (size_t)t - 1) / (size_t)t};
    ggx_internal_parallel_for(t, run_chunk, &j);
}

#define LOOP(name) (table_of(ggx_batch_get_isa())->name)

/* Arguments of one call: the float shape (and Fresnel term), outputs and inputs in order. */
static batch_args args(const ggx_shapef *sf, const ggx_fresnel *f)
{
    batch_args a;
    memset(&a, 0, sizeof a);
    a.s = sf;
    ggx_fresnelf_from(&a.f, GGX_FRESNEL_OR_ONE(f));
    return a;
}

GGX_API void ggx_batch_ndf(float *d, size_t n, const ggx_shape *s, const float *mx, const float *my, const float *mz)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, NULL);
    a.out[0] = d, a.in[0] = mx, a.in[1] = my, a.in[2] = mz;
    run(LOOP(ndf), &a, n);
}

GGX_API void ggx_batch_g1(float *g1, size_t n, const ggx_shape *s, const float *ux, const float *uy, const float *uz,
                          const float *mx, const float *my, const float *mz)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, NULL);
    a.out[0] = g1, a.in[0] = ux, a.in[1] = uy, a.in[2] = uz, a.in[3] = mx, a.in[4] = my, a.in[5] = mz;
    run(LOOP(g1), &a, n);
}

GGX_API void ggx_batch_pdf_vndf(float *pdf, size_t n, const ggx_shape *s, const float *vx, const float *vy,
                                const float *vz, const float *mx, const float *my, const float *mz)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, NULL);
    a.out[0] = pdf, a.in[0] = vx, a.in[1] = vy, a.in[2] = vz, a.in[3] = mx, a.in[4] = my, a.in[5] = mz;
    run(LOOP(pdf_vndf), &a, n);
}

GGX_API ggx_status ggx_batch_sample_normals(ggx_sampler_id sampler, float *mx, float *my, float *mz, size_t n,
                                            const ggx_shape *s, const float *vx, const float *vy, const float *vz,
                                            const float *u1, const float *u2)
{
    const ggx_sampler_info *info = ggx_sampler_get(sampler);
    if (!info || !info->batch || !(info->family == GGX_FAMILY_NDF || info->family == GGX_FAMILY_VNDF))
        return GGX_ERR_RANGE;
    if (!mx || !my || !mz || !s || !u1 || !u2 || (info->family == GGX_FAMILY_VNDF && (!vx || !vy || !vz)))
        return n ? GGX_ERR_NULL : GGX_OK;
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, NULL);
    a.sampler = (int)sampler;
    a.out[0] = mx, a.out[1] = my, a.out[2] = mz, a.in[0] = vx, a.in[1] = vy, a.in[2] = vz, a.in[3] = u1, a.in[4] = u2;
    run(LOOP(normals), &a, n);
    return GGX_OK;
}

GGX_API void ggx_batch_sample_vndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *vx,
                                   const float *vy, const float *vz, const float *u1, const float *u2)
{
    ggx_batch_sample_normals(GGX_SAMPLER_CAPS, mx, my, mz, n, s, vx, vy, vz, u1, u2);
}

GGX_API void ggx_batch_sample_ndf(float *mx, float *my, float *mz, size_t n, const ggx_shape *s, const float *u1,
                                  const float *u2)
{
    ggx_batch_sample_normals(GGX_SAMPLER_STRETCH, mx, my, mz, n, s, NULL, NULL, NULL, u1, u2);
}

GGX_API void ggx_batch_sample_vndf_aniso(float *mx, float *my, float *mz, size_t n, const float *alpha_x,
                                         const float *alpha_y, const float *vx, const float *vy, const float *vz,
                                         const float *u1, const float *u2)
{
    batch_args a = args(NULL, NULL);
    a.out[0] = mx, a.out[1] = my, a.out[2] = mz, a.in[0] = vx, a.in[1] = vy, a.in[2] = vz, a.in[3] = u1, a.in[4] = u2;
    a.in[5] = alpha_x, a.in[6] = alpha_y;
    run(LOOP(normals_aniso), &a, n);
}

GGX_API void ggx_batch_brdf(float *f_r, size_t n, const ggx_shape *s, const ggx_fresnel *fr, const float *wix,
                            const float *wiy, const float *wiz, const float *wox, const float *woy, const float *woz)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, fr);
    a.out[0] = f_r, a.in[0] = wix, a.in[1] = wiy, a.in[2] = wiz, a.in[3] = wox, a.in[4] = woy, a.in[5] = woz;
    run(LOOP(brdf), &a, n);
}

GGX_API void ggx_batch_sample_brdf(float *wox, float *woy, float *woz, float *pdf, float *weight, size_t n,
                                   const ggx_shape *s, const ggx_fresnel *fr, const float *wix, const float *wiy,
                                   const float *wiz, const float *u1, const float *u2)
{
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, fr);
    a.sampler = GGX_SAMPLER_BRDF;
    a.out[0] = wox, a.out[1] = woy, a.out[2] = woz, a.out[3] = pdf, a.out[4] = weight;
    a.in[0] = wix, a.in[1] = wiy, a.in[2] = wiz, a.in[3] = u1, a.in[4] = u2;
    run(LOOP(sample_brdf), &a, n);
}

GGX_API ggx_status ggx_batch_sample_directions(ggx_sampler_id sampler, float *wox, float *woy, float *woz, float *pdf,
                                               float *weight, size_t n, const ggx_shape *s, const ggx_fresnel *fr,
                                               const float *wix, const float *wiy, const float *wiz, const float *u1,
                                               const float *u2)
{
    const ggx_sampler_info *info = ggx_sampler_get(sampler);
    if (!info || !info->batch || info->family != GGX_FAMILY_DIRECTION) return GGX_ERR_RANGE;
    if (!wox || !woy || !woz || !pdf || !weight || !s || !wix || !wiy || !wiz || !u1 || !u2)
        return n ? GGX_ERR_NULL : GGX_OK;
    ggx_shapef sf;
    ggx_shapef_from(&sf, s);
    batch_args a = args(&sf, fr);
    a.sampler = (int)sampler;
    a.out[0] = wox, a.out[1] = woy, a.out[2] = woz, a.out[3] = pdf, a.out[4] = weight;
    a.in[0] = wix, a.in[1] = wiy, a.in[2] = wiz, a.in[3] = u1, a.in[4] = u2;
    run(LOOP(sample_brdf), &a, n);
    return GGX_OK;
}
