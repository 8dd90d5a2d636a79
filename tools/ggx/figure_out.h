/* The command's figures as files: canvases (libs/plot) written through the command's atomic output files, the rules
 * of a figure's --out, and the figure names of --figure. SPDX-License-Identifier: MIT */
#ifndef GGX_TOOL_FIGURE_OUT_H
#define GGX_TOOL_FIGURE_OUT_H

#include "cli.h"
#include "figure.h"

/* canvas_open over out_open(path): the file appears complete at canvas_close_file or not at all; any failure of
 * cairo or of the file is one line and exit 2 (141 for a reader that has gone), as out_close. */
void canvas_open_file(canvas *c, const char *path, canvas_format fmt, int w, int h, int dark);
void canvas_close_file(canvas *c);

/* 1 for "-" (standard output), a descriptor named as a file (/dev/stdout, /dev/fd/N: out_descriptor) and what is
 * not a regular file (a device, a FIFO): written in any format. */
int path_is_stream(const char *path);
/* The format a file name asks for by its extension (.png, .svg, .pdf in any case: path_has_ext), else deflt. */
canvas_format format_of_name(const char *path, canvas_format deflt);
/* The format of a figure's file given by option opt (--out, --figure): its name's, or deflt for a stream; dies with
 * one line for a file name that ends in none of them. */
canvas_format figure_format_of(const char *opt, const char *path, canvas_format deflt);
/* Writes the figure to path: PNG, SVG or PDF as its name says (standard output and devices: fmt), w x h exactly. */
void figure_write(const figure_spec *f, const char *path, canvas_format fmt, int w, int h);
/* The figure named on the command line; dies on an unknown name, listing the names. */
figure_kind figure_from_name(const char *name);

#endif
