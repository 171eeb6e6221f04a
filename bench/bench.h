/*
 * bench.h - what every benchmark shares: a monotonic clock, the process's
 * CPU time, and the machine line each table is printed with (CPU model,
 * cores, compiler, date), so that a figure always says where and when it
 * was measured.
 */
#ifndef SVET_BENCH_H
#define SVET_BENCH_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Seconds on a monotonic clock. */
static inline double bench_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU seconds of the whole process, every thread included: the rate per
 * CPU-second that a machine shared with other work disturbs less. */
static inline double bench_cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The CPU's model name from /proc/cpuinfo, or "unknown CPU". */
static inline void bench_cpu_model(char *out, size_t n)
{
    snprintf(out, n, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "model name", 10) == 0) {
            char *c = strchr(line, ':');
            if (c) {
                snprintf(out, n, "%s", c + 2);
                out[strcspn(out, "\n")] = '\0';
            }
            break;
        }
    fclose(f);
}

/* The 1-minute load average (/proc/loadavg), or -1: a figure measured while
 * other jobs ran is noisy, and its table says so. */
static inline double bench_loadavg(void)
{
    double l = -1;
    FILE *f = fopen("/proc/loadavg", "r");
    if (f) {
        if (fscanf(f, "%lf", &l) != 1)
            l = -1;
        fclose(f);
    }
    return l;
}

/* What the load average says of the timings: "load average L: a quiet
 * machine" when it is below half the core count (no other job competed for
 * a core), else "load average L: the machine was shared with other jobs,
 * so the rates are low and noisy". Written into buf; returns buf. */
static inline const char *bench_load_words(char *buf, size_t n)
{
    double l = bench_loadavg();
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    if (l < 0)
        snprintf(buf, n, "load average unknown");
    else if (cores > 0 && l < 0.5 * (double)cores)
        snprintf(buf, n, "load average %.2f: a quiet machine", l);
    else
        snprintf(buf, n, "load average %.2f: the machine was shared with "
                 "other jobs, so the rates are low and noisy", l);
    return buf;
}

/* Today's date and time in UTC, "YYYY-MM-DD HH:MM UTC", into buf (or
 * "unknown date"); returns buf. */
static inline const char *bench_date(char *buf, size_t n)
{
    time_t now = time(NULL);
    struct tm tm;
    if (now == (time_t)-1 || !gmtime_r(&now, &tm) ||
        strftime(buf, n, "%Y-%m-%d %H:%M UTC", &tm) == 0)
        snprintf(buf, n, "unknown date");
    return buf;
}

/* "Machine: <cpu>, <n> cores; compiler <version>; OMP_WAIT_POLICY=<p>;
 * date <date>" */
static inline void bench_print_machine(FILE *f)
{
    char cpu[256], date[64];
    bench_cpu_model(cpu, sizeof cpu);
    const char *wait = getenv("OMP_WAIT_POLICY");
    fprintf(f, "Machine: %s, %ld cores; compiler gcc-compatible %s; "
               "OMP_WAIT_POLICY=%s; date %s", cpu,
            sysconf(_SC_NPROCESSORS_ONLN), __VERSION__,
            wait ? wait : "(unset)", bench_date(date, sizeof date));
}

#endif
