/* The one parallel loop of the project: every threaded pass of the library, the internal libraries and the lab runs
 * through it. SPDX-License-Identifier: MIT */
#ifndef GGX_COMMON_PARALLEL_H
#define GGX_COMMON_PARALLEL_H

/* Runs fn(ctx, k) for every k in [0, count), each k on a thread of its own, k = 0 on the calling thread, and returns
 * when all have returned. A thread that cannot be started (or the bookkeeping of many) costs no work: its k runs on
 * the calling thread after k = 0. Which thread runs which k is the only thing that varies, so a pass whose k-th
 * share depends only on k (a fixed split of the work, partial sums combined in k order) gives the same result for
 * every count of threads that were started. count <= 1 runs fn(ctx, 0) alone (count < 1: nothing). */
void ggx_internal_parallel_for(int count, void (*fn)(void *ctx, int k), void *ctx);

#endif
