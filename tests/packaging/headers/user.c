/* A user's translation unit of the inline API: two kernels per precision, the bounded samplers among them (their
 * selects are where compilers' parenthesis warnings bite). Compiled as C and as C++ by tests/packaging/header_matrix.sh with
 * every warning an error. SPDX-License-Identifier: MIT */
#include "ggx/ggx_inline.h"

int user_kernels(const ggx_shape *s, const ggx_fresnel *f, float *out);

int user_kernels(const ggx_shape *s, const ggx_fresnel *f, float *out)
{
    ggx_shapef sf;
    ggx_fresnelf ff;
    ggx_shapef_from(&sf, s);
    ggx_fresnelf_from(&ff, f);
    ggx_vec3f vf = {0.6f, 0.0f, 0.8f};
    ggx_samplef a = ggx_sample_brdf_bounded_f(&sf, &ff, vf, 0.25f, 0.75f);
    ggx_samplef b = ggx_sample_brdf_bounded_azimuth_f(&sf, &ff, vf, 0.25f, 0.75f);
    ggx_vec3 vd = {0.6, 0.0, 0.8};
    ggx_sample c = ggx_sample_brdf_bounded_d(s, f, vd, 0.25, 0.75);
    out[0] = a.pdf;
    out[1] = b.pdf;
    out[2] = (float)c.pdf;
    out[3] = ggx_ndf_f(&sf, vf);
    return a.event == GGX_EVENT_REFLECT;
}

/* The fit's header beside it: its types and declarations in every language mode. */
#include "ggx/ggx_fit.h"

int user_fit(ggx_shape *out, const ggx_vec3 *m, size_t n);

int user_fit(ggx_shape *out, const ggx_vec3 *m, size_t n)
{
    ggx_fit_options opt = {GGX_FIT_ANISOTROPIC, 100, 1e-6, 1, NULL, NULL, 0};
    ggx_fit_info info;
    ggx_heightfield_options hopt = {0, 2};
    (void)hopt;
    return ggx_fit_normals(out, m, NULL, n, &opt, &info) == GGX_OK && info.best == GGX_FIT_ELLIPSOID;
}

/* The filter's header too. */
#include "ggx/ggx_filter.h"

int user_filter(ggx_shape *out, const ggx_shape *lobes, size_t n);

int user_filter(ggx_shape *out, const ggx_shape *lobes, size_t n)
{
    ggx_filter_options opt = {100, 1e-8, 8, 16, 1};
    ggx_filter_info info;
    double params[GGX_LOBE_PARAMS];
    (void)params;
    return ggx_filter_lobes(out, lobes, NULL, n, &opt, &info) == GGX_OK && info.converged;
}
