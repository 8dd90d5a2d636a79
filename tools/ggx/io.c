/* Output files written atomically, and PNG images with a small bitmap font. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <png.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

void ensure_dir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) die("output folder '%s' is not a folder", dir);
    } else if (mkdir(dir, 0777) != 0) {
        die("cannot create output folder '%s': %s", dir, strerror(errno));
    }
    if (access(dir, W_OK) != 0) die("output folder '%s' is not writable", dir);
}

/* ---- pending temporaries ----
 * The temporary files being written, and those of a set (out_begin_set) finished but not yet renamed. They are
 * removed on every way out that does not rename them: exit (atexit: die() exits), and the signals that end a
 * command (SIGINT, SIGTERM, SIGHUP, SIGPIPE: the handler unlinks them, then ends the process by the same signal).
 * The handler reads only this array; an entry is published after its string is complete and cleared before it is
 * freed. */
enum { MAX_PENDING = 64 };
static char *volatile pending[MAX_PENDING];
static char *set_path[MAX_PENDING]; /* the final names of a set's finished temporaries, by pending slot */
static int set_open;

static void unlink_pending(void)
{
    for (int i = 0; i < MAX_PENDING; i++) {
        char *t = pending[i];
        if (t) unlink(t);
    }
}

static void on_signal(int sig)
{
    unlink_pending();
    signal(sig, SIG_DFL);
    raise(sig);
}

static void install_cleanup(void)
{
    static int done;
    if (done) return;
    done = 1;
    atexit(unlink_pending);
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
    for (unsigned i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction old, sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        /* a signal the caller ignores (nohup, a runner that ignores SIGPIPE) stays ignored */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(sigs[i], &sa, NULL);
    }
}

static int add_pending(char *tmp)
{
    for (int i = 0; i < MAX_PENDING; i++)
        if (!pending[i]) {
            pending[i] = tmp;
            return i;
        }
    die("too many output files at once");
}

static void drop_pending(int slot)
{
    char *t = pending[slot];
    pending[slot] = NULL;
    free(t);
    free(set_path[slot]);
    set_path[slot] = NULL;
}

static char *dup_or_die(const char *s)
{
    char *d = strdup(s);
    if (!d) die("out of memory");
    return d;
}

void out_stdout_failed(void)
{
    /* the error of the failed write is gone by now; flushing again repeats it and sets errno */
    clearerr(stdout);
    if (fputc('\n', stdout) != EOF && fflush(stdout) == 0) errno = EIO;
    if (errno == EPIPE) exit(141); /* the reader has gone: end quietly, as SIGPIPE would */
    die("cannot write to standard output: %s", strerror(errno));
}

void out_flush_stdout(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) out_stdout_failed();
}

int progress_wanted(int option) { return option >= 0 ? option : isatty(2); }

void progress_show(const char *label, long done, long total)
{
    int width = 40, filled = (int)(width * (double)done / (double)total);
    fprintf(stderr, "\r  %-14s [", label);
    for (int i = 0; i < width; i++) fputc(i < filled ? '#' : '.', stderr);
    fprintf(stderr, "] %3d%%", (int)(100.0 * (double)done / (double)total));
    fflush(stderr);
}

void progress_end(const char *label, long total)
{
    progress_show(label, total, total);
    fputc('\n', stderr);
}

void out_check(out_file *o)
{
    if (!ferror(o->f)) return;
    if (o->f == stdout) out_stdout_failed();
    die("cannot write '%s': %s", o->path, strerror(errno ? errno : EIO));
}

static void open_in_place(out_file *o, const char *path)
{
    o->f = fopen(path, "wb");
    if (!o->f) die("cannot write '%s': %s", path, strerror(errno));
    o->path = dup_or_die(path);
}

void out_open(out_file *o, const char *path)
{
    memset(o, 0, sizeof *o);
    o->slot = -1;
    install_cleanup();
    if (!path || strcmp(path, "-") == 0) {
        o->f = stdout;
        return;
    }
    struct stat st, lst;
    const char *target = path;
    char *resolved = NULL;
    mode_t mode;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) die("cannot write '%s': it is a folder", path);
        if (!S_ISREG(st.st_mode)) {
            open_in_place(o, path); /* a device, a FIFO, a socket (or a link to one): never replaced */
            return;
        }
        mode = st.st_mode & 07777;
        if (lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
            /* a link to a regular file: its target is replaced, the link kept */
            resolved = realpath(path, NULL);
            if (!resolved) die("cannot write '%s': %s", path, strerror(errno));
            target = resolved;
        }
    } else if (errno == ENOENT && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        open_in_place(o, path); /* a dangling link: the file it names is created through it */
        return;
    } else if (errno != ENOENT) {
        die("cannot write '%s': %s", path, strerror(errno));
    } else {
        mode_t mask = umask(0);
        umask(mask);
        mode = 0666 & ~mask;
    }
    size_t n = strlen(target) + 16;
    char *tmp = malloc(n);
    if (!tmp) die("out of memory");
    snprintf(tmp, n, "%s.tmpXXXXXX", target);
    o->path = dup_or_die(target);
    o->mode = mode;
    free(resolved);
    sigset_t all, old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old); /* no signal between creating the file and recording it */
    int fd = mkstemp(tmp);
    int e = errno;
    if (fd >= 0) o->slot = add_pending(tmp);
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (fd < 0) {
        free(tmp);
        die("cannot write '%s': %s", path, strerror(e));
    }
    o->f = fdopen(fd, "wb");
    if (!o->f) die("cannot write '%s': %s", path, strerror(errno));
}

void out_close(out_file *o)
{
    if (o->f == stdout) {
        out_flush_stdout();
        return;
    }
    int bad = ferror(o->f), e = bad ? (errno ? errno : EIO) : 0;
    if (fflush(o->f) != 0 && !bad) bad = 1, e = errno;
    if (fclose(o->f) != 0 && !bad) bad = 1, e = errno;
    o->f = NULL;
    if (bad) die("cannot write '%s': %s", o->path, strerror(e)); /* the temporary goes at exit */
    if (o->slot >= 0) {
        chmod(pending[o->slot], o->mode);
        if (set_open) {
            set_path[o->slot] = o->path; /* renamed by out_commit_set */
            o->path = NULL;
        } else {
            if (rename(pending[o->slot], o->path) != 0) die("cannot write '%s': %s", o->path, strerror(errno));
            drop_pending(o->slot);
        }
    }
    free(o->path);
    memset(o, 0, sizeof *o);
}

void out_begin_set(void) { set_open = 1; }

void out_commit_set(void)
{
    set_open = 0;
    for (int i = 0; i < MAX_PENDING; i++) {
        if (!set_path[i]) continue;
        if (rename(pending[i], set_path[i]) != 0) die("cannot write '%s': %s", set_path[i], strerror(errno));
        drop_pending(i);
    }
}

image image_new(int w, int h, unsigned char r, unsigned char g, unsigned char b)
{
    image im = {w, h, malloc((size_t)w * (size_t)h * 3)};
    if (!im.rgb) die("out of memory");
    for (long i = 0; i < (long)w * h; i++) im.rgb[3 * i] = r, im.rgb[3 * i + 1] = g, im.rgb[3 * i + 2] = b;
    return im;
}

void image_free(image *im)
{
    free(im->rgb);
    im->rgb = NULL;
}

void image_set(image *im, int x, int y, const unsigned char c[3])
{
    if (x < 0 || y < 0 || x >= im->w || y >= im->h) return;
    memcpy(im->rgb + 3 * ((long)y * im->w + x), c, 3);
}

/* A 5 x 7 font of our own: each glyph is 7 rows, the low 5 bits of each row from left (bit 4) to right (bit 0). */
typedef struct glyph {
    char c;
    unsigned char rows[7];
} glyph;
static const glyph FONT[] = {
    {'0', {14, 17, 19, 21, 25, 17, 14}}, {'1', {4, 12, 4, 4, 4, 4, 14}},      {'2', {14, 17, 1, 2, 4, 8, 31}},
    {'3', {31, 2, 4, 2, 1, 17, 14}},     {'4', {2, 6, 10, 18, 31, 2, 2}},     {'5', {31, 16, 30, 1, 1, 17, 14}},
    {'6', {6, 8, 16, 30, 17, 17, 14}},   {'7', {31, 1, 2, 4, 8, 8, 8}},       {'8', {14, 17, 17, 14, 17, 17, 14}},
    {'9', {14, 17, 17, 15, 1, 2, 12}},   {'.', {0, 0, 0, 0, 0, 12, 12}},      {'-', {0, 0, 0, 31, 0, 0, 0}},
    {'+', {0, 4, 4, 31, 4, 4, 0}},       {',', {0, 0, 0, 0, 12, 4, 8}},       {'(', {2, 4, 8, 8, 8, 4, 2}},
    {')', {8, 4, 2, 2, 2, 4, 8}},        {'=', {0, 0, 31, 0, 31, 0, 0}},      {':', {0, 12, 12, 0, 12, 12, 0}},
    {'/', {0, 1, 2, 4, 8, 16, 0}},       {' ', {0, 0, 0, 0, 0, 0, 0}},        {'A', {14, 17, 17, 31, 17, 17, 17}},
    {'B', {30, 17, 17, 30, 17, 17, 30}}, {'C', {14, 17, 16, 16, 16, 17, 14}}, {'D', {30, 17, 17, 17, 17, 17, 30}},
    {'E', {31, 16, 16, 30, 16, 16, 31}}, {'F', {31, 16, 16, 30, 16, 16, 16}}, {'G', {14, 17, 16, 23, 17, 17, 15}},
    {'H', {17, 17, 17, 31, 17, 17, 17}}, {'I', {14, 4, 4, 4, 4, 4, 14}},     {'J', {7, 2, 2, 2, 2, 18, 12}},
    {'K', {17, 18, 20, 24, 20, 18, 17}}, {'L', {16, 16, 16, 16, 16, 16, 31}}, {'M', {17, 27, 21, 21, 17, 17, 17}},
    {'N', {17, 17, 25, 21, 19, 17, 17}}, {'O', {14, 17, 17, 17, 17, 17, 14}}, {'P', {30, 17, 17, 30, 16, 16, 16}},
    {'Q', {14, 17, 17, 17, 21, 18, 13}}, {'R', {30, 17, 17, 30, 20, 18, 17}}, {'S', {15, 16, 16, 14, 1, 1, 30}},
    {'T', {31, 4, 4, 4, 4, 4, 4}},       {'U', {17, 17, 17, 17, 17, 17, 14}}, {'V', {17, 17, 17, 17, 17, 10, 4}},
    {'W', {17, 17, 17, 21, 21, 21, 10}}, {'X', {17, 17, 10, 4, 10, 17, 17}},  {'Y', {17, 17, 10, 4, 4, 4, 4}},
    {'Z', {31, 1, 2, 4, 8, 16, 31}},
};

void image_text(image *im, int x, int y, const char *text, int scale, const unsigned char c[3])
{
    for (; *text; text++, x += 6 * scale) {
        char ch = *text >= 'a' && *text <= 'z' ? (char)(*text - 'a' + 'A') : *text;
        const glyph *g = NULL;
        for (unsigned k = 0; k < sizeof FONT / sizeof FONT[0]; k++)
            if (FONT[k].c == ch) g = &FONT[k];
        if (!g) continue;
        for (int r = 0; r < 7; r++)
            for (int b = 0; b < 5; b++)
                if (g->rows[r] & (1 << (4 - b)))
                    for (int dy = 0; dy < scale; dy++)
                        for (int dx = 0; dx < scale; dx++) image_set(im, x + b * scale + dx, y + r * scale + dy, c);
    }
}

/* Dark blue-black through purple and orange to pale yellow, piecewise linear between our own control colours,
 * ordered by lightness so that brighter always means denser. */
void colormap(double t, unsigned char out[3])
{
    static const double ctrl[][3] = {{0.02, 0.02, 0.08}, {0.25, 0.05, 0.45}, {0.62, 0.15, 0.45},
                                     {0.90, 0.40, 0.20}, {0.98, 0.75, 0.25}, {0.99, 0.98, 0.75}};
    const int n = sizeof ctrl / sizeof ctrl[0];
    if (!(t > 0)) t = 0;
    if (t > 1) t = 1;
    double x = t * (n - 1);
    int i = (int)x;
    if (i >= n - 1) i = n - 2;
    double f = x - i;
    for (int k = 0; k < 3; k++) out[k] = (unsigned char)(255.0 * ((1 - f) * ctrl[i][k] + f * ctrl[i + 1][k]) + 0.5);
}

/* libpng's errors come back here, silently (the command prints one line of its own); its warnings are dropped. */
static char png_message[128];
static void png_fail(png_structp png, png_const_charp msg)
{
    snprintf(png_message, sizeof png_message, "%s", msg);
    png_longjmp(png, 1);
}
static void png_quiet(png_structp png, png_const_charp msg) { (void)png, (void)msg; }

void write_png(const image *im, const char *path)
{
    out_file o;
    out_open(&o, path);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, png_fail, png_quiet);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) die("cannot write '%s': libpng failed to start", path);
    if (setjmp(png_jmpbuf(png))) {
        /* a failed write (full disk) shows as the stream's error; anything else is libpng's message */
        if (ferror(o.f)) out_check(&o);
        die("cannot write '%s': %s", path, png_message);
    }
    png_init_io(png, o.f);
    png_set_IHDR(png, info, (png_uint_32)im->w, (png_uint_32)im->h, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < im->h; y++) png_write_row(png, im->rgb + 3 * (long)y * im->w);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    out_close(&o);
}
