// What the C benches share: a clock reading in seconds and the comparison that sorts timings
// (qsort) for their medians. Include after defining _POSIX_C_SOURCE (clock_gettime).
#ifndef RTPBR_BENCH_TIME_H
#define RTPBR_BENCH_TIME_H

#include <time.h>

// Seconds on `clock` (CLOCK_MONOTONIC: wall time; CLOCK_PROCESS_CPUTIME_ID: the CPU time of the
// whole process, lavapipe's worker threads included).
static inline double bench_seconds(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

// qsort's comparison of two doubles, ascending.
static inline int bench_compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

#endif // RTPBR_BENCH_TIME_H
