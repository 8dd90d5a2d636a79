/*
 * libggx CUDA build: every public float kernel of ggx_inline.h in a __global__ grid-stride loop
 * over struct-of-arrays inputs, the same per-element code run on the host, and its double twin as a reference (see
 * ggx_cuda.h). The samplers come from GGX_SAMPLER_LIST, so a new line of the registry is compiled for the device
 * here without an edit.
 *
 * Built with warnings on and as errors under GGX_WERROR; without --expt-relaxed-constexpr (the kernels call no
 * constexpr host function) and without fast math (the kernels assume IEEE arithmetic: nvcc's defaults keep float
 * division and square root correctly rounded and denormals; only FMA contraction differs from the host).
 * SPDX-License-Identifier: MIT
 */
#include <cuda_runtime.h>

#include <stdio.h>
#include <string.h>

#include "ggx_cuda.h"

/* ---- per-element code: op_<name><P>::run(a, i) reads element i of a's inputs and writes element i of its outputs;
 * P = 32 runs the float kernels (device and host), P = 64 their double twins (host, the reference) ---- */

/* The double twin of ggx_cuda_args: the same inputs (floats, widened exactly), double outputs. */
typedef struct args_d {
    ggx_shape s;
    ggx_fresnel f;
    double eta;
    int mode;
    unsigned seed;
    size_t n;
    const float *in[GGX_CUDA_MAX_IN];
    double *out[GGX_CUDA_MAX_OUT];
} args_d;

#define IN(k) a.in[k][i]
#define DIR(k) FN(k_v3)(IN(k), IN((k) + 1), IN((k) + 2))

template <class A, class V> static __host__ __device__ inline void put3(const A &a, size_t i, V v)
{
    a.out[0][i] = v.x, a.out[1][i] = v.y, a.out[2][i] = v.z;
}
template <class A, class V> static __host__ __device__ inline void put2(const A &a, size_t i, V v)
{
    a.out[0][i] = v.x, a.out[1][i] = v.y;
}
template <class A, class S> static __host__ __device__ inline void put_sample(const A &a, size_t i, S r)
{
    put3(a, i, r.w);
    a.out[3][i] = r.pdf, a.out[4][i] = r.weight, a.out[5][i] = (float)r.event;
}
template <class V, class A> static __host__ __device__ inline V dir_at(const A &a, size_t i, int k)
{
    V v;
    v.x = a.in[k][i], v.y = a.in[k + 1][i], v.z = a.in[k + 2][i];
    return v;
}

/* The rejection samplers' source of numbers: a counter-based generator, so that every element (on the device a
 * thread) has its own stream from (seed, element) with no state in memory, and the host replays the same stream.
 * Each number is the SplitMix64 mix (Steele, Lea and Flood 2014) of key + count * golden gamma, cut to 24 bits so
 * that the float the kernel converts it to is exact. */
typedef struct counter_rng {
    unsigned long long key;
    unsigned long long count;
} counter_rng;

extern "C" {
static __host__ __device__ double counter_uniform(void *state)
{
    counter_rng *r = (counter_rng *)state;
    unsigned long long z = r->key + ++r->count * 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 40) * (1.0 / 16777216.0); /* in [0, 1) */
}
}

/* Evaluations: name, input layout, what they use beyond the shape, the expression for element i (FN(x) names the
 * kernel ggx_x_f or ggx_x_d). */
#define GGX_CUDA_EVALS(X)                                                                                              \
    X(ndf, DIR, 0, FN(ndf)(&a.s, DIR(0)))                                                                              \
    X(ndf_spherical, PAIR, 0, FN(ndf_spherical)(&a.s, IN(0), IN(1)))                                                   \
    X(p22, PAIR, 0, FN(p22)(&a.s, IN(0), IN(1)))                                                                       \
    X(gaussian_curvature, DIR, 0, FN(gaussian_curvature)(&a.s, DIR(0)))                                                \
    X(projected_area, DIR, 0, FN(projected_area)(&a.s, DIR(0)))                                                        \
    X(lune_area, DIR2, 0, FN(lune_area)(&a.s, DIR(0), DIR(3)))                                                         \
    X(lambda, DIR, GGX_CUDA_SIGNED, FN(lambda)(&a.s, DIR(0)))                                                          \
    X(g1_smith, DIR, 0, FN(g1_smith)(&a.s, DIR(0)))                                                                    \
    X(g1, DIR2, 0, FN(g1)(&a.s, DIR(0), DIR(3)))                                                                       \
    X(g2, DIR3, 0, FN(g2)(&a.s, DIR(0), DIR(3), DIR(6)))                                                               \
    X(g2_height_correlated, DIR3, 0, FN(g2_height_correlated)(&a.s, DIR(0), DIR(3), DIR(6)))                           \
    X(pdf_vndf, DIR2, 0, FN(pdf_vndf)(&a.s, DIR(0), DIR(3)))                                                           \
    X(pdf_ndf, DIR, 0, FN(pdf_ndf)(&a.s, DIR(0)))                                                                      \
    X(fresnel_eval, SCALAR, GGX_CUDA_USES_FRESNEL, FN(fresnel_eval)(&a.f, IN(0)))                                      \
    X(fresnel_dielectric_eval, SCALAR, GGX_CUDA_USES_ETA, FN(fresnel_dielectric_eval)(IN(0), a.eta))                   \
    X(fresnel_conductor_eval, SCALAR, GGX_CUDA_USES_FRESNEL, FN(fresnel_conductor_eval)(IN(0), a.f.eta, a.f.k))        \
    X(fresnel_schlick_eval, SCALAR, GGX_CUDA_USES_FRESNEL, FN(fresnel_schlick_eval)(IN(0), a.f.f0))                    \
    X(jacobian_reflect, DIR2, 0, FN(jacobian_reflect)(DIR(0), DIR(3)))                                                 \
    X(jacobian_refract, DIR3, GGX_CUDA_USES_ETA, FN(jacobian_refract)(DIR(0), DIR(3), DIR(6), 1, a.eta))               \
    X(brdf_eval, DIR2, GGX_CUDA_USES_FRESNEL, FN(brdf_eval)(&a.s, &a.f, DIR(0), DIR(3)))                               \
    X(bsdf_eval, DIR2, GGX_CUDA_USES_ETA | GGX_CUDA_USES_MODE,                                                         \
      FN(bsdf_eval)(&a.s, a.eta, DIR(0), DIR(3), (ggx_transport)a.mode))                                               \
    X(pdf_brdf, DIR2, 0, FN(pdf_brdf)(&a.s, DIR(0), DIR(3)))                                                           \
    X(pdf_bsdf, DIR2, GGX_CUDA_USES_ETA, FN(pdf_bsdf)(&a.s, a.eta, DIR(0), DIR(3)))

/* Kernels with other outputs: name, input layout, output layout, uses, forward map, the statement for element i. */
#define GGX_CUDA_VECTORS(X)                                                                                            \
    X(half_reflect, DIR2, VEC, 0, NULL, put3(a, i, FN(half_reflect)(DIR(0), DIR(3))))                                  \
    X(half_refract, DIR2, VEC, GGX_CUDA_USES_ETA, NULL, put3(a, i, FN(half_refract)(DIR(0), DIR(3), 1, a.eta)))        \
    X(reflect, DIR2, VEC, 0, NULL, put3(a, i, FN(reflect)(DIR(0), DIR(3))))                                            \
    X(refract, DIR2, REFRACT, GGX_CUDA_USES_ETA, NULL, refract_at(a, i, FN(refract)))                                  \
    X(disk_polar, PAIR, POINT, 0, NULL, put2(a, i, FN(disk_polar)(IN(0), IN(1))))                                      \
    X(disk_concentric, PAIR, POINT, 0, NULL, put2(a, i, FN(disk_concentric)(IN(0), IN(1))))                            \
    X(disk_polar_inv, POINT, UV, 0, "disk_polar", put2(a, i, FN(disk_polar_inv)(FN(k_v2)(IN(0), IN(1)))))              \
    X(disk_concentric_inv, POINT, UV, 0, "disk_concentric",                                                            \
      put2(a, i, FN(disk_concentric_inv)(FN(k_v2)(IN(0), IN(1)))))                                                     \
    X(sample_ndf, PAIR, NORMAL, 0, NULL, put3(a, i, FN(sample_ndf)(&a.s, IN(0), IN(1))))                               \
    X(sample_vndf, VIEW_U2, VNORMAL, 0, NULL, put3(a, i, FN(sample_vndf)(&a.s, DIR(0), IN(3), IN(4))))

/* ggx_refract_*: the direction and the success flag. */
template <class A, class V, class R>
static __host__ __device__ inline void refract_at(const A &a, size_t i, int (*fn)(V, V, R, V *))
{
    V t;
    int ok = fn(dir_at<V>(a, i, 0), dir_at<V>(a, i, 3), a.eta, &t);
    put3(a, i, t);
    a.out[3][i] = (float)ok;
}

/* The two signatures of direction samplers, told apart by overloading: a registry line of family DIRECTION whose
 * kernel has either signature needs no edit here (another signature fails to compile, at draw()). */
template <class Smp, class S, class F, class V, class R, class A>
static __host__ __device__ inline Smp draw(Smp (*fn)(const S *, const F *, V, R, R), const A &a, size_t i)
{
    return fn(&a.s, &a.f, dir_at<V>(a, i, 0), a.in[3][i], a.in[4][i]);
}
template <class Smp, class S, class V, class R, class A>
static __host__ __device__ inline Smp draw(Smp (*fn)(const S *, R, V, R, R, R, ggx_transport), const A &a, size_t i)
{
    return fn(&a.s, a.eta, dir_at<V>(a, i, 0), a.in[3][i], a.in[4][i], a.in[5][i], (ggx_transport)a.mode);
}
template <class Smp, class S, class F, class V, class R>
static constexpr ggx_cuda_in draw_in(Smp (*)(const S *, const F *, V, R, R))
{
    return GGX_CUDA_IN_VIEW_U2;
}
template <class Smp, class S, class V, class R>
static constexpr ggx_cuda_in draw_in(Smp (*)(const S *, R, V, R, R, R, ggx_transport))
{
    return GGX_CUDA_IN_VIEW_U3;
}
template <class Smp, class S, class F, class V, class R>
static constexpr int draw_uses(Smp (*)(const S *, const F *, V, R, R))
{
    return GGX_CUDA_USES_FRESNEL;
}
template <class Smp, class S, class V, class R>
static constexpr int draw_uses(Smp (*)(const S *, R, V, R, R, R, ggx_transport))
{
    return GGX_CUDA_USES_ETA | GGX_CUDA_USES_MODE;
}

/* The samplers of the registry: one op per sampler, and one per inverse map where the registry lists one. */
#define GGX_CUDA_SAMPLER_OPS(ID, name, stem, family, domain, inverse, batch, help)                                     \
    GGX_CUDA_SAMPLE_OP_##family(stem) GGX_CUDA_INVERSE_OP_##family##_##inverse(stem)
#define GGX_CUDA_SAMPLE_OP_NDF(stem) GGX_CUDA_OP(stem, put3(a, i, FN(stem)(&a.s, IN(0), IN(1))))
#define GGX_CUDA_SAMPLE_OP_VNDF(stem) GGX_CUDA_OP(stem, put3(a, i, FN(stem)(&a.s, DIR(0), IN(3), IN(4))))
#define GGX_CUDA_SAMPLE_OP_REJECTION(stem)                                                                             \
    GGX_CUDA_OP(stem, counter_rng r = {((unsigned long long)a.seed << 32) ^ i, 0}; unsigned trials = 0;                \
                put3(a, i, FN(stem)(&a.s, DIR(0), counter_uniform, &r, &trials)); a.out[3][i] = (float)trials)
#define GGX_CUDA_SAMPLE_OP_DIRECTION(stem) GGX_CUDA_OP(stem, put_sample(a, i, draw(FN(stem), a, i)))
#define GGX_CUDA_INVERSE_OP_NDF_1(stem) GGX_CUDA_OP(stem##_inv, put2(a, i, FN(stem##_inv)(&a.s, DIR(0))))
#define GGX_CUDA_INVERSE_OP_VNDF_1(stem) GGX_CUDA_OP(stem##_inv, put2(a, i, FN(stem##_inv)(&a.s, DIR(0), DIR(3))))
#define GGX_CUDA_INVERSE_OP_NDF_0(stem)
#define GGX_CUDA_INVERSE_OP_VNDF_0(stem)
#define GGX_CUDA_INVERSE_OP_REJECTION_0(stem)
#define GGX_CUDA_INVERSE_OP_DIRECTION_0(stem)

/* Each op is a class template over the precision, declared once and defined for 32 and 64 below. */
#define GGX_CUDA_OP(name, ...)                                                                                         \
    template <> struct op_##name<PREC> {                                                                               \
        static __host__ __device__ void run(const ARGS &a, size_t i) { __VA_ARGS__; }                                  \
    };
#define GGX_CUDA_EVAL_OP(name, in, uses, expr) GGX_CUDA_OP(name, a.out[0][i] = (expr))
#define GGX_CUDA_VECTOR_OP(name, in, out, uses, forward, stmt) GGX_CUDA_OP(name, stmt)

#define GGX_CUDA_DECL(name) template <int P> struct op_##name;
#define GGX_CUDA_EVAL_DECL(name, in, uses, expr) GGX_CUDA_DECL(name)
#define GGX_CUDA_VECTOR_DECL(name, in, out, uses, forward, stmt) GGX_CUDA_DECL(name)
#define GGX_CUDA_SAMPLER_DECL(ID, name, stem, family, domain, inverse, batch, help)                                    \
    GGX_CUDA_DECL(stem) GGX_CUDA_INVERSE_DECL_##inverse(stem)
#define GGX_CUDA_INVERSE_DECL_1(stem) GGX_CUDA_DECL(stem##_inv)
#define GGX_CUDA_INVERSE_DECL_0(stem)
GGX_CUDA_EVALS(GGX_CUDA_EVAL_DECL)
GGX_CUDA_VECTORS(GGX_CUDA_VECTOR_DECL)
GGX_SAMPLER_LIST(GGX_CUDA_SAMPLER_DECL)

#define PREC 32
#define ARGS ggx_cuda_args
#define FN(x) ggx_##x##_f
GGX_CUDA_EVALS(GGX_CUDA_EVAL_OP)
GGX_CUDA_VECTORS(GGX_CUDA_VECTOR_OP)
GGX_SAMPLER_LIST(GGX_CUDA_SAMPLER_OPS)
#undef PREC
#undef ARGS
#undef FN

#define PREC 64
#define ARGS args_d
#define FN(x) ggx_##x##_d
GGX_CUDA_EVALS(GGX_CUDA_EVAL_OP)
GGX_CUDA_VECTORS(GGX_CUDA_VECTOR_OP)
GGX_SAMPLER_LIST(GGX_CUDA_SAMPLER_OPS)
#undef PREC
#undef ARGS
#undef FN

/* ---- the loops ---- */

/* A grid-stride loop: any n with any grid; the launch below uses one thread per element up to 2^16 blocks. */
template <class Op> __global__ void ggx_cuda_loop(ggx_cuda_args a)
{
    size_t stride = (size_t)gridDim.x * blockDim.x;
    for (size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x; i < a.n; i += stride) Op::run(a, i);
}

template <class Op> static void host_loop(const ggx_cuda_args *a)
{
    for (size_t i = 0; i < a->n; i++) Op::run(*a, i);
}

template <class Op> static int launch(const ggx_cuda_args *a)
{
    const unsigned threads = 128;
    size_t blocks = (a->n + threads - 1) / threads;
    if (blocks == 0) return (int)cudaSuccess;
    ggx_cuda_loop<Op><<<(unsigned)(blocks < 65536 ? blocks : 65536), threads>>>(*a);
    return (int)cudaGetLastError();
}

/* The reference sees exactly what the float kernels see: the float shape (ggx_shapef, normalised) widened field by
 * field, the Fresnel term with its index in double (the float kernels keep it too), the float index ratio. */
template <class Op> static void reference_loop(const ggx_cuda_args *a, double *const *out)
{
    args_d d;
    memset(&d, 0, sizeof d);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) d.s.a[r][c] = a->s.a[r][c], d.s.ainv_t[r][c] = a->s.ainv_t[r][c];
    d.s.det = a->s.det, d.s.an_len = a->s.an_len, d.s.ndf_scale = a->s.ndf_scale, d.s.kind = a->s.kind;
    d.s.an.x = 0, d.s.an.y = 0, d.s.an.z = a->s.an_len;
    d.s.alpha_x = a->s.alpha_x, d.s.alpha_y = a->s.alpha_y;
    d.s.tangent_cos = a->s.tangent_cos, d.s.tangent_sin = a->s.tangent_sin;
    d.f.kind = a->f.kind, d.f.eta = a->f.eta_wide, d.f.k = a->f.k, d.f.f0 = a->f.f0;
    d.eta = a->eta, d.mode = a->mode, d.seed = a->seed, d.n = a->n;
    for (int c = 0; c < GGX_CUDA_MAX_IN; c++) d.in[c] = a->in[c];
    for (int c = 0; c < GGX_CUDA_MAX_OUT; c++) d.out[c] = out[c];
    for (size_t i = 0; i < d.n; i++) Op::run(d, i);
}

/* ---- the table ---- */

#define GGX_CUDA_ROW(name, in, out, uses, forward)                                                                     \
    {#name,                                                                                                            \
     in,                                                                                                               \
     GGX_CUDA_OUT_##out,                                                                                               \
     uses,                                                                                                             \
     forward,                                                                                                          \
     host_loop<op_##name<32>>,                                                                                         \
     launch<op_##name<32>>,                                                                                            \
     reference_loop<op_##name<64>>},
#define GGX_CUDA_EVAL_ROW(name, in, uses, expr) GGX_CUDA_ROW(name, GGX_CUDA_IN_##in, EVAL, uses, NULL)
#define GGX_CUDA_VECTOR_ROW(name, in, out, uses, forward, stmt) GGX_CUDA_ROW(name, GGX_CUDA_IN_##in, out, uses, forward)
#define GGX_CUDA_SAMPLER_ROWS(ID, name, stem, family, domain, inverse, batch, help)                                    \
    GGX_CUDA_SAMPLE_ROW_##family(stem) GGX_CUDA_INVERSE_ROW_##family##_##inverse(stem)
#define GGX_CUDA_SAMPLE_ROW_NDF(stem) GGX_CUDA_ROW(stem, GGX_CUDA_IN_PAIR, NORMAL, 0, NULL)
#define GGX_CUDA_SAMPLE_ROW_VNDF(stem) GGX_CUDA_ROW(stem, GGX_CUDA_IN_VIEW_U2, VNORMAL, 0, NULL)
#define GGX_CUDA_SAMPLE_ROW_REJECTION(stem) GGX_CUDA_ROW(stem, GGX_CUDA_IN_VIEW, REJECT, 0, NULL)
#define GGX_CUDA_SAMPLE_ROW_DIRECTION(stem)                                                                            \
    GGX_CUDA_ROW(stem, draw_in(ggx_##stem##_f), SAMPLE, draw_uses(ggx_##stem##_f), NULL)
#define GGX_CUDA_INVERSE_ROW_NDF_1(stem) GGX_CUDA_ROW(stem##_inv, GGX_CUDA_IN_NORMAL, UV, 0, #stem)
#define GGX_CUDA_INVERSE_ROW_VNDF_1(stem) GGX_CUDA_ROW(stem##_inv, GGX_CUDA_IN_VIEW_NORMAL, UV, 0, #stem)
#define GGX_CUDA_INVERSE_ROW_NDF_0(stem)
#define GGX_CUDA_INVERSE_ROW_VNDF_0(stem)
#define GGX_CUDA_INVERSE_ROW_REJECTION_0(stem)
#define GGX_CUDA_INVERSE_ROW_DIRECTION_0(stem)

extern "C" const ggx_cuda_kernel ggx_cuda_kernels[] = {
    GGX_CUDA_EVALS(GGX_CUDA_EVAL_ROW) GGX_CUDA_VECTORS(GGX_CUDA_VECTOR_ROW) GGX_SAMPLER_LIST(GGX_CUDA_SAMPLER_ROWS)};
extern "C" const int ggx_cuda_kernel_count = (int)(sizeof ggx_cuda_kernels / sizeof ggx_cuda_kernels[0]);

/* ---- host side ---- */

extern "C" int ggx_cuda_in_columns(ggx_cuda_in in)
{
    switch (in) {
    case GGX_CUDA_IN_DIR: return 3;
    case GGX_CUDA_IN_DIR2: return 6;
    case GGX_CUDA_IN_DIR3: return 9;
    case GGX_CUDA_IN_SCALAR: return 1;
    case GGX_CUDA_IN_PAIR: return 2;
    case GGX_CUDA_IN_POINT: return 2;
    case GGX_CUDA_IN_VIEW_U2: return 5;
    case GGX_CUDA_IN_VIEW_U3: return 6;
    case GGX_CUDA_IN_VIEW: return 3;
    case GGX_CUDA_IN_NORMAL: return 3;
    case GGX_CUDA_IN_VIEW_NORMAL: return 6;
    }
    return 0;
}

extern "C" int ggx_cuda_out_columns(ggx_cuda_out out)
{
    switch (out) {
    case GGX_CUDA_OUT_EVAL: return 1;
    case GGX_CUDA_OUT_VEC: return 3;
    case GGX_CUDA_OUT_NORMAL: return 3;
    case GGX_CUDA_OUT_VNORMAL: return 3;
    case GGX_CUDA_OUT_REJECT: return 4;
    case GGX_CUDA_OUT_SAMPLE: return 6;
    case GGX_CUDA_OUT_REFRACT: return 4;
    case GGX_CUDA_OUT_POINT: return 2;
    case GGX_CUDA_OUT_UV: return 2;
    }
    return 0;
}

static void say(char *why, size_t len, const char *what, cudaError_t e)
{
    if (why && len) snprintf(why, len, "%s: %s (%s)", what, cudaGetErrorString(e), cudaGetErrorName(e));
}

extern "C" int ggx_cuda_device_check(char *why, size_t why_len)
{
    int count = 0;
    cudaError_t e = cudaGetDeviceCount(&count);
    /* No GPU, or no driver (a machine with the toolkit only): nothing to run on, not a failure. */
    if (e == cudaErrorNoDevice || e == cudaErrorInsufficientDriver || (e == cudaSuccess && count == 0)) {
        say(why, why_len, "no CUDA device or driver", e == cudaSuccess ? cudaErrorNoDevice : e);
        return 0;
    }
    if (e != cudaSuccess) {
        say(why, why_len, "cudaGetDeviceCount", e);
        return -1;
    }
    cudaDeviceProp p;
    e = cudaGetDeviceProperties(&p, 0);
    if (e != cudaSuccess) {
        say(why, why_len, "cudaGetDeviceProperties", e);
        return -1;
    }
    /* The build's code (CMAKE_CUDA_ARCHITECTURES) must run on this device: ask the runtime for one loop's image. */
    cudaFuncAttributes fa;
    e = cudaFuncGetAttributes(&fa, ggx_cuda_loop<op_ndf<32>>);
    if (e != cudaSuccess) {
        char what[400];
        snprintf(what, sizeof what, "device 0 (%s, sm_%d%d) has no code of this build (CMAKE_CUDA_ARCHITECTURES)",
                 p.name, p.major, p.minor);
        say(why, why_len, what, e);
        return -1;
    }
    if (why && why_len)
        snprintf(why, why_len, "device 0: %s, sm_%d%d, code sm_%d", p.name, p.major, p.minor, fa.binaryVersion);
    return 1;
}

extern "C" int ggx_cuda_run_device(const ggx_cuda_kernel *k, const ggx_cuda_args *a, char *why, size_t why_len)
{
    int nin = ggx_cuda_in_columns(k->in), nout = ggx_cuda_out_columns(k->out);
    size_t bytes = a->n * sizeof(float);
    float *buf = NULL;
    ggx_cuda_args d = *a;
    /* one allocation for every column */
    cudaError_t e = cudaMalloc((void **)&buf, (bytes ? bytes : 1) * (size_t)(nin + nout));
    if (e != cudaSuccess) {
        say(why, why_len, "cudaMalloc", e);
        return -1;
    }
    for (int c = 0; c < nin && e == cudaSuccess; c++) {
        d.in[c] = buf + (size_t)c * a->n;
        e = cudaMemcpy(buf + (size_t)c * a->n, a->in[c], bytes, cudaMemcpyHostToDevice);
    }
    for (int c = 0; c < nout; c++) d.out[c] = buf + (size_t)(nin + c) * a->n;
    if (e == cudaSuccess) e = (cudaError_t)k->launch(&d);
    if (e == cudaSuccess) e = cudaDeviceSynchronize();
    for (int c = 0; c < nout && e == cudaSuccess; c++)
        e = cudaMemcpy(a->out[c], d.out[c], bytes, cudaMemcpyDeviceToHost);
    if (e != cudaSuccess) say(why, why_len, k->name, e);
    cudaFree(buf);
    return e == cudaSuccess ? 0 : -1;
}
