/* The image loop of render_tiles.h: the camera of each scene, and the tiles shared among threads, each pixel's
 * samples drawn from streams of their own. SPDX-License-Identifier: MIT */
#include <math.h>
#include <string.h>

#include "common/parallel.h"
#include "ggx/ggx_inline.h"
#include "render_tiles.h"

#define R_DEG (GGX_PI / 180)
#define TILE 16

/* The sphere is seen from 4 units at 10 degrees elevation from -y; the plane from 3.2 units at 35 degrees elevation,
 * azimuth 60 degrees, so that the default sun (azimuth -120, elevation 35) is mirrored at the image's centre. */
render_camera render_camera_make(const render_spec *r)
{
    double elev = r->scene == RENDER_SPHERE ? 10 * R_DEG : 35 * R_DEG;
    double az = r->scene == RENDER_SPHERE ? -90 * R_DEG : 60 * R_DEG;
    double dist = r->scene == RENDER_SPHERE ? 4.0 : 3.2, fov = r->scene == RENDER_SPHERE ? 34 * R_DEG : 50 * R_DEG;
    render_camera c;
    c.pos = ggx_k_v3_d(dist * cos(elev) * cos(az), dist * cos(elev) * sin(az), dist * sin(elev));
    c.fwd = ggx_k_normalize_d(ggx_k_scale_d(c.pos, -1));
    c.right = ggx_k_normalize_d(ggx_k_cross_d(c.fwd, ggx_k_v3_d(0, 0, 1)));
    c.up = ggx_k_cross_d(c.right, c.fwd);
    c.tan_half = tan(fov / 2);
    return c;
}

ggx_vec3 render_camera_dir(const render_spec *r, const render_camera *c, double x, double y)
{
    double aspect = (double)r->width / r->height;
    double sx = (2 * x / r->width - 1) * c->tan_half * aspect, sy = (1 - 2 * y / r->height) * c->tan_half;
    return ggx_k_normalize_d(ggx_k_add_d(c->fwd, ggx_k_add_d(ggx_k_scale_d(c->right, sx), ggx_k_scale_d(c->up, sy))));
}

typedef struct job {
    const render_spec *r;
    render_estimator est;
    const void *ctx;
    render_camera cam;
    float *rgb, *var;
    int tiles_x, tiles;
    int next;        /* the next tile to take (atomic) */
    long done;       /* pixels finished (atomic) */
    long overflowed; /* values beyond the largest float (atomic) */
} job;

static void render_tile(job *j, int tile)
{
    const render_spec *r = j->r;
    int x0 = tile % j->tiles_x * TILE, y0 = tile / j->tiles_x * TILE;
    long over = 0;
    for (int y = y0; y < y0 + TILE && y < r->height; y++)
        for (int x = x0; x < x0 + TILE && x < r->width; x++) {
            uint64_t pixel = (uint64_t)y * (uint64_t)r->width + (uint64_t)x;
            double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
            for (int s = 0; s < r->spp; s++) {
                render_stream rs = {render_mix64(render_mix64(r->seed ^ 0x6a09e667f3bcc909ULL) + pixel) ^
                                    render_mix64((uint64_t)s + 1)};
                double sx = r->jitter ? render_uniform(&rs) : 0.5, sy = r->jitter ? render_uniform(&rs) : 0.5;
                double L[3] = {0, 0, 0};
                j->est(j->ctx, &j->cam, x + sx, y + sy, &rs, L);
                for (int k = 0; k < 3; k++) sum[k] += L[k], sq[k] += L[k] * L[k];
            }
            for (int k = 0; k < 3; k++) {
                double mean = sum[k] / r->spp;
                float m = (float)mean;
                j->rgb[3 * pixel + k] = m;
                over += !isfinite(m);
                if (j->var) {
                    float v = r->spp > 1
                                  ? (float)(fmax(0.0, sq[k] - r->spp * mean * mean) / ((double)r->spp * (r->spp - 1)))
                                  : 0.0f;
                    j->var[3 * pixel + k] = v;
                    over += !isfinite(v);
                }
            }
        }
    long px = (long)((x0 + TILE < r->width ? TILE : r->width - x0) * (y0 + TILE < r->height ? TILE : r->height - y0));
    __atomic_fetch_add(&j->done, px, __ATOMIC_RELAXED);
    if (over) __atomic_fetch_add(&j->overflowed, over, __ATOMIC_RELAXED);
}

/* worker k: tiles taken in turn from the shared counter until none is left; worker 0 (the calling thread) reports
 * progress between its tiles */
static void worker(void *ctx, int k)
{
    job *j = ctx;
    long total = (long)j->r->width * j->r->height;
    for (;;) {
        int t = __atomic_fetch_add(&j->next, 1, __ATOMIC_RELAXED);
        if (t >= j->tiles) return;
        render_tile(j, t);
        if (k == 0 && j->r->progress)
            j->r->progress(j->r->progress_ctx, __atomic_load_n(&j->done, __ATOMIC_RELAXED), total);
    }
}

long render_tiles(const render_spec *r, render_estimator est, const void *ctx, float *rgb, float *var)
{
    job j;
    memset(&j, 0, sizeof j);
    j.r = r, j.est = est, j.ctx = ctx, j.cam = render_camera_make(r), j.rgb = rgb, j.var = var;
    j.tiles_x = (r->width + TILE - 1) / TILE;
    j.tiles = j.tiles_x * ((r->height + TILE - 1) / TILE);
    long total = (long)r->width * r->height;
    ggx_internal_parallel_for(r->threads > j.tiles ? j.tiles : r->threads, worker, &j);
    if (r->progress) r->progress(r->progress_ctx, total, total);
    return j.overflowed;
}
