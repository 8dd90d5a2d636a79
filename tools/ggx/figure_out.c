/* The command's figures as files (figure_out.h). SPDX-License-Identifier: MIT */
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "figure_out.h"

/* A canvas's file: the command's output file and its name for messages. */
typedef struct canvas_file {
    out_file out;
    char *path;
} canvas_file;

static int write_file(void *closure, const unsigned char *data, size_t n)
{
    canvas_file *cf = closure;
    return fwrite(data, 1, n, cf->out.f) == n ? 0 : -1;
}

void canvas_open_file(canvas *c, const char *path, canvas_format fmt, int w, int h, int dark)
{
    canvas_file *cf = calloc(1, sizeof *cf);
    if (!cf) die("out of memory");
    cf->path = alloc_printf("%s", path ? path : "-");
    out_open(&cf->out, path);
    if (canvas_open(c, fmt, w, h, dark, write_file, cf) != 0) die("cannot draw '%s': %s", cf->path, c->error);
}

void canvas_close_file(canvas *c)
{
    canvas_file *cf = c->closure;
    if (canvas_close(c) != 0) {
        if (c->write_failed || ferror(cf->out.f)) out_check(&cf->out);
        die("cannot write '%s': %s", cf->path, c->error);
    }
    out_close(&cf->out);
    free(cf->path);
    free(cf);
}

int path_is_stream(const char *path)
{
    struct stat st;
    return !path || strcmp(path, "-") == 0 || out_descriptor(path) >= 0 ||
           (stat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode));
}

canvas_format format_of_name(const char *path, canvas_format deflt)
{
    static const canvas_format FORMATS[] = {FMT_PNG, FMT_SVG, FMT_PDF};
    for (int i = 0; i < 3; i++)
        if (path_has_ext(path, format_ext(FORMATS[i]))) return FORMATS[i];
    return deflt;
}

canvas_format figure_format_of(const char *opt, const char *path, canvas_format deflt)
{
    canvas_format fmt = format_of_name(path, deflt);
    if (!path_is_stream(path) && !path_has_ext(path, format_ext(fmt)))
        die("%s: '%s' does not name a format: end it in .png, .svg or .pdf (or give - for standard output)", opt, path);
    return fmt;
}

void figure_write(const figure_spec *f, const char *path, canvas_format fmt, int w, int h)
{
    canvas c;
    canvas_open_file(&c, path, fmt, w, h, f->dark);
    figure_draw(c.cr, c.th, 0, 0, w, h, f, NULL);
    canvas_close_file(&c);
}

figure_kind figure_from_name(const char *name)
{
    int k = figure_kind_of(name);
    if (k >= 0) return (figure_kind)k;
    char names[256] = "";
    for (int i = 0; i < FIG_COUNT; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "",
                 figure_name((figure_kind)i));
    die("--figure: unknown figure '%s' (%s)", name ? name : "", names);
}
