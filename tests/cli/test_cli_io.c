/* The command's output folders: many processes creating the same folder at once all succeed (a folder that
 * another process made first is success, not "File exists"). SPDX-License-Identifier: MIT */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"

enum { ROUNDS = 200, PROCS = 8 };

int main(void)
{
    char base[] = "/tmp/ggx-dirrace-XXXXXX";
    if (!mkdtemp(base)) return perror("mkdtemp"), 1;
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
    rmdir(base);
    printf("ensure_dir: %d rounds of %d processes, %d failed\n", ROUNDS, PROCS, failed);
    return failed != 0;
}
