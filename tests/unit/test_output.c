/* The command's output files and folders (libs/output): many processes creating the same folder at once all succeed (a
 * folder that another process made first is success, not "File exists"); a folder ensure_dir made goes again on
 * SIGTERM and SIGINT, one it found stays; the descriptors named as files (/dev/stdout, /dev/fd/N, links to them) and
 * nothing else; extensions in any case; strings of any length. SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "output.h"

enum { ROUNDS = 200, PROCS = 8 };

static int failures;
static void expect(int cond, const char *what)
{
    if (!cond) {
        printf("FAIL: %s\n", what);
        failures++;
    }
}

static int race(const char *base)
{
    int failed = 0;
    for (int r = 0; r < ROUNDS && !failed; r++) {
        char dir[64];
        snprintf(dir, sizeof dir, "%s/d%d", base, r);
        int go[2];
        if (pipe(go) != 0) return perror("pipe"), 1;
        pid_t pid[PROCS];
        for (int p = 0; p < PROCS; p++) {
            pid[p] = fork();
            if (pid[p] == 0) { /* wait for the start, then race the others */
                char c;
                close(go[1]);
                if (read(go[0], &c, 1) != 0) _exit(3);
                ensure_dir(dir);
                _exit(0);
            }
        }
        close(go[0]);
        close(go[1]); /* every child's read returns at once */
        for (int p = 0; p < PROCS; p++) {
            int st;
            waitpid(pid[p], &st, 0);
            if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) failed++;
        }
        rmdir(dir);
    }
    printf("ensure_dir: %d rounds of %d processes, %d failed\n", ROUNDS, PROCS, failed);
    return failed;
}

/* ensure_dir(dir) in a child that then ends by sig: 1 when dir exists afterwards. */
static int survives_signal(const char *dir, int sig)
{
    pid_t pid = fork();
    if (pid == 0) {
        signal(sig, SIG_DFL);
        ensure_dir(dir);
        raise(sig);
        _exit(0);
    }
    int st;
    waitpid(pid, &st, 0);
    expect(WIFSIGNALED(st) && WTERMSIG(st) == sig, "the child ends by the signal");
    struct stat s;
    return stat(dir, &s) == 0;
}

int main(void)
{
    char base[] = "/tmp/ggx-dirrace-XXXXXX";
    if (!mkdtemp(base)) return perror("mkdtemp"), 1;
    expect(race(base) == 0, "ensure_dir raced by several processes");

    /* a folder made by the command goes on SIGTERM and SIGINT; one that was there stays, with what is in it */
    char *made = alloc_printf("%s/made", base), *kept = alloc_printf("%s/kept", base);
    expect(!survives_signal(made, SIGTERM), "a folder ensure_dir made stays after SIGTERM");
    expect(!survives_signal(made, SIGINT), "a folder ensure_dir made stays after SIGINT");
    expect(mkdir(kept, 0777) == 0, "mkdir");
    expect(survives_signal(kept, SIGTERM), "a folder that was there is removed on SIGTERM");

    /* descriptors named as files, directly or through links; digits elsewhere are names */
    expect(out_descriptor("/dev/stdout") == 1 && out_descriptor("/dev/stderr") == 2, "/dev/stdout, /dev/stderr");
    expect(out_descriptor("/dev/fd/3") == 3 && out_descriptor("/proc/self/fd/17") == 17, "/dev/fd/N, /proc/self/fd/N");
    char *pid_fd = alloc_printf("/proc/%ld/fd/4", (long)getpid());
    expect(out_descriptor(pid_fd) == 4, "/proc/PID/fd/N");
    char *link = alloc_printf("%s/log", base), *link2 = alloc_printf("%s/log2", base);
    expect(symlink("/dev/stdout", link) == 0 && symlink("log", link2) == 0, "symlink");
    expect(out_descriptor(link) == 1 && out_descriptor(link2) == 1, "a link (to a link) to /dev/stdout");
    char *digits = alloc_printf("%s/1", kept);
    expect(out_descriptor(digits) == -1 && out_descriptor("1") == -1 && out_descriptor("-") == -1 &&
               out_descriptor("/dev/null") == -1 && out_descriptor("/dev/fd/") == -1,
           "names that are no descriptor");

    /* one test of extensions, in any case */
    expect(path_has_ext("a.png", ".png") && path_has_ext("A.PNG", ".png") && path_has_ext("dir/x.Svg", ".svg") &&
               path_has_ext(".md", ".md"),
           "extensions in any case");
    expect(!path_has_ext("a.png.txt", ".png") && !path_has_ext("png", ".png") && !path_has_ext(NULL, ".png") &&
               !path_has_ext("a.jpg", ".png"),
           "other names");

    /* a string longer than any fixed buffer */
    char *longer = alloc_printf("%0*d/%s", 5000, 7, "level-0.exr");
    expect(strlen(longer) == 5012 && strcmp(longer + 5000, "/level-0.exr") == 0, "alloc_printf of 5012 bytes");

    unlink(link2), unlink(link), rmdir(kept), rmdir(base);
    free(made), free(kept), free(pid_fd), free(link), free(link2), free(digits), free(longer);
    printf("cli io: %s\n", failures ? "FAILED" : "all pass");
    return failures != 0;
}
