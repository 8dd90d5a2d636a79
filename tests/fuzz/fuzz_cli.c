/* libFuzzer target: the ggx command's parsers (options, numbers, shape syntax, directions, a distant light, Fresnel,
 * sampler names, with the sampler's domain and view checks) fed from raw bytes split into arguments at NUL bytes.
 * die() jumps back instead of exiting. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

#define ALL_OPTS                                                                                                       \
    "alpha,skew,rotate,matrix,wi,wo,view,n,seed,out,format,sampler,figure,fresnel,eta,size,log,claim,progress,no-"     \
    "progress,light,spp,depth,level,threads"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 4096) return 0;
    char *buf = malloc(size + 1);
    memcpy(buf, data, size);
    buf[size] = '\0';
    char *argv[40] = {"ggx", "fuzz"};
    int argc = 2;
    for (char *p = buf; p < buf + size && argc < 39;) {
        argv[argc++] = p;
        p += strlen(p) + 1;
    }
    argv[argc] = NULL;
    jmp_buf jb;
    cli_die_jump = &jb;
    if (setjmp(jb) == 0) {
        options o;
        parse_options(argc, argv, 2, &o, ALL_OPTS);
        ggx_shape s;
        shape_from_options(&o, &s);
        if (!(s.det > 0)) abort();
        ggx_fresnel f = fresnel_from_options(&o);
        if (!(ggx_fresnel_eval(&f, 0.5) >= 0 && ggx_fresnel_eval(&f, 0.5) <= 1)) abort();
        if (o.light) { /* the one syntax of a distant light: a unit direction and an irradiance >= 0 */
            ggx_vec3 d;
            double v[3];
            parse_light_point(o.light, &d, v);
            if (!(fabs(d.x * d.x + d.y * d.y + d.z * d.z - 1) < 1e-12 && v[2] >= 0)) abort();
        }
        if (o.sampler) { /* the name, then the shape and view against the sampler's registry entry */
            const ggx_sampler_info *smp = find_sampler(o.sampler);
            require_domain(smp, &s);
            if (o.have_view) require_view(smp, o.view);
        }
        if (o.have_view && !(fabs(o.view.x * o.view.x + o.view.y * o.view.y + o.view.z * o.view.z - 1) < 1e-12))
            abort();
    }
    /* every argument on its own as a direction */
    for (int i = 2; i < argc; i++) {
        if (setjmp(jb) == 0) {
            ggx_vec3 v;
            parse_direction(argv[i], &v);
            if (!(isfinite(v.x) && isfinite(v.y) && isfinite(v.z))) abort();
        }
    }
    cli_die_jump = NULL;
    free(buf);
    return 0;
}
