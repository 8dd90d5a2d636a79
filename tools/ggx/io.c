/* Output files written atomically, and progress bars. SPDX-License-Identifier: MIT */
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

void ensure_dir(const char *dir)
{
    /* mkdir first: a folder that another process makes between a check and mkdir (EEXIST) is success */
    struct stat st;
    if (mkdir(dir, 0777) != 0) {
        int e = errno;
        if (stat(dir, &st) != 0) die("cannot create output folder '%s': %s", dir, strerror(e));
        if (!S_ISDIR(st.st_mode)) die("output folder '%s' is not a folder", dir);
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
    int have_old = 0;
    if (stat(path, &st) == 0) {
        have_old = 1;
        if (S_ISDIR(st.st_mode)) die("cannot write '%s': it is a folder", path);
        if (!S_ISREG(st.st_mode)) {
            open_in_place(o, path); /* a device, a FIFO, a socket (or a link to one): never replaced */
            return;
        }
        /* as a redirect: a file the user may not write is an error, and stays as it was */
        if (access(path, W_OK) != 0) die("cannot write '%s': %s", path, strerror(errno));
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
    /* The replacement keeps the file's owner and group; where the user cannot give it them (another user's file
     * in a folder of theirs), the file is written in place, as a redirect writes it. */
    if (have_old && (st.st_uid != geteuid() || st.st_gid != getegid()) && fchown(fd, st.st_uid, st.st_gid) != 0) {
        close(fd);
        unlink(tmp);
        drop_pending(o->slot);
        free(o->path);
        o->slot = -1;
        open_in_place(o, path);
        return;
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
        if (rename(pending[i], set_path[i]) != 0) die("cannot write '%s': %s", set_path[i], strerror(errno));
        drop_pending(i);
    }
}
