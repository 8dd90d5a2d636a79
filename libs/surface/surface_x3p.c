/* ISO 25178-72 (ISO 5436-2) .x3p through libzip and libxml2, areal data (FeatureType SUR) as the standard's schema
 * (ISO5436_2.xsd) lays it out. The archive holds main.xml at its root or in one folder (the paths it names are
 * relative to that folder), md5checksum.hex (the MD5 of main.xml, as md5sum writes it) and the point data.
 * main.xml gives the axes (Record1/Axes/CX, CY, CZ), the matrix size (Record3/MatrixDimension, one layer) and the
 * points, either inline (Record3/DataList: one Datum per point, x fastest, holding the values of the absolute axes
 * separated by ';'; an empty Datum is a missing point) or in a member (Record3/DataLink/PointDataLink: the same values
 * in binary, little-endian, each axis in its DataType) with an optional ValidPointsLink bit array (1 = valid, least
 * significant bit first). DataType is I (int16), L (int32), F (float32) or D (float64); an integer coordinate is
 * Offset + Increment x value, a float one Offset + value; NaN marks a missing point too. An incremental x or y axis
 * has its spacing in Increment; an absolute one gives every point's coordinate, read when the coordinates lie on a
 * regular grid (their step becomes the spacing; a decreasing axis is mirrored) and refused otherwise. z must be
 * absolute. Every member read is checked against its zip CRC, main.xml against md5checksum.hex and the point data and
 * valid-points array against MD5ChecksumPointData and MD5ChecksumValidPoints (where the build has libcrypto).
 * Profiles (PRF), point clouds (PCL) and lists (ListDimension) are refused: a fit needs an areal grid.
 * SPDX-License-Identifier: MIT */
#include <ctype.h>
#include <float.h>
#include <limits.h>
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
#ifdef GGX_HAVE_MD5
#include <openssl/evp.h>
#endif

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

/* The text of an element, blanks trimmed and control characters turned into spaces (so a reason quoting it stays
 * one line); 0 if the element is absent. */
static int text_of(xmlNode *root, const char *const *path, char *out, size_t n)
{
    xmlNode *e = child(root, path);
    out[0] = '\0';
    if (!e) return 0;
    xmlChar *t = xmlNodeGetContent(e);
    if (!t) return 1;
    const char *p = (const char *)t;
    while (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r') p++;
    snprintf(out, n, "%s", p);
    for (size_t k = strlen(out); k > 0 && strchr(" \n\t\r", out[k - 1]); k--) out[k - 1] = '\0';
    for (char *c = out; *c; c++)
        if ((unsigned char)*c < 0x20) *c = ' ';
    xmlFree(t);
    return 1;
}

/* The 32 hexadecimal digits of the MD5 of n bytes into hex (33 bytes); 0, or -1 where the build has no MD5. */
static int md5_hex(const unsigned char *data, size_t n, char *hex)
{
#ifdef GGX_HAVE_MD5
    unsigned char d[EVP_MAX_MD_SIZE];
    unsigned int len = 0;
    if (EVP_Digest(data, n, d, &len, EVP_md5(), NULL) != 1 || len != 16) return -1;
    for (unsigned k = 0; k < 16; k++) snprintf(hex + 2 * k, 3, "%02x", d[k]);
    return 0;
#else
    (void)data, (void)n, (void)hex;
    return -1;
#endif
}

/* Whether the MD5 of data matches the 32 hexadecimal digits at the start of want (any case); 1 where the build has
 * no MD5 to check with. */
static int md5_matches(const unsigned char *data, size_t n, const char *want, char *got)
{
    if (md5_hex(data, n, got) != 0) return 1;
    for (int k = 0; k < 32; k++) {
        char c = want[k];
        if (c >= 'A' && c <= 'F') c = (char)(c - 'A' + 'a');
        if (c != got[k]) return 0;
    }
    return 1;
}

/* A member of the archive into memory (at most limit bytes), its CRC checked: NULL with a reason in why on failure.
 * The buffer grows with the bytes actually inflated, so an archive that claims a huge member costs no more memory
 * than its data inflate to. libzip checks the CRC once a read reaches the member's end, so one read past the size
 * it states is made. */
static unsigned char *member(zip_t *z, const char *name, size_t limit, size_t *len, char *why, size_t whyn)
{
    zip_stat_t st;
    if (zip_stat(z, name, 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) {
        snprintf(why, whyn, "'%s' is not in the archive", name);
        return NULL;
    }
    if (st.size > limit) {
        snprintf(why, whyn, "'%s' is %llu bytes, more than the %zu it may hold", name, (unsigned long long)st.size,
                 limit);
        return NULL;
    }
    zip_file_t *f = zip_fopen(z, name, 0);
    if (!f) {
        snprintf(why, whyn, "cannot open '%s' in the archive: %s", name, zip_strerror(z));
        return NULL;
    }
    size_t cap = 0, n = 0, total = (size_t)st.size;
    unsigned char *buf = NULL, extra;
    int bad = 0;
    while (n < total) {
        if (n == cap) {
            size_t c = cap ? 2 * cap : 1 << 16;
            if (c > total) c = total;
            unsigned char *nb = realloc(buf, c);
            if (!nb) {
                bad = 1;
                break;
            }
            buf = nb, cap = c;
        }
        zip_int64_t got = zip_fread(f, buf + n, cap - n);
        if (got <= 0) {
            bad = 1;
            break;
        }
        n += (size_t)got;
    }
    if (!bad && zip_fread(f, &extra, 1) != 0) bad = 1; /* the end of the member, where its CRC is checked */
    if (bad) snprintf(why, whyn, "'%s' in the archive: %s", name, n == total ? zip_file_strerror(f) : "truncated");
    zip_fclose(f);
    if (!bad && !buf && !(buf = malloc(1))) bad = 1, snprintf(why, whyn, "out of memory");
    if (bad) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* An x, y or z axis of Record1/Axes: absolute or incremental, its data type's size, increment and offset. */
typedef struct axis {
    char name[3], type[8], dtype[8], inc[48], off[48];
    int absolute, size, integer;
    double increment, offset;
} axis;

static int read_axis(xmlNode *root, const char *name, axis *a, char *err, size_t errn)
{
    memset(a, 0, sizeof *a);
    snprintf(a->name, sizeof a->name, "%s", name);
    text_of(root, (const char *[]){"Record1", "Axes", name, "AxisType", NULL}, a->type, sizeof a->type);
    text_of(root, (const char *[]){"Record1", "Axes", name, "DataType", NULL}, a->dtype, sizeof a->dtype);
    text_of(root, (const char *[]){"Record1", "Axes", name, "Increment", NULL}, a->inc, sizeof a->inc);
    text_of(root, (const char *[]){"Record1", "Axes", name, "Offset", NULL}, a->off, sizeof a->off);
    if (strcmp(a->type, "A") != 0 && strcmp(a->type, "I") != 0)
        return surface_fail(err, errn, "%s AxisType '%s' is not A (absolute) or I (incremental)", name, a->type);
    a->absolute = a->type[0] == 'A';
    char *end;
    a->increment = a->inc[0] ? strtod(a->inc, &end) : 1.0;
    if (a->inc[0] && (*end || !isfinite(a->increment) || a->increment == 0.0))
        return surface_fail(err, errn, "%s Increment '%s' is not a finite, non-zero number", name, a->inc);
    a->offset = a->off[0] ? strtod(a->off, &end) : 0.0;
    if (a->off[0] && (*end || !isfinite(a->offset)))
        return surface_fail(err, errn, "%s Offset '%s' is not a finite number", name, a->off);
    if (!a->absolute) {
        if (!(a->increment > 0.0) || !a->inc[0])
            return surface_fail(err, errn, "the incremental %s axis needs a positive Increment, not '%s'", name,
                                a->inc);
        return 0;
    }
    a->size = strcmp(a->dtype, "D") == 0                                 ? 8
              : strcmp(a->dtype, "F") == 0 || strcmp(a->dtype, "L") == 0 ? 4
              : strcmp(a->dtype, "I") == 0                               ? 2
                                                                         : 0;
    if (!a->size) return surface_fail(err, errn, "%s DataType '%s' is not D, F, L or I", name, a->dtype);
    a->integer = a->dtype[0] == 'I' || a->dtype[0] == 'L';
    return 0;
}

/* A coordinate from its stored value: Offset + Increment x value for integers, Offset + value for floats. */
static double coordinate(const axis *a, double v) { return a->integer ? a->offset + a->increment * v : a->offset + v; }

/* The value of one axis from little-endian bytes. */
static double binary_value(const axis *a, const unsigned char *b)
{
    uint64_t u = 0;
    for (int k = a->size - 1; k >= 0; k--) u = u << 8 | b[k];
    if (a->size == 8) {
        double v;
        memcpy(&v, &u, 8);
        return v;
    }
    if (a->size == 4 && a->dtype[0] == 'F') {
        uint32_t u32 = (uint32_t)u;
        float f;
        memcpy(&f, &u32, 4);
        return f;
    }
    if (a->size == 4) return (double)(int32_t)(uint32_t)u;
    return (double)(int16_t)(uint16_t)u;
}

/* One value of a Datum in an axis' type: 0, or -1 where it is not a number of that type (an integer out of range,
 * a float beyond float32). */
static int text_value(const axis *a, const char *p, const char **end, double *v)
{
    char *e;
    *v = strtod(p, &e);
    *end = e;
    if (e == p) return -1;
    if (a->integer) {
        double lim = a->size == 2 ? 32767.0 : 2147483647.0;
        return *v == floor(*v) && *v >= -lim - 1.0 && *v <= lim ? 0 : -1;
    }
    if (a->size == 4) {
        if (isfinite(*v) && fabs(*v) > FLT_MAX) return -1;
        *v = (float)*v;
    }
    return 0;
}

/* The step of an absolute x or y axis whose coordinates c[k] (at grid index idx(k), NaN where missing) lie on a
 * regular grid: the least-squares line through them, every point within a thousandth of a step of it (or of the
 * coordinates' own float precision). 0 with *step, or -1 with the reason. */
static int regular_step(const axis *a, const double *c, size_t nx, size_t ny, int along_x, double *step, char *err,
                        size_t errn)
{
    double n = 0, si = 0, sc = 0;
    size_t count = nx * ny;
    for (size_t k = 0; k < count; k++)
        if (isfinite(c[k])) n += 1, si += (double)(along_x ? k % nx : k / nx), sc += c[k];
    if (n < 2) return surface_fail(err, errn, "the absolute %s axis has fewer than 2 valid coordinates", a->name);
    double mi = si / n, mc = sc / n, sii = 0, sic = 0, cmax = 0;
    for (size_t k = 0; k < count; k++)
        if (isfinite(c[k])) {
            double u = (double)(along_x ? k % nx : k / nx) - mi;
            sii += u * u, sic += u * (c[k] - mc), cmax = fmax(cmax, fabs(c[k]));
        }
    double b = sii > 0 ? sic / sii : 0.0;
    if (!(fabs(b) > 0) || !isfinite(b))
        return surface_fail(err, errn, "the absolute %s axis does not advance along the grid: ggx reads a regular grid",
                            a->name);
    double eps = a->dtype[0] == 'F' ? FLT_EPSILON : DBL_EPSILON, tol = fmax(1e-3 * fabs(b), 8 * eps * cmax);
    for (size_t k = 0; k < count; k++) {
        if (!isfinite(c[k])) continue;
        double i = (double)(along_x ? k % nx : k / nx), d = c[k] - (mc + b * (i - mi));
        if (fabs(d) > tol)
            return surface_fail(err, errn,
                                "the absolute %s axis is irregular: point (%zu, %zu) lies at %.9g m, %.3g m off the "
                                "grid of step %.6g m; ggx reads only a regular grid",
                                a->name, k % nx, k / nx, c[k], d, fabs(b));
    }
    *step = b;
    return 0;
}

/* Fields per point (the absolute axes among x, y, z) and their bytes in binary data. */
static void point_layout(const axis *ax, int *nf, size_t *bytes)
{
    *nf = 0, *bytes = 0;
    for (int k = 0; k < 3; k++)
        if (ax[k].absolute) (*nf)++, *bytes += (size_t)ax[k].size;
}

/* The index in the archive of main.xml: at the root, else the one main.xml one folder deep (macOS' __MACOSX copies
 * aside); its folder, with the slash, in base. -1 with the reason. */
static zip_int64_t find_main(zip_t *z, char *base, size_t basen, char *err, size_t errn)
{
    base[0] = '\0';
    zip_int64_t at = zip_name_locate(z, "main.xml", 0);
    if (at >= 0) return at;
    zip_int64_t n = zip_get_num_entries(z, 0), found = -1;
    for (zip_int64_t k = 0; k < n; k++) {
        const char *name = zip_get_name(z, (zip_uint64_t)k, 0), *slash = name ? strchr(name, '/') : NULL;
        if (!slash || strcmp(slash + 1, "main.xml") != 0 || strncmp(name, "__MACOSX/", 9) == 0) continue;
        if (found >= 0) {
            surface_fail(err, errn, "more than one folder holds a main.xml ('%s', '%s')", base, name);
            return -1;
        }
        found = k;
        snprintf(base, basen, "%.*s", (int)(slash + 1 - name), name);
    }
    if (found < 0) surface_fail(err, errn, "no main.xml in the archive, at its root or in one folder");
    return found;
}

/* What the steps of reading an archive share: the archive, main.xml's root and folder, the axes, the grid and the
 * coordinates read (vals[k] for the absolute axes, NULL for the others; vals[2] the heights). */
typedef struct x3p_read {
    zip_t *z;
    xmlNode *root;
    char base[256];
    axis ax[3];
    size_t nx, ny, count, rec;
    int nf;
    double *vals[3];
    char *err;
    size_t errn;
} x3p_read;

/* md5checksum.hex (Record4/ChecksumFile, where given): the MD5 of main.xml. */
static int check_main_md5(x3p_read *r, const unsigned char *xml, size_t xl)
{
    char sumfile[256] = "", path[600], why[400], md5[33] = "";
    text_of(r->root, (const char *[]){"Record4", "ChecksumFile", NULL}, sumfile, sizeof sumfile);
    snprintf(path, sizeof path, "%s%s", r->base, sumfile[0] ? sumfile : "md5checksum.hex");
    if (!sumfile[0] && zip_name_locate(r->z, path, 0) < 0) return 0;
    size_t hl = 0;
    unsigned char *hex = member(r->z, path, 4096, &hl, why, sizeof why);
    if (!hex) return surface_fail(r->err, r->errn, "the checksum file of main.xml: %s", why);
    size_t k = 0;
    while (k < hl && k < 32 && isxdigit(hex[k])) k++;
    int rc = 0;
    if (k != 32) rc = surface_fail(r->err, r->errn, "'%s' does not start with 32 hexadecimal digits (an MD5)", path);
    else if (!md5_matches(xml, xl, (const char *)hex, md5))
        rc = surface_fail(r->err, r->errn,
                          "main.xml's MD5 is %s, not the %.32s of '%s': the file is damaged or was changed after it "
                          "was written",
                          md5, (const char *)hex, path);
    free(hex);
    return rc;
}

/* Record1's feature type (SUR), the axes (z absolute) and Record3's matrix size: r->ax, nx, ny, count, nf, rec. */
static int read_grid(x3p_read *r)
{
    char feat[16] = "";
    text_of(r->root, (const char *[]){"Record1", "FeatureType", NULL}, feat, sizeof feat);
    if (strcmp(feat, "PRF") == 0 || strcmp(feat, "PCL") == 0)
        return surface_fail(r->err, r->errn,
                            "FeatureType %s is %s, not an areal surface (SUR): ggx fit needs a grid of heights", feat,
                            feat[1] == 'R' ? "a profile" : "a point cloud");
    if (strcmp(feat, "SUR") != 0)
        return surface_fail(r->err, r->errn, "FeatureType '%s' is not SUR (an areal surface)", feat);
    if (read_axis(r->root, "CX", &r->ax[0], r->err, r->errn) || read_axis(r->root, "CY", &r->ax[1], r->err, r->errn) ||
        read_axis(r->root, "CZ", &r->ax[2], r->err, r->errn))
        return -1;
    if (!r->ax[2].absolute)
        return surface_fail(r->err, r->errn, "the z axis is incremental (AxisType I): the standard has it absolute");
    if (child(r->root, (const char *[]){"Record3", "ListDimension", NULL}))
        return surface_fail(r->err, r->errn,
                            "Record3 holds a list of points (ListDimension), not a matrix: ggx fit needs a grid");
    char sx[32] = "", sy[32] = "", sz[32] = "";
    text_of(r->root, (const char *[]){"Record3", "MatrixDimension", "SizeX", NULL}, sx, sizeof sx);
    text_of(r->root, (const char *[]){"Record3", "MatrixDimension", "SizeY", NULL}, sy, sizeof sy);
    text_of(r->root, (const char *[]){"Record3", "MatrixDimension", "SizeZ", NULL}, sz, sizeof sz);
    char *e1, *e2, *e3;
    unsigned long long nxl = strtoull(sx, &e1, 10), nyl = strtoull(sy, &e2, 10),
                       nzl = sz[0] ? strtoull(sz, &e3, 10) : 1;
    if (!sx[0] || !sy[0] || *e1 || *e2 || (sz[0] && *e3) || nxl < 2 || nyl < 2 || nxl > 1000000 || nyl > 1000000 ||
        nzl != 1 || nxl * nyl > 1ull << 28)
        return surface_fail(r->err, r->errn,
                            "MatrixDimension %s x %s x %s: need 2 to 1e6 points a side, 2^28 in all, and one layer", sx,
                            sy, sz);
    r->nx = (size_t)nxl, r->ny = (size_t)nyl, r->count = r->nx * r->ny;
    point_layout(r->ax, &r->nf, &r->rec);
    return 0;
}

/* One Datum's text: the absolute axes' values separated by ';' into point i (an empty Datum: a missing point). */
static int read_datum(x3p_read *r, const char *p, size_t i)
{
    while (isspace((unsigned char)*p)) p++;
    if (!*p) {
        for (int k = 0; k < 3; k++)
            if (r->vals[k]) r->vals[k][i] = NAN;
        return 0;
    }
    for (int k = 0, f = 0; k < 3; k++) {
        if (!r->ax[k].absolute) continue;
        const char *end;
        double v;
        if (f++ > 0) {
            while (isspace((unsigned char)*p)) p++;
            if (*p++ != ';') return -1;
        }
        if (text_value(&r->ax[k], p, &end, &v) != 0) return -1;
        r->vals[k][i] = coordinate(&r->ax[k], v), p = end;
    }
    while (isspace((unsigned char)*p)) p++;
    return *p ? -1 : 0;
}

/* Inline points (Record3/DataList): one Datum per point, x fastest. */
static int read_inline(x3p_read *r, xmlNode *list)
{
    const axis *ax = r->ax;
    size_t i = 0;
    for (xmlNode *d = list->children; d; d = d->next) {
        if (d->type != XML_ELEMENT_NODE || strcmp((const char *)d->name, "Datum") != 0) continue;
        if (i == r->count)
            return surface_fail(r->err, r->errn, "DataList holds more than the %zu x %zu points of MatrixDimension",
                                r->nx, r->ny);
        xmlChar *t = xmlNodeGetContent(d);
        int bad = read_datum(r, t ? (const char *)t : "", i);
        if (t) xmlFree(t);
        if (bad)
            return surface_fail(r->err, r->errn,
                                "Datum %zu is not %d value%s separated by ';' of the DataType%s (%s%s%s)", i + 1, r->nf,
                                r->nf > 1 ? "s" : "", r->nf > 1 ? "s" : "", ax[0].absolute ? ax[0].dtype : "",
                                ax[1].absolute ? ax[1].dtype : "", ax[2].dtype);
        i++;
    }
    if (i != r->count)
        return surface_fail(r->err, r->errn, "DataList holds %zu points, not the %zu x %zu of MatrixDimension", i,
                            r->nx, r->ny);
    return 0;
}

/* Binary points (Record3/DataLink): the same values per point, little-endian, checked against their MD5 where given,
 * and the valid-points bit array where there is one. */
static int read_binary(x3p_read *r, const char *link)
{
    char vlink[256] = "", lsum[64] = "", vsum[64] = "", path[600], why[400], md5[33] = "";
    text_of(r->root, (const char *[]){"Record3", "DataLink", "MD5ChecksumPointData", NULL}, lsum, sizeof lsum);
    text_of(r->root, (const char *[]){"Record3", "DataLink", "ValidPointsLink", NULL}, vlink, sizeof vlink);
    text_of(r->root, (const char *[]){"Record3", "DataLink", "MD5ChecksumValidPoints", NULL}, vsum, sizeof vsum);
    size_t count = r->count, rec = r->rec, dl = 0, vl = 0;
    snprintf(path, sizeof path, "%s%s", r->base, link);
    unsigned char *bin = member(r->z, path, count * rec, &dl, why, sizeof why), *valid = NULL;
    int rc = 0;
    if (!bin) return surface_fail(r->err, r->errn, "the point data: %s", why);
    if (dl != count * rec) {
        rc = surface_fail(r->err, r->errn,
                          "the point data '%s' holds %zu bytes, not the %zu of %zu x %zu points of %zu bytes", link, dl,
                          count * rec, r->nx, r->ny, rec);
        goto done;
    }
    if (lsum[0] && !md5_matches(bin, dl, lsum, md5)) {
        rc = surface_fail(r->err, r->errn, "the point data's MD5 is %s, not the MD5ChecksumPointData %s", md5, lsum);
        goto done;
    }
    for (size_t i = 0; i < count; i++) {
        const unsigned char *b = bin + i * rec;
        for (int k = 0; k < 3; k++)
            if (r->ax[k].absolute)
                r->vals[k][i] = coordinate(&r->ax[k], binary_value(&r->ax[k], b)), b += r->ax[k].size;
    }
    if (!vlink[0]) goto done;
    snprintf(path, sizeof path, "%s%s", r->base, vlink);
    if (!(valid = member(r->z, path, (count + 7) / 8, &vl, why, sizeof why)) || vl != (count + 7) / 8) {
        rc = valid ? surface_fail(r->err, r->errn, "the valid-points array '%s' holds %zu bytes, not %zu", vlink, vl,
                                  (count + 7) / 8)
                   : surface_fail(r->err, r->errn, "the valid-points array: %s", why);
        goto done;
    }
    if (vsum[0] && !md5_matches(valid, vl, vsum, md5)) {
        rc = surface_fail(r->err, r->errn, "the valid-points array's MD5 is %s, not the MD5ChecksumValidPoints %s", md5,
                          vsum);
        goto done;
    }
    for (size_t i = 0; i < count; i++)
        if (!(valid[i / 8] >> (i % 8) & 1))
            for (int k = 0; k < 3; k++)
                if (r->vals[k]) r->vals[k][i] = NAN;
done:
    free(bin), free(valid);
    return rc;
}

/* The grid's spacings from the absolute axes' coordinates (a point missing one coordinate is missing), and the
 * heights in the order of increasing x and y (a decreasing axis mirrored). */
static int place_points(x3p_read *r, surface *s)
{
    double *xc = r->vals[0], *yc = r->vals[1], *h = r->vals[2];
    size_t nx = r->nx, ny = r->ny;
    for (size_t i = 0; i < r->count; i++)
        if ((xc && !isfinite(xc[i])) || (yc && !isfinite(yc[i])) || !isfinite(h[i])) {
            h[i] = NAN;
            if (xc) xc[i] = NAN;
            if (yc) yc[i] = NAN;
        }
    double dx = r->ax[0].increment, dy = r->ax[1].increment;
    if ((xc && regular_step(&r->ax[0], xc, nx, ny, 1, &dx, r->err, r->errn) != 0) ||
        (yc && regular_step(&r->ax[1], yc, nx, ny, 0, &dy, r->err, r->errn) != 0))
        return -1;
    if (dx < 0) /* a decreasing x axis: each row mirrored */
        for (size_t j = 0; j < ny; j++)
            for (size_t i = 0; i < nx / 2; i++) {
                double t = h[j * nx + i];
                h[j * nx + i] = h[j * nx + nx - 1 - i], h[j * nx + nx - 1 - i] = t;
            }
    if (dy < 0) /* a decreasing y axis: the rows in reverse order */
        for (size_t j = 0; j < ny / 2; j++)
            for (size_t i = 0; i < nx; i++) {
                double t = h[j * nx + i];
                h[j * nx + i] = h[(ny - 1 - j) * nx + i], h[(ny - 1 - j) * nx + i] = t;
            }
    s->kind = SURFACE_HEIGHTS, s->nx = nx, s->ny = ny, s->dx = fabs(dx), s->dy = fabs(dy), s->z_scale = 1.0;
    return 0;
}

/* main.xml's steps once it is parsed: its checksum, the grid, the points (inline or binary), their placement. */
static int read_main(x3p_read *r, const unsigned char *xml, size_t xl, surface *s)
{
    if (check_main_md5(r, xml, xl) || read_grid(r)) return -1;
    size_t count = r->count;
    if (!(s->h = malloc(count * sizeof *s->h)) ||
        (r->ax[0].absolute && !(r->vals[0] = malloc(count * sizeof(double)))) ||
        (r->ax[1].absolute && !(r->vals[1] = malloc(count * sizeof(double)))))
        return surface_fail(r->err, r->errn, "out of memory");
    r->vals[2] = s->h;
    xmlNode *list = child(r->root, (const char *[]){"Record3", "DataList", NULL});
    char link[256] = "";
    text_of(r->root, (const char *[]){"Record3", "DataLink", "PointDataLink", NULL}, link, sizeof link);
    int rc = list      ? read_inline(r, list)
             : link[0] ? read_binary(r, link)
                       : surface_fail(r->err, r->errn, "Record3 has neither a DataList nor a DataLink's PointDataLink");
    return rc ? rc : place_points(r, s);
}

int surface_parse_x3p(const unsigned char *data, size_t n, surface *s, char *err, size_t errn)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(data, n, 0, &ze);
    zip_t *z = src ? zip_open_from_source(src, ZIP_RDONLY | ZIP_CHECKCONS, &ze) : NULL;
    if (!z) {
        if (src) zip_source_free(src);
        int code = zip_error_code_zip(&ze);
        zip_error_fini(&ze);
        return surface_fail(err, errn, "not a readable zip archive%s",
                            code == ZIP_ER_INCONS ? " (its directory and its entries disagree)" : "");
    }
    zip_error_fini(&ze);
    x3p_read r = {.z = z, .err = err, .errn = errn};
    int rc = -1;
    size_t xl = 0;
    unsigned char *xml = NULL;
    xmlDoc *doc = NULL;
    char path[600], why[400];
    if (find_main(z, r.base, sizeof r.base, err, errn) < 0) goto done;
    snprintf(path, sizeof path, "%smain.xml", r.base);
    if (!(xml = member(z, path, 1 << 26, &xl, why, sizeof why))) {
        rc = surface_fail(err, errn, "%s", why);
        goto done;
    }
    if (xl > INT_MAX) {
        rc = surface_fail(err, errn, "main.xml is too large");
        goto done;
    }
    doc = xmlReadMemory((const char *)xml, (int)xl, "main.xml", NULL,
                        XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING | XML_PARSE_HUGE);
    if (!(r.root = doc ? xmlDocGetRootElement(doc) : NULL)) {
        rc = surface_fail(err, errn, "main.xml is not well-formed XML");
        goto done;
    }
    rc = read_main(&r, xml, xl, s);
done:
    if (rc != 0) free(s->h), s->h = NULL;
    if (doc) xmlFreeDoc(doc);
    free(xml), free(r.vals[0]), free(r.vals[1]);
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
    for (size_t i = 0; i < count; i++) {
        double v = s->h[i] * (s->z_scale > 0 ? s->z_scale : 1.0);
        uint64_t u;
        memcpy(&u, &v, 8);
        for (int k = 0; k < 8; k++) bin[i * 8 + (size_t)k] = (unsigned char)(u >> (8 * k));
    }
    /* the checksums the standard asks for, where the build has MD5 */
    char bin_md5[33] = "";
    int have_md5 = md5_hex(bin, count * 8, bin_md5) == 0;
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
             "  <DataLink><PointDataLink>bindata/data.bin</PointDataLink>%s%s%s</DataLink></Record3>\n"
             "%s</p:ISO5436_2>\n",
             s->dx, s->dy, s->nx, s->ny, have_md5 ? "<MD5ChecksumPointData>" : "", have_md5 ? bin_md5 : "",
             have_md5 ? "</MD5ChecksumPointData>" : "",
             have_md5 ? " <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>\n" : "");
    /* md5checksum.hex as md5sum writes it */
    char sum[64] = "";
    if (have_md5 && md5_hex((const unsigned char *)xml, strlen(xml), sum) == 0) strcat(sum, " *main.xml\n");
    zip_source_t *a = zip_source_buffer(z, xml, strlen(xml), 0), *b = zip_source_buffer(z, bin, count * 8, 0),
                 *c = sum[0] ? zip_source_buffer(z, sum, strlen(sum), 0) : NULL;
    int ok = a && b && (c || !sum[0]) && zip_file_add(z, "main.xml", a, ZIP_FL_ENC_UTF_8) >= 0 &&
             zip_file_add(z, "bindata/data.bin", b, ZIP_FL_ENC_UTF_8) >= 0 &&
             (!c || zip_file_add(z, "md5checksum.hex", c, ZIP_FL_ENC_UTF_8) >= 0);
    if (!ok) {
        if (a) zip_source_free(a);
        if (b) zip_source_free(b);
        if (c) zip_source_free(c);
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
