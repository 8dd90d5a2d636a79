/* OpenEXR surfaces through the OpenEXR C core library (OpenEXRCore): part 0 of a scanline or tiled file (level 0 of
 * a mipmap or ripmap), any compression the library decodes (OpenEXRCore 3.1 decodes none, RLE, ZIPS, ZIP, PIZ, PXR24,
 * B44 and B44A, not DWAA or DWAB), channels of type HALF, FLOAT or UINT. Heights are the channel "Y", else "Z", else
 * the file's first channel; a normal map is R, G and optionally B, components stored directly in [-1, 1]; radiance
 * is R, G, B (or a grey image's Y, else its first channel, for all three). Subsampled
 * channels are skipped over in files compressed as bytes (none, RLE, ZIP) and refused elsewhere. Written as a
 * scanline file with ZIP compression (16 lines a chunk) in FLOAT: heights in one channel "Y" (times z_scale where it
 * is set) with their grid spacing dx, dy (where set) in the header attribute "spacing" (v2d, in the heights' unit,
 * read back as dx, dy with z_scale 1), normals and radiance in R, G, B. SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#ifdef GGX_HAVE_EXR
#include <openexr.h>

#define EXR_MAX_SIDE 65536
/* a chunk that decompresses to more than this is refused before the library allocates it */
#define EXR_MAX_CHUNK_BYTES ((uint64_t)1 << 30)
#define EXR_UNREADABLE "not a readable OpenEXR file (corrupt or truncated)"
/* the header attribute (v2d) of a height field's grid spacing along x and y, in the unit of its heights */
#define EXR_SPACING_ATTR "spacing"

typedef struct exr_mem {
    const unsigned char *p;
    size_t n;
} exr_mem;

static int64_t exr_mem_read(exr_const_context_t ctx, void *user, void *buf, uint64_t sz, uint64_t off,
                            exr_stream_error_func_ptr_t error_cb)
{
    (void)ctx, (void)error_cb;
    const exr_mem *m = user;
    if (off >= (uint64_t)m->n) return 0;
    uint64_t left = (uint64_t)m->n - off;
    if (sz > left) sz = left;
    memcpy(buf, m->p + off, (size_t)sz);
    return (int64_t)sz;
}

static int64_t exr_mem_size(exr_const_context_t ctx, void *user)
{
    (void)ctx;
    const exr_mem *m = user;
    return m->n > (size_t)INT64_MAX ? -1 : (int64_t)m->n;
}

/* the library's errors are not printed: the caller says what failed, in one line */
static void exr_quiet(exr_const_context_t ctx, exr_result_t code, const char *msg) { (void)ctx, (void)code, (void)msg; }

typedef struct exr_reader {
    exr_context_t ctx;
    exr_decode_pipeline_t dec;
    int dec_ready;
    exr_compression_t comp;
    int nwant;         /* channels wanted: 1 (heights), 2 or 3 (normals) */
    int want[3];       /* their indices in the part's channel list */
    size_t nx, ny;     /* the data window */
    size_t rows_alloc; /* rows held by s->h or s->m so far */
    const surface_read_options *o;
    surface *s;
    uint8_t dummy[16];
} exr_reader;

static int exr_find_channel(const exr_attr_chlist_t *cl, const char *name)
{
    for (int i = 0; i < cl->num_channels; i++)
        if (cl->entries[i].name.str && strcmp(cl->entries[i].name.str, name) == 0) return i;
    return -1;
}

/* Grows s->h or s->m to hold at least `rows` rows (geometrically, capped at ny): memory follows the data actually
 * decoded, so a header that claims a huge image over a few bytes costs nothing. */
static int exr_grow(exr_reader *r, size_t rows)
{
    if (rows <= r->rows_alloc) return 0;
    size_t want = r->rows_alloc * 2;
    if (want < rows) want = rows;
    if (want < 64) want = 64;
    if (want > r->ny) want = r->ny;
    surface *o = r->s;
    size_t elem = o->kind == SURFACE_HEIGHTS   ? sizeof *o->h
                  : o->kind == SURFACE_NORMALS ? sizeof *o->m
                                               : 3 * sizeof *o->rgb;
    if (want > SIZE_MAX / elem / r->nx) return -1;
    void **slot = o->kind == SURFACE_HEIGHTS   ? (void **)&o->h
                  : o->kind == SURFACE_NORMALS ? (void **)&o->m
                                               : (void **)&o->rgb;
    void *p = realloc(*slot, want * r->nx * elem);
    if (!p) return -1;
    *slot = p;
    r->rows_alloc = want;
    return 0;
}

static double exr_half(uint16_t h)
{
    int e = (h >> 10) & 31, m = h & 1023;
    double v = e == 0 ? ldexp((double)m, -24) : e == 31 ? (m ? NAN : INFINITY) : ldexp((double)(m + 1024), e - 25);
    return h & 0x8000 ? -v : v;
}

/* One sample as stored in the file (little-endian) */
static double exr_sample(const uint8_t *p, int type)
{
    if (type == EXR_PIXEL_HALF) return exr_half((uint16_t)(p[0] | p[1] << 8));
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    if (type == EXR_PIXEL_UINT) return (double)u;
    float f;
    memcpy(&f, &u, sizeof f);
    return (double)f;
}

static const char *exr_compression_name(exr_compression_t c)
{
    static const char *const names[] = {"none", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
    return (unsigned)c < sizeof names / sizeof *names ? names[c] : "unknown";
}

static int exr_type_bytes(int type) { return type == EXR_PIXEL_HALF ? 2 : 4; }

/* Decodes one chunk into s: its top-left pixel is (px, py) within the data window and it must cover w x h pixels
 * from there. The library reads and decompresses the chunk; its samples are then taken from the decompressed block
 * (per line, each channel's samples in the channel list's order) with every offset checked against the block's
 * size. (The library's own unpacking is not used: OpenEXRCore 3.1 writes through the pointer of a skipped channel
 * when it converts half to float.) Returns 0, or -1 with err. */
static int exr_decode_chunk(exr_reader *r, const exr_chunk_info_t *ci, size_t px, size_t py, size_t w, size_t h,
                            char *err, size_t errn)
{
    if (ci->width <= 0 || ci->height <= 0 || px >= r->nx || py >= r->ny || w < 1 || h < 1 || w > r->nx - px ||
        h > r->ny - py || h > (size_t)ci->height || ci->packed_size == 0 || ci->unpacked_size == 0 ||
        (r->comp == EXR_COMPRESSION_NONE && ci->packed_size != ci->unpacked_size))
        return surface_fail(err, errn, EXR_UNREADABLE);
    if (ci->unpacked_size > EXR_MAX_CHUNK_BYTES || ci->packed_size > EXR_MAX_CHUNK_BYTES)
        return surface_fail(err, errn, "an OpenEXR chunk of %llu bytes: too large",
                            (unsigned long long)ci->unpacked_size);
    exr_result_t rv = r->dec_ready ? exr_decoding_update(r->ctx, 0, ci, &r->dec)
                                   : exr_decoding_initialize(r->ctx, 0, ci, &r->dec);
    if (rv != EXR_ERR_SUCCESS) return surface_fail(err, errn, EXR_UNREADABLE);
    r->dec_ready = 1;
    exr_decode_pipeline_t *d = &r->dec;
    if (d->channel_count < 1 || !d->channels) return surface_fail(err, errn, EXR_UNREADABLE);
    for (int k = 0; k < r->nwant; k++)
        if (r->want[k] >= d->channel_count || d->channels[r->want[k]].width < 0 ||
            (size_t)d->channels[r->want[k]].width < w)
            return surface_fail(err, errn, EXR_UNREADABLE);
    /* the default routines give the read and decompress steps; one channel is marked for output with a pixel stride
     * that rules out the library's direct read (which would bypass the decompressed block), then unpacking is off */
    for (int i = 0; i < d->channel_count; i++) d->channels[i].decode_to_ptr = NULL;
    exr_coding_channel_info_t *c0 = &d->channels[r->want[0]];
    c0->decode_to_ptr = r->dummy;
    c0->user_data_type = c0->data_type;
    c0->user_bytes_per_element = (int16_t)exr_type_bytes(c0->data_type);
    c0->user_pixel_stride = 2 * c0->user_bytes_per_element;
    c0->user_line_stride = 0;
    rv = exr_decoding_choose_default_routines(r->ctx, 0, d);
    c0->decode_to_ptr = NULL;
    if (rv != EXR_ERR_SUCCESS || !d->read_fn) return surface_fail(err, errn, EXR_UNREADABLE);
    d->unpack_and_convert_fn = NULL;
    rv = exr_decoding_run(r->ctx, 0, d);
    if (rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED)
        return surface_fail(err, errn, "this OpenEXR library does not decode the file's compression (%s)",
                            exr_compression_name(r->comp));
    if (rv != EXR_ERR_SUCCESS || !d->unpacked_buffer) return surface_fail(err, errn, EXR_UNREADABLE);
    if (exr_grow(r, py + h) != 0) return surface_fail(err, errn, "out of memory");
    const uint8_t *block = d->unpacked_buffer;
    uint64_t size = ci->unpacked_size, off = 0;
    for (int32_t line = 0; line < ci->height; line++) {
        int64_t y = (int64_t)ci->start_y + line; /* (tiled files carry no subsampled channels) */
        uint64_t at[3] = {0, 0, 0};
        for (int c = 0; c < d->channel_count; c++) {
            const exr_coding_channel_info_t *ch = &d->channels[c];
            if (ch->y_samples > 1 && y % ch->y_samples != 0) continue;
            for (int k = 0; k < r->nwant; k++)
                if (r->want[k] == c) at[k] = off;
            if (ch->width < 0) return surface_fail(err, errn, EXR_UNREADABLE);
            off += (uint64_t)ch->width * (uint64_t)exr_type_bytes(ch->data_type);
            if (off > size) return surface_fail(err, errn, EXR_UNREADABLE);
        }
        if ((size_t)line >= h) continue;
        for (size_t x = 0; x < w; x++) {
            size_t i = (py + (size_t)line) * r->nx + px + x;
            double v[3];
            for (int k = 0; k < r->nwant; k++) {
                int type = d->channels[r->want[k]].data_type;
                v[k] = exr_sample(block + at[k] + x * (size_t)exr_type_bytes(type), type);
            }
            if (r->s->kind == SURFACE_HEIGHTS) r->s->h[i] = v[0];
            else if (r->s->kind == SURFACE_NORMALS) r->s->m[i] = surface_texel_normal(v, r->nwant, r->o->y_down);
            else
                for (int k = 0; k < 3; k++) r->s->rgb[3 * i + k] = (float)v[r->nwant == 3 ? k : 0];
        }
    }
    return 0;
}

static int exr_read_scanlines(exr_reader *r, const exr_attr_box2i_t *dw, char *err, size_t errn)
{
    int64_t y = dw->min.y, end = (int64_t)dw->max.y + 1;
    while (y < end) {
        exr_chunk_info_t ci;
        if (exr_read_scanline_chunk_info(r->ctx, 0, (int)y, &ci) != EXR_ERR_SUCCESS)
            return surface_fail(err, errn, EXR_UNREADABLE);
        int64_t first = ci.start_y, next = (int64_t)ci.start_y + ci.height;
        if (ci.height <= 0 || first > y || next <= y || first < dw->min.y)
            return surface_fail(err, errn, EXR_UNREADABLE);
        size_t py = (size_t)(first - dw->min.y), rows = (size_t)(next - first);
        if (rows > r->ny - py) rows = r->ny - py;
        if (exr_decode_chunk(r, &ci, 0, py, r->nx, rows, err, errn) != 0) return -1;
        y = next;
    }
    return 0;
}

static int exr_read_tiles(exr_reader *r, char *err, size_t errn)
{
    int32_t tw = 0, th = 0, lw = 0, lh = 0;
    if (exr_get_tile_sizes(r->ctx, 0, 0, 0, &tw, &th) != EXR_ERR_SUCCESS ||
        exr_get_level_sizes(r->ctx, 0, 0, 0, &lw, &lh) != EXR_ERR_SUCCESS || tw <= 0 || th <= 0)
        return surface_fail(err, errn, EXR_UNREADABLE);
    if ((size_t)lw != r->nx || (size_t)lh != r->ny) return surface_fail(err, errn, EXR_UNREADABLE);
    size_t ntx = (r->nx + (size_t)tw - 1) / (size_t)tw, nty = (r->ny + (size_t)th - 1) / (size_t)th;
    for (size_t ty = 0; ty < nty; ty++) {
        for (size_t tx = 0; tx < ntx; tx++) {
            exr_chunk_info_t ci;
            if (exr_read_tile_chunk_info(r->ctx, 0, (int)tx, (int)ty, 0, 0, &ci) != EXR_ERR_SUCCESS)
                return surface_fail(err, errn, EXR_UNREADABLE);
            size_t px = tx * (size_t)tw, py = ty * (size_t)th;
            size_t w = r->nx - px < (size_t)tw ? r->nx - px : (size_t)tw;
            size_t h = r->ny - py < (size_t)th ? r->ny - py : (size_t)th;
            if (exr_decode_chunk(r, &ci, px, py, w, h, err, errn) != 0) return -1;
        }
    }
    return 0;
}

/* Everything after the context is open: the part's layout, the channels wanted, then the chunks. */
static int exr_parse_part(exr_reader *r, size_t n, char *err, size_t errn)
{
    int parts = 0;
    exr_storage_t storage;
    exr_attr_box2i_t dw;
    const exr_attr_chlist_t *cl = NULL;
    int32_t chunks = 0;
    if (exr_get_count(r->ctx, &parts) != EXR_ERR_SUCCESS || parts < 1 ||
        exr_get_storage(r->ctx, 0, &storage) != EXR_ERR_SUCCESS ||
        exr_get_data_window(r->ctx, 0, &dw) != EXR_ERR_SUCCESS || exr_get_channels(r->ctx, 0, &cl) != EXR_ERR_SUCCESS ||
        !cl || cl->num_channels < 1 || !cl->entries || exr_get_compression(r->ctx, 0, &r->comp) != EXR_ERR_SUCCESS)
        return surface_fail(err, errn, EXR_UNREADABLE);
    if (storage == EXR_STORAGE_DEEP_SCANLINE || storage == EXR_STORAGE_DEEP_TILED)
        return surface_fail(err, errn, "a deep OpenEXR image is not a surface");
    if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) return surface_fail(err, errn, EXR_UNREADABLE);
    int64_t w = (int64_t)dw.max.x - dw.min.x + 1, h = (int64_t)dw.max.y - dw.min.y + 1;
    /* a height field needs its neighbours; a normal map (or radiance) may be one texel */
    if (w < 1 || h < 1 || ((w < 2 || h < 2) && r->o->want == SURFACE_HEIGHTS))
        return surface_fail(err, errn, "%lld x %lld pixels: a height field needs at least 2 x 2", (long long)w,
                            (long long)h);
    if (w > EXR_MAX_SIDE || h > EXR_MAX_SIDE)
        return surface_fail(err, errn, "%lld x %lld pixels: too large (at most %d a side)", (long long)w, (long long)h,
                            EXR_MAX_SIDE);
    r->nx = (size_t)w, r->ny = (size_t)h;
    if (r->nx > SIZE_MAX / r->ny || r->nx * r->ny > SIZE_MAX / sizeof(ggx_vec3))
        return surface_fail(err, errn, "%lld x %lld pixels: too large", (long long)w, (long long)h);
    /* each chunk has an 8-byte entry in the offset table: more chunks than that fits are a truncated file */
    if (exr_get_chunk_count(r->ctx, 0, &chunks) != EXR_ERR_SUCCESS || chunks < 1 || (uint64_t)chunks > n / 8)
        return surface_fail(err, errn, EXR_UNREADABLE);
    if (r->o->want == SURFACE_HEIGHTS) {
        int k = exr_find_channel(cl, "Y");
        if (k < 0) k = exr_find_channel(cl, "Z");
        if (k < 0) k = 0;
        r->want[0] = k, r->nwant = 1;
        r->s->kind = SURFACE_HEIGHTS;
        r->s->channels = cl->num_channels; /* the file's: a caller that wants one channel alone can refuse more */
        /* the grid spacing, where the file states it (surface_encode_exr's "spacing"): heights in its unit */
        exr_attr_v2d_t sp;
        if (exr_attr_get_v2d(r->ctx, 0, EXR_SPACING_ATTR, &sp) == EXR_ERR_SUCCESS && isfinite(sp.x) && isfinite(sp.y) &&
            sp.x > 0.0 && sp.y > 0.0)
            r->s->dx = sp.x, r->s->dy = sp.y, r->s->z_scale = 1.0;
    } else if (r->o->want == SURFACE_RADIANCE) {
        /* R, G, B; else a grey image's Y (or its first channel) for all three */
        r->want[0] = exr_find_channel(cl, "R"), r->want[1] = exr_find_channel(cl, "G");
        r->want[2] = exr_find_channel(cl, "B");
        r->nwant = 3;
        if (r->want[0] < 0 || r->want[1] < 0 || r->want[2] < 0) {
            int k = exr_find_channel(cl, "Y");
            r->want[0] = k < 0 ? 0 : k, r->nwant = 1;
        }
        r->s->kind = SURFACE_RADIANCE;
    } else {
        r->want[0] = exr_find_channel(cl, "R"), r->want[1] = exr_find_channel(cl, "G");
        r->want[2] = exr_find_channel(cl, "B");
        if (r->want[0] < 0 || r->want[1] < 0) return surface_fail(err, errn, "no R and G channels for a normal map");
        r->nwant = r->want[2] < 0 ? 2 : 3;
        r->s->kind = SURFACE_NORMALS;
        r->s->channels = r->nwant;
    }
    for (int k = 0; k < r->nwant; k++) {
        const exr_attr_chlist_entry_t *e = &cl->entries[r->want[k]];
        if (e->pixel_type != EXR_PIXEL_HALF && e->pixel_type != EXR_PIXEL_FLOAT && e->pixel_type != EXR_PIXEL_UINT)
            return surface_fail(err, errn, EXR_UNREADABLE);
        if (e->x_sampling != 1 || e->y_sampling != 1)
            return surface_fail(err, errn, "OpenEXR channel '%s' is subsampled (not supported)",
                                e->name.str ? e->name.str : "");
    }
    /* subsampled channels: not valid in tiled files, and only taken with the compressions that treat a chunk as
     * bytes (OpenEXRCore 3.1's B44 reads past its buffer on them; PIZ, PXR24 and DWA also work per channel) */
    for (int i = 0; i < cl->num_channels; i++) {
        if (cl->entries[i].x_sampling == 1 && cl->entries[i].y_sampling == 1) continue;
        if (storage == EXR_STORAGE_TILED)
            return surface_fail(err, errn, "a tiled OpenEXR file with subsampled channels (not valid)");
        if (r->comp != EXR_COMPRESSION_NONE && r->comp != EXR_COMPRESSION_RLE && r->comp != EXR_COMPRESSION_ZIPS &&
            r->comp != EXR_COMPRESSION_ZIP)
            return surface_fail(err, errn, "an OpenEXR file with subsampled channels in %s compression (not supported)",
                                exr_compression_name(r->comp));
    }
    int rc = storage == EXR_STORAGE_SCANLINE ? exr_read_scanlines(r, &dw, err, errn) : exr_read_tiles(r, err, errn);
    if (rc == 0 && r->rows_alloc != r->ny) rc = surface_fail(err, errn, EXR_UNREADABLE);
    return rc;
}

int surface_parse_exr(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn)
{
    exr_mem m = {data, n};
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_quiet;
    init.user_data = &m;
    init.read_fn = exr_mem_read;
    init.size_fn = exr_mem_size;
    init.flags = EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE | EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    exr_reader r;
    memset(&r, 0, sizeof r);
    r.o = o, r.s = s;
    s->h = NULL, s->m = NULL, s->rgb = NULL;
    s->nx = s->ny = 0;
    s->dx = s->dy = 0, s->z_scale = 0, s->bits = 0, s->channels = 0;
    if (!data || n < 4 || exr_start_read(&r.ctx, "<memory>", &init) != EXR_ERR_SUCCESS) {
        if (r.ctx) exr_finish(&r.ctx);
        return surface_fail(err, errn, EXR_UNREADABLE);
    }
    int rc = exr_parse_part(&r, n, err, errn);
    if (r.dec_ready) exr_decoding_destroy(r.ctx, &r.dec);
    exr_finish(&r.ctx);
    if (rc != 0) {
        free(s->h), free(s->m), free(s->rgb);
        s->h = NULL, s->m = NULL, s->rgb = NULL;
        s->nx = s->ny = 0;
        return -1;
    }
    s->nx = r.nx, s->ny = r.ny;
    return 0;
}

/* The file's bytes, gathered in memory: the library writes the offset table last, at an earlier offset. */
typedef struct exr_sink {
    unsigned char *p;
    size_t n, cap;
    int failed;
} exr_sink;

static int64_t exr_sink_write(exr_const_context_t ctx, void *user, const void *buf, uint64_t sz, uint64_t off,
                              exr_stream_error_func_ptr_t error_cb)
{
    (void)ctx, (void)error_cb;
    exr_sink *k = user;
    if (off > SIZE_MAX - sz) return k->failed = 1, -1;
    size_t end = (size_t)(off + sz);
    if (end > k->cap) {
        size_t cap = k->cap ? k->cap : 1 << 16;
        while (cap < end) cap = cap > SIZE_MAX / 2 ? end : cap * 2;
        unsigned char *p = realloc(k->p, cap);
        if (!p) return k->failed = 1, -1;
        if (cap > k->cap) memset(p + k->cap, 0, cap - k->cap);
        k->p = p, k->cap = cap;
    }
    memcpy(k->p + off, buf, (size_t)sz);
    if (end > k->n) k->n = end;
    return (int64_t)sz;
}

/* The library's compression step, which exr_compress_or_store calls. */
typedef struct exr_compress_step {
    exr_result_t (*fn)(exr_encode_pipeline_t *e);
} exr_compress_step;

/* The library's compression step, then a chunk that it did not shrink stored as it is: OpenEXRCore keeps a
 * compressed chunk exactly as large as the raw one, which every reader takes for raw data (a chunk whose packed size
 * equals its unpacked size is uncompressed). */
static exr_result_t exr_compress_or_store(exr_encode_pipeline_t *e)
{
    const exr_compress_step *step = e->encoding_user_data;
    exr_result_t rv = step->fn(e);
    if (rv != EXR_ERR_SUCCESS || e->packed_bytes == 0 || e->compressed_bytes < e->packed_bytes ||
        e->compressed_buffer == e->packed_buffer)
        return rv;
    if (!e->compressed_buffer || e->compressed_alloc_size < e->packed_bytes) return EXR_ERR_OUT_OF_MEMORY;
    memcpy(e->compressed_buffer, e->packed_buffer, e->packed_bytes);
    e->compressed_bytes = e->packed_bytes;
    return rv;
}

/* surface_encode_exr_channels, with the attribute "spacing" in the header where spacing is not NULL. */
static int encode_channels(size_t nx, size_t ny, int nch, const char *const *names, float *const *plane,
                           const double *spacing, unsigned char **data, size_t *n, char *err, size_t errn)
{
    *data = NULL, *n = 0;
    if (nx < 1 || ny < 1 || nx > INT32_MAX || ny > INT32_MAX || nch < 1)
        return surface_fail(err, errn, "no image, or too large for OpenEXR");
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_quiet;
    exr_sink sink = {NULL, 0, 0, 0};
    init.user_data = &sink;
    init.write_fn = exr_sink_write;
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc;
    memset(&enc, 0, sizeof enc);
    int enc_ready = 0, part = 0, started = 0;
    int32_t lines = 0;
    exr_compress_step step = {NULL};
    exr_result_t rv = exr_start_write(&ctx, "<memory>", EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS) started = 1;
    if (rv == EXR_ERR_SUCCESS) rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, (int32_t)nx, (int32_t)ny, EXR_COMPRESSION_ZIP);
    for (int k = 0; k < nch && rv == EXR_ERR_SUCCESS; k++)
        rv = exr_add_channel(ctx, part, names[k], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (rv == EXR_ERR_SUCCESS && spacing) {
        exr_attr_v2d_t sp = {.x = spacing[0], .y = spacing[1]};
        rv = exr_attr_set_v2d(ctx, part, EXR_SPACING_ATTR, &sp);
    }
    if (rv == EXR_ERR_SUCCESS) rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS) rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv == EXR_ERR_SUCCESS && lines < 1) rv = EXR_ERR_UNKNOWN;
    for (size_t y = 0; y < ny && rv == EXR_ERR_SUCCESS; y += (size_t)lines) {
        exr_chunk_info_t ci;
        rv = exr_write_scanline_chunk_info(ctx, part, (int)y, &ci);
        if (rv != EXR_ERR_SUCCESS) break;
        rv = enc_ready ? exr_encoding_update(ctx, part, &ci, &enc) : exr_encoding_initialize(ctx, part, &ci, &enc);
        if (rv != EXR_ERR_SUCCESS) break;
        enc_ready = 1;
        for (int c = 0; c < enc.channel_count && rv == EXR_ERR_SUCCESS; c++) {
            exr_coding_channel_info_t *ch = &enc.channels[c];
            int k = -1;
            for (int j = 0; j < nch; j++)
                if (ch->channel_name && strcmp(ch->channel_name, names[j]) == 0) k = j;
            if (k < 0) {
                rv = EXR_ERR_UNKNOWN;
                break;
            }
            ch->encode_from_ptr = (const uint8_t *)(plane[k] + y * nx);
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(nx * sizeof(float));
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
        }
        if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_choose_default_routines(ctx, part, &enc);
        if (rv == EXR_ERR_SUCCESS && enc.compress_fn) {
            step.fn = enc.compress_fn;
            enc.encoding_user_data = &step;
            enc.compress_fn = exr_compress_or_store;
        }
        if (rv == EXR_ERR_SUCCESS) rv = exr_encoding_run(ctx, part, &enc);
    }
    if (enc_ready) exr_encoding_destroy(ctx, &enc);
    exr_result_t fin = started ? exr_finish(&ctx) : EXR_ERR_SUCCESS;
    if (rv == EXR_ERR_SUCCESS) rv = fin;
    if (rv == EXR_ERR_SUCCESS && sink.failed) rv = EXR_ERR_OUT_OF_MEMORY;
    if (rv != EXR_ERR_SUCCESS) {
        free(sink.p);
        return surface_fail(err, errn, "%s", exr_get_error_code_as_string(rv));
    }
    *data = sink.p, *n = sink.n;
    return 0;
}

int surface_encode_exr_channels(size_t nx, size_t ny, int nch, const char *const *names, float *const *plane,
                                unsigned char **data, size_t *n, char *err, size_t errn)
{
    return encode_channels(nx, ny, nch, names, plane, NULL, data, n, err, errn);
}

int surface_encode_exr(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn)
{
    *data = NULL, *n = 0;
    int heights = s->kind == SURFACE_HEIGHTS, nch = heights ? 1 : 3;
    if (s->nx < 1 || s->ny < 1 || s->nx > INT32_MAX || s->ny > INT32_MAX || s->nx > SIZE_MAX / s->ny ||
        s->nx * s->ny > SIZE_MAX / sizeof(float) / 3 ||
        (heights                      ? !s->h
         : s->kind == SURFACE_NORMALS ? !s->m
                                      : !s->rgb))
        return surface_fail(err, errn, "no surface, or too large for OpenEXR");
    size_t count = s->nx * s->ny;
    static const char *const rgb[3] = {"R", "G", "B"}, *const y[1] = {"Y"};
    float *plane[3] = {NULL, NULL, NULL};
    for (int k = 0; k < nch; k++)
        if (!(plane[k] = malloc(count * sizeof(float)))) {
            for (int j = 0; j < k; j++) free(plane[j]);
            return surface_fail(err, errn, "out of memory");
        }
    double scale = s->z_scale > 0 ? s->z_scale : 1.0;
    for (size_t i = 0; i < count; i++) {
        if (heights) {
            plane[0][i] = (float)(s->h[i] * scale);
        } else if (s->kind == SURFACE_RADIANCE) {
            for (int k = 0; k < 3; k++) plane[k][i] = s->rgb[3 * i + k];
        } else {
            plane[0][i] = (float)s->m[i].x, plane[1][i] = (float)s->m[i].y, plane[2][i] = (float)s->m[i].z;
        }
    }
    /* heights written times z_scale are in the unit of the spacing, which the header then states */
    double spacing[2] = {s->dx, s->dy};
    int spaced = heights && s->dx > 0 && s->dy > 0 && isfinite(s->dx) && isfinite(s->dy);
    int rc = encode_channels(s->nx, s->ny, nch, heights ? y : rgb, plane, spaced ? spacing : NULL, data, n, err, errn);
    for (int k = 0; k < nch; k++) free(plane[k]);
    return rc;
}

int surface_write_exr(const char *path, const surface *s, char *err, size_t errn)
{
    unsigned char *data;
    size_t n;
    char why[160];
    if (surface_encode_exr(s, &data, &n, why, sizeof why) != 0)
        return surface_fail(err, errn, "cannot write '%s' (%s)", path, why);
    return surface_write_bytes(path, data, n, err, errn);
}

#else
int surface_parse_exr(const unsigned char *data, size_t n, const surface_read_options *o, surface *s, char *err,
                      size_t errn)
{
    (void)data, (void)n, (void)o, (void)s;
    return surface_fail(err, errn, "OpenEXR support was not built (OpenEXR missing: apt-get install libopenexr-dev)");
}
int surface_write_exr(const char *path, const surface *s, char *err, size_t errn)
{
    (void)path, (void)s;
    return surface_fail(err, errn, "OpenEXR support was not built (OpenEXR missing: apt-get install libopenexr-dev)");
}
int surface_encode_exr(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn)
{
    (void)s;
    *data = NULL, *n = 0;
    return surface_fail(err, errn, "OpenEXR support was not built (OpenEXR missing: apt-get install libopenexr-dev)");
}
int surface_encode_exr_channels(size_t nx, size_t ny, int nch, const char *const *names, float *const *plane,
                                unsigned char **data, size_t *n, char *err, size_t errn)
{
    (void)nx, (void)ny, (void)nch, (void)names, (void)plane;
    *data = NULL, *n = 0;
    return surface_fail(err, errn, "OpenEXR support was not built (OpenEXR missing: apt-get install libopenexr-dev)");
}
#endif
