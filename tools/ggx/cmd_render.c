/* ggx render: an image of a sphere or a plane of the material (render.h), as PNG (tone-mapped, with a caption), OpenEXR
 * or PFM (linear). SPDX-License-Identifier: MIT */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cmd_render.h"
#include "surface.h"

#define CAPTION_MIN_WIDTH 256
#define CAPTION_FONT 10.0
#define CAPTION_LINES 5

static void on_progress(void *ctx, long done, long total)
{
    int *last = ctx, pc = (int)(100.0 * (double)done / (double)total);
    if (pc == *last) return;
    *last = pc;
    progress_show("render", done, total);
}

typedef enum out_kind { OUT_PNG, OUT_EXR, OUT_PFM } out_kind;

static out_kind out_kind_of(const char *path)
{
    if (path_has_ext(path, ".exr")) return OUT_EXR;
    if (path_has_ext(path, ".pfm")) return OUT_PFM;
    if (path_has_ext(path, ".png") || path_is_stream(path)) return OUT_PNG; /* standard output, a device: PNG */
    die("--out '%s': give a .png (tone-mapped), .exr or .pfm (linear) name", path);
}

/* The light of --light: sky, white, point:THETA,PHI[,E] or an environment file. Words for the caption in words. */
static void light_from_options(const options *o, render_spec *r, render_env *env, char *words, size_t n)
{
    const char *l = o->light ? o->light : "sky";
    char err[400];
    if (strcmp(l, "sky") == 0) {
        if (render_env_default_sky(env, err, sizeof err) != 0) die("--light sky: %s", err);
        snprintf(words, n, "built-in sky, sun at 35° elevation, azimuth −120°, 1.5° radius");
    } else if (strcmp(l, "white") == 0) {
        if (render_env_white(env, 1.0, err, sizeof err) != 0) die("--light white: %s", err);
        snprintf(words, n, "uniform white environment, L = 1 (the furnace)");
    } else if (strncmp(l, "point:", 6) == 0) {
        double v[3];
        parse_light_point(l, &r->light_dir, v);
        r->light = RENDER_LIGHT_DIRECTIONAL;
        r->light_irradiance = v[2];
        snprintf(words, n, "distant light from θ %g°, φ %g°, irradiance %g", v[0], v[1], v[2]);
        return;
    } else {
        surface s;
        surface_read_options ro = {SURFACE_RADIANCE, 0};
        if (surface_read(l, &ro, &s, err, sizeof err) != 0) die("--light: %s", err);
        if (s.nx > 65536 || s.ny > 65536) die("--light '%s': too large", l);
        long neg = 0;
        float *rgb = s.rgb, peak = 0.0f;
        for (size_t i = 0; i < 3 * s.nx * s.ny; i++)
            if (rgb[i] > peak) peak = rgb[i];
        if (peak > 0.0f && peak < FLT_MIN)
            fprintf(stderr,
                    "ggx: note: the brightest radiance of '%s' is %g, a subnormal float (below %g): it keeps fewer "
                    "digits, and so does the image\n",
                    l, (double)peak, (double)FLT_MIN);
        s.rgb = NULL;
        int w = (int)s.nx, h = (int)s.ny;
        surface_free(&s);
        int rc = render_env_init(env, w, h, rgb, &neg, err, sizeof err);
        if (neg) fprintf(stderr, "ggx: note: %ld negative values of '%s' read as 0\n", neg, l);
        if (rc != 0) die("--light '%s': %s", l, err);
        const char *base = strrchr(l, '/');
        snprintf(words, n, "environment %s (%d × %d)", base ? base + 1 : l, w, h);
    }
    r->light = RENDER_LIGHT_ENV;
    r->env = env;
}

static void render_help(void)
{
    printf("usage: ggx render [shape] [--fresnel F] [--scene sphere|plane] [--light "
           "sky|white|FILE|point:THETA,PHI[,E]]\n"
           "                  [--spp N] [--size W[xH]] [--compensate] [--sampler NAME] [--strategy mis|light|bsdf]\n"
           "                  [--depth N] [--exposure EV] [--threads N] [--seed S] [--out FILE]\n"
           "       ggx render --volume [shape] [--density RHO] [--phase specular|diffuse] [--albedo A|R,G,B]\n"
           "                  [--scatter N] [--light ...] [--spp N] ...: the unit sphere filled with SGGX flakes\n"
           "       ggx render --normal-map FILE ...: a normal map's filtered chain against its ground truth\n"
           "                  (ggx render --normal-map x --help)\n\n"
           "An image of a unit sphere (default) or an infinite plane made of the material, path traced with the\n"
           "library's BSDFs, samplers and pdfs.\n"
           "  --fresnel F      one (default), conductor:ETA,K or schlick:F0: a reflector; dielectric:ETA: rough "
           "glass\n"
           "                   (light refracted through the sphere and out; below the plane nothing comes back)\n"
           "  --scene          sphere: x of the shape along the parallels (east), y to the north pole, seen from\n"
           "                   -y, 10 degrees up; plane: z = 0, x along world x, seen from azimuth 60, 35 up\n"
           "  --light          sky (default): a built-in clear sky with a sun at 35 degrees elevation, azimuth -120;\n"
           "                   white: the uniform environment L = 1; FILE: a latitude-longitude environment in\n"
           "                   OpenEXR, Radiance .hdr or PFM (row 0 at the zenith +z, column 0 at phi = 0 (+x),\n"
           "                   phi towards +y; NaN or infinite values are refused, negative ones read as 0);\n"
           "                   point:THETA,PHI[,E]: a distant light from that direction, irradiance E (default 1)\n"
           "  --spp N          samples per pixel (default 64);  --size W[xH] pixels (default 256)\n"
           "  --compensate     add the multiple-scattering lobes (energy compensation; seconds of setup for\n"
           "                   anisotropic and skewed shapes)\n"
           "  --sampler NAME   how a reflector samples directions (default brdf-bounded; any sampler but bsdf;\n"
           "                   samplers of normals reflect the view); the glass always uses bsdf\n"
           "  --strategy       mis (default): light and BSDF samples by the power heuristic; light, bsdf: one\n"
           "  --depth N        the most surface interactions of a path (default 32)\n"
           "  --volume         a medium of flakes S = A^T A of the shape, in world coordinates (unskewed: flakes\n"
           "                   facing the zenith), filling the sphere: --density RHO flakes per unit volume\n"
           "                   (default 1; extinction RHO sigma(d)), --phase specular (default) or diffuse,\n"
           "                   --albedo A or R,G,B in [0, 1] (default 1), --scatter N the most scattering events\n"
           "                   of a path (default 256; 1: single scattering); environment lights only\n"
           "  --exposure EV    PNG only: the image is sRGB of min(1, 2^EV L) per channel (clamped, default 0)\n"
           "  --threads N      default: the processors online; the image is the same for any N and one --seed\n"
           "  --out FILE       .png (8-bit sRGB, and below it a caption when W >= %d), .exr (linear float RGB)\n"
           "                   or .pfm (linear float RGB); default render.png; - writes PNG to standard output\n\n"
           "%s\n",
           CAPTION_MIN_WIDTH, SHAPE_HELP);
    print_samplers(stdout);
}

static const command_spec RENDER_SPEC = {
    SHAPE_OPTS ",fresnel,scene,light,spp,size,compensate,sampler,strategy,depth,exposure,threads,seed,"
               "out,progress,no-progress,volume,density,phase,albedo,scatter",
    render_help, 0};

int cmd_render(int argc, char **argv)
{
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--normal-map") == 0 || strncmp(argv[i], "--normal-map=", 13) == 0)
            return render_normal_map(argc, argv); /* a normal map's filtered chain against its ground truth */
    options o;
    if (!command_options(&RENDER_SPEC, argc, argv, 2, &o)) return 0;
    render_spec r;
    render_spec_defaults(&r);
    shape_from_options(&o, &r.shape);
    r.fresnel = fresnel_from_options(&o);
    const char *path = o.out ? o.out : "render.png";
    out_kind kind = out_kind_of(path);
    if (o.scene && strcmp(o.scene, "sphere") != 0 && strcmp(o.scene, "plane") != 0)
        die("--scene: unknown scene '%s' (sphere, plane)", o.scene);
    r.scene = o.scene && strcmp(o.scene, "plane") == 0 ? RENDER_PLANE : RENDER_SPHERE;
    if (o.strategy && strcmp(o.strategy, "mis") != 0 && strcmp(o.strategy, "light") != 0 &&
        strcmp(o.strategy, "bsdf") != 0)
        die("--strategy: unknown strategy '%s' (mis, light, bsdf)", o.strategy);
    r.strategy = !o.strategy || o.strategy[0] == 'm' ? RENDER_MIS
                 : o.strategy[0] == 'l'              ? RENDER_LIGHT_ONLY
                                                     : RENDER_BSDF_ONLY;
    r.width = o.size ? o.size : 256;
    r.height = o.size_h ? o.size_h : r.width;
    r.spp = (int)o.spp;
    r.depth = o.depth;
    r.seed = o.seed;
    r.compensate = o.compensate;
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    r.threads = o.threads ? o.threads : cpus >= 1 && cpus <= 256 ? (int)cpus : 1;
    if (o.sampler) r.sampler = find_sampler(o.sampler);
    if (r.sampler && r.sampler->id >= GGX_SAMPLER_COUNT)
        die("sampler '%s' is not in the library's registry", o.sampler);
    render_volume vol;
    render_volume_defaults(&vol);
    if (!o.volume && (o.density >= 0 || o.albedo[0] >= 0 || o.phase || o.scatter))
        die("--density, --phase, --albedo and --scatter describe the medium of --volume");
    if (o.volume && (o.fresnel || o.compensate || o.sampler))
        die("--volume renders flakes: --fresnel, --compensate and --sampler are a surface's");
    if (o.density >= 0) vol.density = o.density;
    if (o.albedo[0] >= 0) memcpy(vol.albedo, o.albedo, sizeof vol.albedo);
    vol.phase = phase_is_diffuse(&o) ? RENDER_PHASE_DIFFUSE : RENDER_PHASE_SPECULAR;
    if (o.scatter) vol.scatter = o.scatter;
    render_env env;
    memset(&env, 0, sizeof env);
    char light_words[200], err[400];
    light_from_options(&o, &r, &env, light_words, sizeof light_words);
    if ((o.volume ? render_volume_prepare(&vol, &r, err, sizeof err) : render_prepare(&r, err, sizeof err)) != 0)
        die("%s", err);
    int last = -1;
    if (progress_wanted(o.progress)) r.progress = on_progress, r.progress_ctx = &last;
    size_t count = (size_t)r.width * (size_t)r.height * 3;
    float *rgb = malloc(count * sizeof *rgb);
    if (!rgb) die("out of memory for a %d x %d image", r.width, r.height);
    long over = o.volume ? render_volume_image(&r, &vol, rgb, NULL) : render_image(&r, rgb, NULL);
    if (r.progress) fputc('\n', stderr);
    if (over)
        die("the image does not fit single precision: %ld pixel values exceed the largest float (%g) with this light "
            "(%s); lower its radiance or irradiance",
            over, (double)FLT_MAX, light_words);
    float brightest = 0.0f;
    for (size_t i = 0; i < count; i++) brightest = fmaxf(brightest, rgb[i]);
    /* the PNG's first 8-bit level: sRGB 0.5 / 255, linear 0.5 / 255 / 12.92 */
    if (kind == OUT_PNG && brightest > 0.0f && exp2(o.exposure) * brightest < 0.5 / 255.0 / 12.92)
        fprintf(stderr,
                "ggx: note: the PNG is black: the image's brightest value is %g, below its first 8-bit level at "
                "--exposure %g (write .exr or .pfm for the linear values)\n",
                (double)brightest, o.exposure);
    surface img;
    memset(&img, 0, sizeof img);
    img.kind = SURFACE_RADIANCE, img.nx = (size_t)r.width, img.ny = (size_t)r.height, img.rgb = rgb;
    if (kind == OUT_PNG) {
        int caption = r.width >= CAPTION_MIN_WIDTH;
        int band = caption ? (int)ceil(CAPTION_LINES * 1.45 * CAPTION_FONT + 8) : 0;
        canvas c;
        canvas_open_file(&c, path, FMT_PNG, r.width, r.height + band, 0);
        paint_linear_rgb(c.cr, 0, 0, 1, rgb, r.width, r.height, o.exposure);
        if (caption) {
            char shape[200], mat[200], cam[200], line[400];
            char l0[480];
            shape_caption(&o, shape, sizeof shape);
            render_material_words(&r, mat, sizeof mat);
            if (o.volume)
                snprintf(mat, sizeof mat, "SGGX flakes, ρ %g, %s phase, albedo %g,%g,%g", vol.density,
                         vol.phase == RENDER_PHASE_DIFFUSE ? "diffuse" : "specular", vol.albedo[0], vol.albedo[1],
                         vol.albedo[2]);
            render_camera_words(&r, cam, sizeof cam);
            const char *frame = o.volume ? "flakes of S = AᵀA in world coordinates, filling the unit sphere"
                                         : render_frame_words(r.scene);
            const char *lines[CAPTION_LINES] = {l0, frame, light_words, cam, line};
            snprintf(l0, sizeof l0, "%s  ·  %s", shape, mat);
            snprintf(line, sizeof line, "%d spp, sampler %s, %s, depth %d, seed %llu  ·  sRGB of min(1, 2^%g L)", r.spp,
                     o.volume                                                      ? "phase"
                     : r.compensate && !(r.fresnel.kind == GGX_FRESNEL_DIELECTRIC) ? "brdf-compensated"
                                                                                   : r.sampler->name,
                     r.strategy == RENDER_MIS          ? "MIS"
                     : r.strategy == RENDER_LIGHT_ONLY ? "light samples only"
                                                       : "BSDF samples only",
                     o.volume ? vol.scatter : r.depth, (unsigned long long)r.seed, o.exposure);
            set_rgb(c.cr, c.th->fg);
            double font = CAPTION_FONT * fmin(1.0, r.width / 560.0);
            text_font(c.cr, font, 0);
            for (int i = 0; i < CAPTION_LINES; i++)
                text_at(c.cr, 6, r.height + 5 + (i + 0.75) * 1.45 * CAPTION_FONT, 0, 0.5, lines[i]);
        }
        canvas_close_file(&c);
    } else {
        unsigned char *data;
        size_t n;
        int rc = kind == OUT_EXR ? surface_encode_exr(&img, &data, &n, err, sizeof err)
                                 : surface_encode_pfm(&img, &data, &n, err, sizeof err);
        if (rc != 0) die("cannot write '%s': %s", path, err);
        out_write_file(path, data, n);
        free(data);
    }
    free(rgb);
    render_release(&r);
    render_env_free(&env);
    return 0;
}
