/* ISO 25178-72 (ISO 5436-2) .x3p through libzip and libxml2: a zip holding main.xml, which gives the axes
 * (Record1/Axes/CX, CY: incremental, with their Increment in metres; CZ: the data type D, F, L or I and, for integers,
 * its Increment and Offset), the matrix size (Record3/MatrixDimension) and the data's member (Record3/DataLink/
 * PointDataLink), little-endian, x fastest; an optional ValidPointsLink bit array (1 = valid, least significant bit
 * first) and NaN mark invalid points. Checksums are not verified, and the writer leaves them out.
 * SPDX-License-Identifier: MIT */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "surface.h"

#ifdef GGX_HAVE_X3P
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <zip.h>

/* The first element named path[0], then path[1] inside it, ...; NULL if absent. */
static xmlNode *child(xmlNode *n, const char *const *path)
{
    for (; *path && n; path++) {
        xmlNode *c = n->children;
        while (c && !(c->type == XML_ELEMENT_NODE && strcmp((const char *)c->name, *path) == 0)) c = c->next;
        n = c;
    }
    return n;
}

static int text_of(xmlNode *root, const char *const *path, char *out, size_t n)
{
    xmlNode *e = child(root, path);
    if (!e) return 0;
    xmlChar *t = xmlNodeGetContent(e);
    if (!t) return 0;
    const char *p = (const char *)t;
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    snprintf(out, n, "%s", p);
    for (size_t k = strlen(out); k > 0 && strchr(" \n\t\r", out[k - 1]); k--) out[k - 1] = '\0';
    xmlFree(t);
    return 1;
}

/* A member of the archive into memory, of exactly `want` bytes when want > 0 (else at most limit); NULL on failure.
 * The buffer grows with the bytes actually decompressed, so an archive that claims a huge member costs no more
 * memory than its data inflate to (deflate expands at most about 1000 to 1). */
static unsigned char *member(zip_t *z, const char *name, size_t want, size_t limit, size_t *len)
{
    zip_stat_t st;
    if (zip_stat(z, name, 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) return NULL;
    if (want ? st.size != want : st.size > limit) return NULL;
    zip_file_t *f = zip_fopen(z, name, 0);
    if (!f) return NULL;
    size_t cap = 0, n = 0, total = (size_t)st.size;
    unsigned char *buf = NULL;
    while (n < total) {
        if (n == cap) {
            size_t c = cap ? 2 * cap : 1 << 16;
            if (c > total) c = total;
            unsigned char *nb = realloc(buf, c);
            if (!nb) break;
            buf = nb, cap = c;
        }
        zip_int64_t got = zip_fread(f, buf + n, cap - n);
        if (got <= 0) break;
        n += (size_t)got;
    }
    zip_fclose(f);
    if (n != total || (total == 0 && !(buf = malloc(1)))) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

int surface_parse_x3p(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(data, n, 0, &ze);
    zip_t *z = src ? zip_open_from_source(src, ZIP_RDONLY, &ze) : NULL;
    if (!z) {
        if (src) zip_source_free(src);
        zip_error_fini(&ze);
        return surface_fail(err, errn, "not a readable zip archive");
    }
    zip_error_fini(&ze);
    int rc = 0;
    size_t xl = 0, dl = 0, vl = 0;
    unsigned char *xml = member(z, "main.xml", 0, 1 << 24, &xl), *bin = NULL, *valid = NULL;
    xmlDoc *doc = NULL;
    if (!xml) {
        rc = surface_fail(err, errn, "no main.xml in the archive");
        goto done;
    }
    doc = xmlReadMemory((const char *)xml, (int)xl, "main.xml", NULL,
                        XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    xmlNode *root = doc ? xmlDocGetRootElement(doc) : NULL;
    if (!root) {
        rc = surface_fail(err, errn, "main.xml is not well-formed XML");
        goto done;
    }
    char feat[16] = "", cxt[8] = "", cyt[8] = "", ztype[8] = "", sx[32] = "", sy[32] = "", sz[32] = "", ix[40] = "",
         iy[40] = "", iz[40] = "", oz[40] = "", link[256] = "", vlink[256] = "";
    text_of(root, (const char *[]){"Record1", "FeatureType", NULL}, feat, sizeof feat);
    text_of(root, (const char *[]){"Record1", "Axes", "CX", "AxisType", NULL}, cxt, sizeof cxt);
    text_of(root, (const char *[]){"Record1", "Axes", "CY", "AxisType", NULL}, cyt, sizeof cyt);
    text_of(root, (const char *[]){"Record1", "Axes", "CZ", "DataType", NULL}, ztype, sizeof ztype);
    text_of(root, (const char *[]){"Record1", "Axes", "CX", "Increment", NULL}, ix, sizeof ix);
    text_of(root, (const char *[]){"Record1", "Axes", "CY", "Increment", NULL}, iy, sizeof iy);
    text_of(root, (const char *[]){"Record1", "Axes", "CZ", "Increment", NULL}, iz, sizeof iz);
    text_of(root, (const char *[]){"Record1", "Axes", "CZ", "Offset", NULL}, oz, sizeof oz);
    text_of(root, (const char *[]){"Record3", "MatrixDimension", "SizeX", NULL}, sx, sizeof sx);
    text_of(root, (const char *[]){"Record3", "MatrixDimension", "SizeY", NULL}, sy, sizeof sy);
    text_of(root, (const char *[]){"Record3", "MatrixDimension", "SizeZ", NULL}, sz, sizeof sz);
    text_of(root, (const char *[]){"Record3", "DataLink", "PointDataLink", NULL}, link, sizeof link);
    text_of(root, (const char *[]){"Record3", "DataLink", "ValidPointsLink", NULL}, vlink, sizeof vlink);
    if (strcmp(feat, "SUR") != 0) {
        rc = surface_fail(err, errn, "FeatureType '%s' is not SUR (an areal surface)", feat);
        goto done;
    }
    if (strcmp(cxt, "I") != 0 || strcmp(cyt, "I") != 0) {
        rc = surface_fail(err, errn, "the x and y axes must be incremental (AxisType I), not '%s', '%s'", cxt, cyt);
        goto done;
    }
    double nxd = strtod(sx, NULL), nyd = strtod(sy, NULL), nzd = sz[0] ? strtod(sz, NULL) : 1.0;
    double dx = strtod(ix, NULL), dy = strtod(iy, NULL), zinc = iz[0] ? strtod(iz, NULL) : 1.0;
    double zoff = oz[0] ? strtod(oz, NULL) : 0.0;
    if (!(nxd >= 2 && nyd >= 2 && nxd <= 1e6 && nyd <= 1e6) || nxd != floor(nxd) || nyd != floor(nyd) || nzd != 1) {
        rc = surface_fail(err, errn, "MatrixDimension %s x %s x %s: need at least 2 x 2 x 1 (one layer)", sx, sy, sz);
        goto done;
    }
    if (!(dx > 0 && dy > 0 && isfinite(dx) && isfinite(dy)) || !isfinite(zinc) || !isfinite(zoff)) {
        rc = surface_fail(err, errn, "the x and y increments must be positive ('%s', '%s')", ix, iy);
        goto done;
    }
    int size = strcmp(ztype, "D") == 0                              ? 8
               : strcmp(ztype, "F") == 0 || strcmp(ztype, "L") == 0 ? 4
               : strcmp(ztype, "I") == 0                            ? 2
                                                                    : 0;
    if (!size) {
        rc = surface_fail(err, errn, "CZ DataType '%s' is not D, F, L or I", ztype);
        goto done;
    }
    size_t nx = (size_t)nxd, ny = (size_t)nyd, count = nx * ny;
    if (!link[0] || !(bin = member(z, link, count * (size_t)size, 0, &dl))) {
        rc = surface_fail(err, errn,
                          "the point data '%s' is not in the archive, or is not %zu x %zu points of type %s "
                          "(%zu bytes) once inflated",
                          link, nx, ny, ztype, count * (size_t)size);
        goto done;
    }
    if (vlink[0] && (!(valid = member(z, vlink, (count + 7) / 8, 0, &vl)))) {
        rc = surface_fail(err, errn, "the valid-points array '%s' is missing or short", vlink);
        goto done;
    }
    if (!(s->h = malloc(count * sizeof *s->h))) {
        rc = surface_fail(err, errn, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < count; i++) {
        const unsigned char *b = bin + i * (size_t)size;
        uint64_t u = 0;
        for (int k = size - 1; k >= 0; k--) u = u << 8 | b[k];
        double v;
        if (size == 8) memcpy(&v, &u, 8);
        else if (size == 4 && ztype[0] == 'F') {
            uint32_t u32 = (uint32_t)u;
            float f;
            memcpy(&f, &u32, 4);
            v = f;
        } else if (size == 4) v = (double)(int32_t)(uint32_t)u * zinc + zoff;
        else v = (double)(int16_t)(uint16_t)u * zinc + zoff;
        if (valid && !(valid[i / 8] >> (i % 8) & 1)) v = NAN;
        s->h[i] = v;
    }
    s->kind = SURFACE_HEIGHTS, s->nx = nx, s->ny = ny, s->dx = dx, s->dy = dy, s->z_scale = 1.0;
done:
    if (doc) xmlFreeDoc(doc);
    free(xml), free(bin), free(valid);
    zip_discard(z);
    return rc;
}

int surface_encode_x3p(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *mem = zip_source_buffer_create(NULL, 0, 0, &ze); /* the archive, in memory */
    zip_t *z = mem ? zip_open_from_source(mem, ZIP_TRUNCATE, &ze) : NULL;
    zip_error_fini(&ze);
    if (!z) {
        if (mem) zip_source_free(mem);
        return surface_fail(err, errn, "x3p: cannot make the archive");
    }
    zip_source_keep(mem); /* kept past zip_close, to be read back */
    size_t count = s->nx * s->ny;
    char *xml = malloc(4096);
    unsigned char *bin = malloc(count * 8 + 1);
    if (!xml || !bin) {
        free(xml), free(bin), zip_discard(z), zip_source_free(mem);
        return surface_fail(err, errn, "out of memory");
    }
    snprintf(xml, 4096,
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
             " <Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType>\n"
             "  <Axes><CX><AxisType>I</AxisType><DataType>D</DataType><Increment>%.17g</Increment>"
             "<Offset>0</Offset></CX>\n"
             "   <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>%.17g</Increment>"
             "<Offset>0</Offset></CY>\n"
             "   <CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1>\n"
             " <Record2><Date>1970-01-01T00:00:00</Date><Creator>libggx</Creator>"
             "<Instrument><Manufacturer>libggx</Manufacturer><Model>ggx</Model><Serial>0</Serial>"
             "<Version>0</Version></Instrument><CalibrationDate>1970-01-01T00:00:00</CalibrationDate>"
             "<ProbingSystem><Type>NonContacting</Type><Identification>synthetic</Identification></ProbingSystem>"
             "<Comment>written by ggx</Comment></Record2>\n"
             " <Record3><MatrixDimension><SizeX>%zu</SizeX><SizeY>%zu</SizeY><SizeZ>1</SizeZ></MatrixDimension>\n"
             "  <DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink></Record3>\n"
             "</p:ISO5436_2>\n",
             s->dx, s->dy, s->nx, s->ny);
    for (size_t i = 0; i < count; i++) {
        double v = s->h[i] * (s->z_scale > 0 ? s->z_scale : 1.0);
        uint64_t u;
        memcpy(&u, &v, 8);
        for (int k = 0; k < 8; k++) bin[i * 8 + (size_t)k] = (unsigned char)(u >> (8 * k));
    }
    zip_source_t *a = zip_source_buffer(z, xml, strlen(xml), 0), *b = zip_source_buffer(z, bin, count * 8, 0);
    int ok = a && b && zip_file_add(z, "main.xml", a, ZIP_FL_ENC_UTF_8) >= 0 &&
             zip_file_add(z, "bindata/data.bin", b, ZIP_FL_ENC_UTF_8) >= 0;
    if (!ok) {
        if (a) zip_source_free(a);
        if (b) zip_source_free(b);
    }
    ok = ok && zip_close(z) == 0;
    if (!ok) zip_discard(z);
    free(xml), free(bin);
    zip_int64_t len = -1;
    unsigned char *out = NULL;
    if (ok && zip_source_open(mem) == 0) {
        if (zip_source_seek(mem, 0, SEEK_END) == 0 && (len = zip_source_tell(mem)) > 0 &&
            zip_source_seek(mem, 0, SEEK_SET) == 0 && (out = malloc((size_t)len)) != NULL &&
            zip_source_read(mem, out, (zip_uint64_t)len) != len)
            free(out), out = NULL;
        zip_source_close(mem);
    }
    zip_source_free(mem);
    if (!out) return surface_fail(err, errn, "x3p: cannot encode the archive");
    *data = out, *n = (size_t)len;
    return 0;
}

int surface_write_x3p(const char *path, const surface *s, char *err, size_t errn)
{
    unsigned char *data;
    size_t n;
    if (surface_encode_x3p(s, &data, &n, err, errn) != 0) return -1;
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(data, 1, n, f) == n;
    if (f && fclose(f) != 0) ok = 0;
    free(data);
    return ok ? 0 : surface_fail(err, errn, "cannot write '%s'", path);
}
#else
int surface_parse_x3p(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    (void)data, (void)n, (void)s;
    return surface_fail(err, errn,
                        "x3p support was not built (libzip and libxml2 missing: apt-get install "
                        "libzip-dev libxml2-dev)");
}
int surface_write_x3p(const char *path, const surface *s, char *err, size_t errn)
{
    (void)path, (void)s;
    return surface_fail(err, errn, "x3p support was not built (libzip and libxml2 missing)");
}
int surface_encode_x3p(const surface *s, unsigned char **data, size_t *n, char *err, size_t errn)
{
    (void)s, (void)data, (void)n;
    return surface_fail(err, errn, "x3p support was not built (libzip and libxml2 missing)");
}
#endif
