/* A command's way out and its output: die, files written as a shell redirect would write them (atomic where that
 * keeps what a redirect keeps), the folders it makes, progress bars on a terminal. The ggx command's, and its tests'.
 * SPDX-License-Identifier: MIT */
#ifndef GGX_OUTPUT_H
#define GGX_OUTPUT_H

#include <setjmp.h>
#include <stddef.h>
#include <stdio.h>

/* Prints "ggx: <message>" on stderr and exits with status 2 (bad input, unwritable output). When cli_die_jump is
 * set (by the fuzz target of the parsers) it jumps there silently instead. */
void die(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));
extern jmp_buf *cli_die_jump;

/* ---- output files ----
 * A path given to out_open (the command's --out) behaves as a shell redirect (`> PATH`) would, and is atomic where
 * that keeps what a redirect keeps:
 * - "-" or no path: standard output.
 * - A descriptor of the process named as a file (/dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N, or a link to
 *   one) is written through that descriptor as the caller opened it: nothing truncated, an appending descriptor
 *   (`>> log`) appended to.
 * - A new file, or an existing regular file (or the target of a symbolic link to one, the link kept) of one name
 *   (link count 1) and no extended attributes, is written to a temporary name in its folder and renamed over it when
 *   complete, keeping its permissions and owner: no partial file is ever left, and the temporary is removed on
 *   every error and on SIGINT, SIGTERM, SIGHUP and SIGPIPE. The temporary's name is the file's with ".tmpXXXXXX"
 *   added, the file's name cut where the two would pass the folder's longest name.
 * - Anything else is written in place, as a redirect writes it (truncated, then written): a device, a FIFO or a
 *   socket; a file with hard links (every name sees the new content) or with extended attributes (ACLs among them:
 *   they are kept); a file whose folder the user may not write (no temporary can be made there) or whose owner the
 *   user cannot give a replacement; a dangling symbolic link (its target created through it). A new file whose
 *   temporary name passes the system's limit on paths is created in place and removed on an error or signal.
 * A file the user may not write is refused, as a redirect refuses it. Every write is checked: a failure is one
 * "ggx: cannot write" line and exit status 2; a reader that has gone (EPIPE) ends the command quietly with status
 * 141, as SIGPIPE would. */
typedef struct out_file {
    FILE *f;
    char *path; /* the file finally written (a link's target) */
    int slot;   /* its temporary's (or its created file's) entry in the pending list, or -1 (in place, stdout) */
    unsigned mode;
} out_file;
void out_open(out_file *o, const char *path);
void out_close(out_file *o); /* flush, check, rename; dies on error */
void out_check(out_file *o); /* dies (or ends quietly on EPIPE) if a write has failed: for long outputs */
/* out_open, the n bytes of data, out_close: a file made whole in memory (an encoded image), put in place the same way */
void out_write_file(const char *path, const unsigned char *data, size_t n);
void out_stdout_failed(void); /* a failed write to stdout: exit 141 on EPIPE, else die */
void out_flush_stdout(void);  /* flushes stdout, out_stdout_failed() on any error so far */
/* A set of files written all or none: after out_begin_set, out_close keeps each finished file under its temporary
 * name; out_commit_set renames them all. An error before the commit removes every one. (A file written in place is
 * written as it comes: only the new files among those are removed.) */
void out_begin_set(void);
void out_commit_set(void);
/* The descriptor path names (/dev/stdout, /dev/fd/N, /proc/self/fd/N or a link to one of them), or -1: a file name
 * made of digits in this process's folder of descriptors, following symbolic links. */
int out_descriptor(const char *path);
/* 1 when path ends with ext (".png"), in any case: the one test of a file name's extension in the command. */
int path_has_ext(const char *path, const char *ext);
/* printf into a string of the length needed (malloc'd): paths have no fixed limit; dies when out of memory. */
char *alloc_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Makes the output folder dir (one level: a folder that exists, or that another process makes at the same time, is
 * success); dies if it cannot be made or is not writable. A folder it makes is removed again, when empty, on every
 * way out before out_keep_dirs (exit, and the signals that remove the temporaries), so that a failed or interrupted
 * run leaves none; what others put in it stays. */
void ensure_dir(const char *dir);
void out_keep_dirs(void); /* the run is complete: the folders ensure_dir made stay */

/* ---- progress on a terminal ----
 * A bar on stderr, redrawn in place: "  LABEL [#####.....]  42%". progress_end draws 100% and ends the line.
 * progress_wanted: the --progress / --no-progress choice (1, 0), or by default (-1) whether stderr is a terminal. */
int progress_wanted(int option);
void progress_show(const char *label, long done, long total);
void progress_end(const char *label, long total);

#endif
