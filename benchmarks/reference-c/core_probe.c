/*
 * What two threads can gain on this machine, whatever the software: each kernel runs on one thread, then on two
 * threads at once (each doing the same amount of work on its own data), and the probe prints the speedup that two
 * threads give over one, 2 t1 / t2 (2.00: two independent cores; about 1.0 to 1.5: two hardware threads of one core,
 * or a shared resource, competing for the units the kernel needs).
 *
 * Kernels (scalar double precision, as the engine computes; gcc -O2 without vectorisation):
 *   fp-throughput  12 independent multiply-add chains: bound by the floating-point units' throughput
 *   fp-latency     one dependent multiply-add chain: bound by latency, leaves the units mostly idle
 *   l2-sweeps      a 512 KiB array read and written in place, again and again: the working set of a
 *                  64 x 64 cloth's solver vectors, bound by the core's caches
 *   dram-stream    a 256 MiB array summed: bound by memory bandwidth
 * Each measurement is the fastest of 5. Usage: core_probe [scale]   (scale 1 takes about 10 s)
 * Build: gcc -O2 -fno-tree-vectorize -pthread -o core_probe core_probe.c
 */
#define _GNU_SOURCE
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    int kernel;
    long repeat;
    double *data;
    size_t length;
    double result;
} Job;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static void *run(void *argument)
{
    Job *job = argument;
    double r = 0.0;
    switch (job->kernel) {
    case 0: {
        double a[12];
        for (int i = 0; i < 12; i++) a[i] = 1.0 + i * 1e-9;
        for (long k = 0; k < job->repeat; k++)
            for (int i = 0; i < 12; i++) a[i] = a[i] * 0.9999999 + 1e-9;
        for (int i = 0; i < 12; i++) r += a[i];
        break;
    }
    case 1: {
        double a = 1.0;
        for (long k = 0; k < 12 * job->repeat; k++) a = a * 0.9999999 + 1e-9;
        r = a;
        break;
    }
    default:
        for (long k = 0; k < job->repeat; k++) {
            double *d = job->data;
            for (size_t i = 0; i < job->length; i++) {
                if (job->kernel == 2) d[i] = d[i] * 0.5 + 1.0;
                else r += d[i];
            }
        }
        r += job->data[job->length / 2];
        break;
    }
    job->result = r;
    return NULL;
}

/* The fastest of 5 runs of the kernel on `threads` threads at once. */
static double fastest(Job *jobs, int threads)
{
    double best = 1e300;
    for (int trial = 0; trial < 5; trial++) {
        pthread_t handles[2];
        double start = now();
        for (int t = 0; t < threads; t++) pthread_create(&handles[t], NULL, run, &jobs[t]);
        for (int t = 0; t < threads; t++) pthread_join(handles[t], NULL);
        double elapsed = now() - start;
        if (elapsed < best) best = elapsed;
    }
    return best;
}

int main(int argc, char **argv)
{
    double scale = argc > 1 ? atof(argv[1]) : 1.0;
    const char *names[] = { "fp-throughput", "fp-latency", "l2-sweeps", "dram-stream" };
    const size_t lengths[] = { 0, 0, 512 * 1024 / 8, 256 * 1024 * 1024 / 8 };
    const long repeats[] = { 40000000, 10000000, 2000, 4 };
    printf("%-14s %12s %12s %9s\n", "kernel", "1 thread s", "2 threads s", "speedup");
    for (int k = 0; k < 4; k++) {
        Job jobs[2];
        for (int t = 0; t < 2; t++) {
            jobs[t].kernel = k;
            jobs[t].repeat = (long)(repeats[k] * scale) > 0 ? (long)(repeats[k] * scale) : 1;
            jobs[t].length = lengths[k];
            jobs[t].data = lengths[k] ? malloc(lengths[k] * sizeof(double)) : NULL;
            for (size_t i = 0; i < lengths[k]; i++) jobs[t].data[i] = 1.0 + (double)(i % 7);
        }
        double one = fastest(jobs, 1), two = fastest(jobs, 2);
        printf("%-14s %12.3f %12.3f %8.2fx\n", names[k], one, two, 2.0 * one / two);
        for (int t = 0; t < 2; t++) free(jobs[t].data);
    }
    return 0;
}
