/*
 * libggx CUDA build: every public float kernel of ggx_inline.h in a __global__ loop over arrays (src/cuda/loops.cu),
 * with the same per-element code callable on the host, and its double twin (the _d kernels on the same inputs) as a
 * reference, so that a test can compare the three. Not part of libggx and not installed: it is the CUDA compile
 * check and the harness of tests/cuda/test_cuda.c. Plain C, so that the test is C11 like the rest of the
 * suite. SPDX-License-Identifier: MIT
 */
#ifndef GGX_CUDA_H
#define GGX_CUDA_H

#include <stddef.h>

#include "ggx/ggx_inline.h"
#include "ggx/ggx_samplers.h"

#ifdef __cplusplus
extern "C" {
#endif

#define GGX_CUDA_MAX_IN 9
#define GGX_CUDA_MAX_OUT 6

/* One launch: a shape, a Fresnel term, an index and a transport mode shared by all elements, and struct-of-arrays
 * inputs and outputs of n floats (device pointers in a launch, host pointers on the host). */
typedef struct ggx_cuda_args {
    ggx_shapef s;
    ggx_fresnelf f;
    float eta;     /* bsdf, refraction: the index ratio */
    int mode;      /* bsdf: ggx_transport */
    unsigned seed; /* rejection samplers: the key of the per-element generator */
    size_t n;
    const float *in[GGX_CUDA_MAX_IN];
    float *out[GGX_CUDA_MAX_OUT];
} ggx_cuda_args;

/* What a kernel reads, in input columns. */
typedef enum ggx_cuda_in {
    GGX_CUDA_IN_DIR,        /* a direction (3) */
    GGX_CUDA_IN_DIR2,       /* two directions (6): (u, m), (v, m), (wi, wo), (w, m) */
    GGX_CUDA_IN_DIR3,       /* three directions (9): (wi, wo, m), (wi, wo, h) */
    GGX_CUDA_IN_SCALAR,     /* one number (1): a cosine */
    GGX_CUDA_IN_PAIR,       /* two numbers (2): (u1, u2), (theta, phi), slopes */
    GGX_CUDA_IN_POINT,      /* a point of the unit disk (2) from the forward map */
    GGX_CUDA_IN_VIEW_U2,    /* a view and (u1, u2) (5) */
    GGX_CUDA_IN_VIEW_U3,    /* a view and (u1, u2, u3) (6) */
    GGX_CUDA_IN_VIEW,       /* a view (3), the random numbers from the per-element generator */
    GGX_CUDA_IN_NORMAL,     /* a normal from the forward sampler (3) */
    GGX_CUDA_IN_VIEW_NORMAL /* a view and a normal from the forward sampler for that view (6) */
} ggx_cuda_in;

/* What a kernel writes, in output columns, and how the test compares and checks them. */
typedef enum ggx_cuda_out {
    GGX_CUDA_OUT_EVAL,    /* a value (1) */
    GGX_CUDA_OUT_VEC,     /* a vector (3) */
    GGX_CUDA_OUT_NORMAL,  /* a sampled normal (3): unit with z >= 0, or zero */
    GGX_CUDA_OUT_VNORMAL, /* a sampled visible normal (3): also m.v >= 0 for the view in input columns 0-2 */
    GGX_CUDA_OUT_REJECT,  /* a visible normal (3) and the number of candidates drawn (1) */
    GGX_CUDA_OUT_SAMPLE,  /* a direction sample: w (3), pdf, weight, event (1 each) */
    GGX_CUDA_OUT_REFRACT, /* a refracted direction (3) and the success flag (1) */
    GGX_CUDA_OUT_POINT,   /* a point of the unit disk (2) */
    GGX_CUDA_OUT_UV       /* (u1, u2) of an inverse map (2) */
} ggx_cuda_out;

/* What a kernel needs beyond the shape (the configurations the test runs it under), and SIGNED for the one
 * evaluation that may be negative (ggx_lambda). */
enum { GGX_CUDA_USES_FRESNEL = 1, GGX_CUDA_USES_ETA = 2, GGX_CUDA_USES_MODE = 4, GGX_CUDA_SIGNED = 8 };

typedef struct ggx_cuda_kernel {
    const char *name; /* the stem: ggx_<name>_f */
    ggx_cuda_in in;
    ggx_cuda_out out;
    int uses;            /* GGX_CUDA_USES_*, GGX_CUDA_SIGNED */
    const char *forward; /* inverse maps (IN_POINT, IN_NORMAL, IN_VIEW_NORMAL): the map they invert; else NULL */
    void (*host)(const ggx_cuda_args *a);  /* the per-element code, run on the host over [0, n) */
    int (*launch)(const ggx_cuda_args *a); /* the __global__ loop on the current device; a cudaError_t */
    /* The double kernels on the same inputs, shape and parameters (the float shape, Fresnel term and index widened
     * exactly), written to out[0 .. columns - 1][0 .. n - 1]; a->out is not used. */
    void (*reference)(const ggx_cuda_args *a, double *const *out);
} ggx_cuda_kernel;

/* Every kernel, generated in part from GGX_SAMPLER_LIST. */
extern const ggx_cuda_kernel ggx_cuda_kernels[];
extern const int ggx_cuda_kernel_count;

/* Input and output columns of a layout. */
int ggx_cuda_in_columns(ggx_cuda_in in);
int ggx_cuda_out_columns(ggx_cuda_out out);

/* Whether a CUDA device can run the kernels: 1 if so; 0 with the reason in why when there is no device or driver
 * (the test skips); -1 with the reason on any other error (the test fails). Prints nothing. */
int ggx_cuda_device_check(char *why, size_t why_len);

/* Runs k on the device: copies a's inputs (host arrays of a->n floats) to the device, launches, copies the outputs
 * back into a's output arrays. 0 on success, else -1 with the CUDA error in why. */
int ggx_cuda_run_device(const ggx_cuda_kernel *k, const ggx_cuda_args *a, char *why, size_t why_len);

#ifdef __cplusplus
}
#endif

#endif /* GGX_CUDA_H */
