/* A command's way out (die) and its output files, written atomically where a replacement keeps what a redirect keeps
 * and in place elsewhere; the folders the command makes; progress bars (output.h). SPDX-License-Identifier: MIT */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#if defined(__linux__)
#include <sys/xattr.h>
#endif
#include <unistd.h>

#include "output.h"

jmp_buf *cli_die_jump;

void die(const char *fmt, ...)
{
    if (cli_die_jump) longjmp(*cli_die_jump, 1);
    va_list ap;
    va_start(ap, fmt);
    fputs("ggx: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    exit(2);
}

char *alloc_printf(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (!s) die("out of memory");
    va_start(ap, fmt);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return s;
}

int path_has_ext(const char *path, const char *ext)
{
    size_t n = path ? strlen(path) : 0, k = strlen(ext);
    return n >= k && strcasecmp(path + n - k, ext) == 0;
}

/* ---- pending temporaries and folders made ----
 * The temporary files being written (and new files created in place), those of a set (out_begin_set) finished but
 * not yet renamed, and the folders ensure_dir made. They are removed on every way out that does not complete them:
 * exit (atexit: die() exits), and the signals that end a command (SIGINT, SIGTERM, SIGHUP, SIGPIPE: the handler
 * unlinks the files and removes the folders if empty, then ends the process by the same signal). The handler reads
 * only these arrays; an entry is published after its string is complete and cleared before it is freed. */
enum { MAX_PENDING = 64 };
static char *volatile pending[MAX_PENDING];
static char *set_path[MAX_PENDING];     /* the final names of a set's finished temporaries, by pending slot */
static char pending_final[MAX_PENDING]; /* 1: the entry is the final file, created in place (nothing to rename) */
static int set_open;
enum { MAX_MADE = 4 };
static char *volatile made[MAX_MADE];

static void unlink_pending(void)
{
    for (int i = 0; i < MAX_PENDING; i++) {
        char *t = pending[i];
        if (t) unlink(t);
    }
    for (int i = MAX_MADE - 1; i >= 0; i--) {
        char *d = made[i];
        if (d) rmdir(d); /* only when empty: what another process put there stays */
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
    pending_final[slot] = 0;
}

static char *dup_or_die(const char *s)
{
    char *d = strdup(s);
    if (!d) die("out of memory");
    return d;
}

void ensure_dir(const char *dir)
{
    if (strcmp(dir, "-") == 0)
        die("--out: '-' is standard output, which cannot hold a folder of files: give a folder's name (./- for one "
            "named -)");
    install_cleanup();
    char *name = dup_or_die(dir);
    sigset_t all, old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old); /* no signal between making the folder and recording it */
    int r = mkdir(dir, 0777), e = errno, slot = -1;
    if (r == 0)
        for (int i = 0; i < MAX_MADE && slot < 0; i++)
            if (!made[i]) made[slot = i] = name;
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (slot < 0) free(name);
    if (r == 0 && slot < 0) {
        rmdir(dir);
        die("too many output folders at once");
    }
    /* mkdir first: a folder that another process makes between a check and mkdir (EEXIST) is success */
    struct stat st;
    if (r != 0) {
        if (stat(dir, &st) != 0) die("cannot create output folder '%s': %s", dir, strerror(e));
        if (!S_ISDIR(st.st_mode)) die("output folder '%s' is not a folder", dir);
    }
    if (access(dir, W_OK) != 0) die("output folder '%s' is not writable", dir);
}

void out_keep_dirs(void)
{
    for (int i = 0; i < MAX_MADE; i++) {
        char *d = made[i];
        made[i] = NULL;
        free(d);
    }
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

/* A new file created in place (its temporary could not be made): it is the command's, so it is removed on every way
 * out that does not complete it, as a temporary is. One that appears meanwhile is written in place. */
static void open_created(out_file *o, const char *path)
{
    char *name = dup_or_die(path);
    sigset_t all, old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old); /* no signal between creating the file and recording it */
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL, 0666);
    int e = errno;
    if (fd >= 0) o->slot = add_pending(name), pending_final[o->slot] = 1;
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (fd < 0) {
        free(name);
        if (e == EEXIST) {
            open_in_place(o, path);
            return;
        }
        die("cannot write '%s': %s", path, strerror(e));
    }
    o->f = fdopen(fd, "wb");
    if (!o->f) die("cannot write '%s': %s", path, strerror(errno));
    o->path = dup_or_die(path);
}

/* The descriptor path names, already open: standard output is the command's stdout (so that its writes keep their
 * order), another a duplicate of it. Its offset and flags are the caller's: an appending descriptor appends. */
static void open_descriptor(out_file *o, const char *path, int fd)
{
    if (fd == 1) {
        o->f = stdout;
        return;
    }
    int d = fcntl(fd, F_DUPFD_CLOEXEC, 3);
    if (d < 0) die("cannot write '%s': %s", path, strerror(errno));
    o->f = fdopen(d, "wb");
    if (!o->f) die("cannot write '%s': %s", path, strerror(errno));
    o->path = dup_or_die(path);
}

/* 1 when dir is this process's folder of descriptors (/dev/fd, /proc/self/fd, /proc/PID/fd or a thread's). */
static int descriptor_folder(const char *dir)
{
    char *real = realpath(dir, NULL);
    if (!real) return 0;
    char own[48];
    snprintf(own, sizeof own, "/proc/%ld/", (long)getpid());
    size_t k = strlen(own);
    int yes = strcmp(real, "/dev/fd") == 0;
    if (!yes && strncmp(real, own, k) == 0) {
        const char *r = real + k;
        if (strncmp(r, "task/", 5) == 0) {
            r += 5 + strspn(r + 5, "0123456789");
            r = *r == '/' ? r + 1 : "";
        }
        yes = strcmp(r, "fd") == 0;
    }
    free(real);
    return yes;
}

/* The target of the symbolic link p (malloc'd), NULL if p is none. */
static char *read_link(const char *p)
{
    for (size_t n = 256;; n *= 2) {
        char *b = malloc(n);
        if (!b) die("out of memory");
        ssize_t k = readlink(p, b, n);
        if (k < 0) {
            free(b);
            return NULL;
        }
        if ((size_t)k < n) {
            b[k] = '\0';
            return b;
        }
        free(b);
    }
}

int out_descriptor(const char *path)
{
    if (!path || !*path) return -1;
    static const char *const STD[3] = {"/dev/stdin", "/dev/stdout", "/dev/stderr"};
    char *p = dup_or_die(path);
    int fd = -1;
    for (int hop = 0; hop < 40 && fd < 0; hop++) { /* 40: the kernel's limit on links followed */
        for (int i = 0; i < 3; i++)
            if (strcmp(p, STD[i]) == 0) fd = i;
        char *slash = strrchr(p, '/');
        const char *base = slash ? slash + 1 : p;
        size_t digits = strspn(base, "0123456789");
        if (fd < 0 && digits > 0 && digits < 10 && base[digits] == '\0') {
            char *dir = slash ? alloc_printf("%.*s", slash == p ? 1 : (int)(slash - p), p) : dup_or_die(".");
            if (descriptor_folder(dir)) fd = atoi(base);
            free(dir);
        }
        if (fd >= 0) break;
        struct stat ls;
        char *t = lstat(p, &ls) == 0 && S_ISLNK(ls.st_mode) ? read_link(p) : NULL;
        if (!t) break;
        if (t[0] != '/' && slash) { /* relative to the link's folder */
            char *j = alloc_printf("%.*s/%s", (int)(slash - p), p, t);
            free(t);
            t = j;
        }
        free(p);
        p = t;
    }
    free(p);
    return fd;
}

/* 1 when the file has extended attributes (ACLs among them), which a replacement would not carry. */
static int has_xattrs(const char *path)
{
#if defined(__linux__)
    return listxattr(path, NULL, 0) > 0;
#else
    (void)path;
    return 0;
#endif
}

/* The temporary's name beside target: its name, cut where needed so that name and suffix fit the folder's longest
 * file name, then ".tmpXXXXXX" (mkstemp's pattern). */
static char *temp_name(const char *target)
{
    const char *slash = strrchr(target, '/');
    size_t dlen = slash ? (size_t)(slash - target) + 1 : 0; /* the folder, with its slash */
    const char *base = target + dlen;
    char *dir = dlen ? alloc_printf("%.*s", (int)dlen, target) : dup_or_die(".");
    long name_max = pathconf(dir, _PC_NAME_MAX);
    free(dir);
    if (name_max <= 0) name_max = NAME_MAX;
    size_t keep = strlen(base), suffix = strlen(".tmpXXXXXX");
    if (keep + suffix > (size_t)name_max) {
        keep = (size_t)name_max > suffix ? (size_t)name_max - suffix : 0;
        while (keep > 0 && ((unsigned char)base[keep] & 0xC0) == 0x80) keep--; /* not inside a UTF-8 character */
    }
    return alloc_printf("%.*s%.*s.tmpXXXXXX", (int)dlen, target, (int)keep, base);
}

/* The one place that decides how a file is written: in place (as a redirect writes it) or through a temporary
 * renamed over it. cli.h states the rules. */
void out_open(out_file *o, const char *path)
{
    memset(o, 0, sizeof *o);
    o->slot = -1;
    install_cleanup();
    if (!path || strcmp(path, "-") == 0) {
        o->f = stdout;
        return;
    }
    int fd = out_descriptor(path);
    if (fd >= 0) {
        open_descriptor(o, path, fd); /* /dev/stdout, /dev/fd/N: as the caller opened them */
        return;
    }
    struct stat st, lst;
    const char *target = path;
    char *resolved = NULL;
    mode_t mode;
    int have_old = stat(path, &st) == 0;
    if (have_old) {
        if (S_ISDIR(st.st_mode)) die("cannot write '%s': it is a folder", path);
        /* as a redirect: a file the user may not write is an error, and stays as it was */
        if (S_ISREG(st.st_mode) && access(path, W_OK) != 0) die("cannot write '%s': %s", path, strerror(errno));
        /* what a replacement would not keep: a device, a FIFO, a socket (or a link to one); a file of several names
         * (hard links); extended attributes (ACLs among them) */
        if (!S_ISREG(st.st_mode) || st.st_nlink > 1 || has_xattrs(path)) {
            open_in_place(o, path);
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
        die("cannot write '%s': %s", path, strerror(errno)); /* a name too long among them */
    } else {
        mode_t mask = umask(0);
        umask(mask);
        mode = 0666 & ~mask;
    }
    char *tmp = temp_name(target), *final = dup_or_die(target); /* a link's target: renamed over, the link kept */
    free(resolved);
    sigset_t all, old;
    sigfillset(&all);
    sigprocmask(SIG_BLOCK, &all, &old); /* no signal between creating the file and recording it */
    int tfd = mkstemp(tmp);
    int e = errno;
    if (tfd >= 0) o->slot = add_pending(tmp);
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (tfd < 0) {
        free(tmp);
        free(final);
        /* no temporary beside it (a folder the user may not write, a path at the system's limit): the file is
         * written in place, as a redirect writes it */
        if (e != EACCES && e != EPERM && e != ENAMETOOLONG) die("cannot write '%s': %s", path, strerror(e));
        if (have_old) open_in_place(o, path);
        else open_created(o, path);
        return;
    }
    /* The replacement keeps the file's owner and group; where the user cannot give it them (another user's file
     * in a folder of theirs), the file is written in place, as a redirect writes it. */
    if (have_old && (st.st_uid != geteuid() || st.st_gid != getegid()) && fchown(tfd, st.st_uid, st.st_gid) != 0) {
        close(tfd);
        unlink(tmp);
        drop_pending(o->slot);
        o->slot = -1;
        free(final);
        open_in_place(o, path);
        return;
    }
    o->path = final;
    o->mode = mode;
    o->f = fdopen(tfd, "wb");
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
    if (bad) die("cannot write '%s': %s", o->path, strerror(e)); /* a temporary (or a file created) goes at exit */
    if (o->slot >= 0) {
        if (!pending_final[o->slot]) chmod(pending[o->slot], o->mode);
        if (set_open) {
            set_path[o->slot] = o->path; /* renamed (or, created in place, kept) by out_commit_set */
            o->path = NULL;
        } else {
            if (!pending_final[o->slot] && rename(pending[o->slot], o->path) != 0)
                die("cannot write '%s': %s", o->path, strerror(errno));
            drop_pending(o->slot);
        }
    }
    free(o->path);
    memset(o, 0, sizeof *o);
}

void out_write_file(const char *path, const unsigned char *data, size_t n)
{
    out_file f;
    out_open(&f, path);
    if (fwrite(data, 1, n, f.f) != n) out_check(&f);
    out_close(&f);
}

void out_begin_set(void) { set_open = 1; }

void out_commit_set(void)
{
    set_open = 0;
    for (int i = 0; i < MAX_PENDING; i++) {
        if (!set_path[i]) continue;
        if (!pending_final[i] && rename(pending[i], set_path[i]) != 0)
            die("cannot write '%s': %s", set_path[i], strerror(errno));
        drop_pending(i);
    }
}
