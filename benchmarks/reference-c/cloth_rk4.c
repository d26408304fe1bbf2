/*
 * Plain C reference of one RK4 step of the course's cloth (issue 5, item 6): what the C# library's RK4 cloth
 * step should cost per spring evaluation when written as flat double arrays and compiled with gcc -O3.
 *
 * Same system as ParticlePhysics' ClothScenario with its defaults: an n x n grid of spacing r = 1 / (n - 1) in
 * the plane y = 0, total mass 1 kg, corners (0, 0) and (0, n - 1) pinned (inverse mass 0, velocity 0);
 * structural, shear and bend springs of stiffness k = 50 N/m and axial damping c = 0.05 N s/m with
 * F_i = -(k (l - L) + c (v_i - v_j) . u) u, F_j = -F_i (zero when l = 0); linear drag -lambda v (0.01) and
 * gravity m (0, -9.81, 0). State y = [x | v], 6 n^2 doubles; dy/dt = [v | F / m]; classical RK4 written like
 * RungeKutta4.cs (one k buffer, one stage buffer, next accumulated). Springs are stored like SpringNetwork: two
 * index arrays and 3 parameters (k, L, c) per spring.
 *
 * Timing: like the C# benchmark, each repetition resets the cloth to rest and runs 16 steps of dt = time_step(n),
 * so a long run cannot drift into divergence. Seven timed batches of about 0.2 s each: the median is reported
 * (BenchmarkDotNet's tables report a mean and a median), and the best in the last column, which is the figure
 * least disturbed by other work on a shared machine. Usage: cloth_rk4 n [n ...]; prints one line per n.
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { STEPS_PER_RESET = 16 };
/* The C# benchmarks' ClothFixture.Rk4TimeStep: 1 ms up to n = 64, then 1 ms (64 / n)^2, inside RK4's stability
   limit, which the axial damping rate c n^2 / M sets on fine cloths (1 ms diverges within 16 steps at n = 128). */
static double time_step(int n) { return n <= 64 ? 0.001 : 0.001 * (64.0 / n) * (64.0 / n); }

typedef struct {
    int n, particles, springs, dim;
    int *first, *second;
    double *params;   /* k, L, c per spring */
    double *mass, *inverse_mass;
    double *initial, *state, *next, *k, *stage, *forces;
    double drag, gravity;
} Cloth;

static void *checked_calloc(size_t count, size_t size)
{
    void *p = calloc(count, size);
    if (!p) {
        fprintf(stderr, "error: out of memory\n");
        exit(1);
    }
    return p;
}

static void add_spring(Cloth *c, int a, int b, double k, double rest, double damping)
{
    int s = c->springs++;
    c->first[s] = a;
    c->second[s] = b;
    c->params[3 * s] = k;
    c->params[3 * s + 1] = rest;
    c->params[3 * s + 2] = damping;
}

static void build(Cloth *c, int n)
{
    const double r = 1.0 / (n - 1), k = 50, damping = 0.05, diagonal = r * sqrt(2.0);
    int capacity = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n > 2 ? n - 2 : 0);
    memset(c, 0, sizeof *c);
    c->n = n;
    c->particles = n * n;
    c->dim = 6 * c->particles;
    c->first = checked_calloc(capacity, sizeof(int));
    c->second = checked_calloc(capacity, sizeof(int));
    c->params = checked_calloc(3 * (size_t)capacity, sizeof(double));
    c->mass = checked_calloc(c->particles, sizeof(double));
    c->inverse_mass = checked_calloc(c->particles, sizeof(double));
    c->initial = checked_calloc(c->dim, sizeof(double));
    c->state = checked_calloc(c->dim, sizeof(double));
    c->next = checked_calloc(c->dim, sizeof(double));
    c->k = checked_calloc(c->dim, sizeof(double));
    c->stage = checked_calloc(c->dim, sizeof(double));
    c->forces = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->drag = 0.01;
    c->gravity = 9.81;
    for (int row = 0; row < n; row++) {
        for (int col = 0; col < n; col++) {
            int i = row * n + col;
            c->initial[3 * i] = col * r;
            c->initial[3 * i + 1] = 0;
            c->initial[3 * i + 2] = row * r;
            c->mass[i] = 1.0 / c->particles;
            c->inverse_mass[i] = (i == 0 || i == n - 1) ? 0.0 : 1.0 / c->mass[i];
        }
    }
    for (int row = 0; row < n; row++) {
        for (int col = 0; col < n; col++) {
            int i = row * n + col;
            if (col + 1 < n) add_spring(c, i, i + 1, k, r, damping);
            if (row + 1 < n) add_spring(c, i, i + n, k, r, damping);
            if (row + 1 < n && col + 1 < n) {
                add_spring(c, i, i + n + 1, k, diagonal, damping);
                add_spring(c, i + 1, i + n, k, diagonal, damping);
            }
            if (col + 2 < n) add_spring(c, i, i + 2, k, 2 * r, damping);
            if (row + 2 < n) add_spring(c, i, i + 2 * n, k, 2 * r, damping);
        }
    }
}

/* dy/dt = [v | F / m] for the state y. */
static void evaluate(Cloth *c, const double *restrict y, double *restrict dydt)
{
    const int m = 3 * c->particles;
    const double *restrict x = y, *restrict v = y + m;
    double *restrict f = c->forces;
    const int *restrict first = c->first, *restrict second = c->second;
    const double *restrict p = c->params;
    memcpy(dydt, v, m * sizeof(double));
    memset(f, 0, m * sizeof(double));
    for (int s = 0; s < c->springs; s++) {
        int a = 3 * first[s], b = 3 * second[s];
        double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
        double length_squared = dx * dx + dy * dy + dz * dz;
        if (length_squared == 0.0) continue;
        double length = sqrt(length_squared), inverse = 1.0 / length;
        double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
        double closing = (v[a] - v[b]) * ux + (v[a + 1] - v[b + 1]) * uy + (v[a + 2] - v[b + 2]) * uz;
        double magnitude = p[3 * s] * (length - p[3 * s + 1]) + p[3 * s + 2] * closing;
        double fx = magnitude * ux, fy = magnitude * uy, fz = magnitude * uz;
        f[a] -= fx; f[a + 1] -= fy; f[a + 2] -= fz;
        f[b] += fx; f[b + 1] += fy; f[b + 2] += fz;
    }
    for (int k = 0; k < m; k++) f[k] -= c->drag * v[k];
    for (int i = 0; i < c->particles; i++) f[3 * i + 1] -= c->mass[i] * c->gravity;
    double *restrict a = dydt + m;
    for (int i = 0; i < c->particles; i++) {
        double w = c->inverse_mass[i];
        a[3 * i] = f[3 * i] * w;
        a[3 * i + 1] = f[3 * i + 1] * w;
        a[3 * i + 2] = f[3 * i + 2] * w;
    }
}

static void rk4_step(Cloth *c, double h)
{
    const int d = c->dim;
    double *restrict y = c->state, *restrict next = c->next, *restrict k = c->k, *restrict stage = c->stage;
    const double half = 0.5 * h, sixth = h / 6.0;
    evaluate(c, y, k);
    for (int i = 0; i < d; i++) { next[i] = y[i] + sixth * k[i]; stage[i] = y[i] + half * k[i]; }
    evaluate(c, stage, k);
    for (int i = 0; i < d; i++) { next[i] += 2.0 * sixth * k[i]; stage[i] = y[i] + half * k[i]; }
    evaluate(c, stage, k);
    for (int i = 0; i < d; i++) { next[i] += 2.0 * sixth * k[i]; stage[i] = y[i] + h * k[i]; }
    evaluate(c, stage, k);
    for (int i = 0; i < d; i++) next[i] += sixth * k[i];
    memcpy(y, next, d * sizeof(double)); /* commit, as ParticleWorld.Step does after its finiteness check */
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void run_batch(Cloth *c, long resets)
{
    const double dt = time_step(c->n);
    for (long r = 0; r < resets; r++) {
        memcpy(c->state, c->initial, c->dim * sizeof(double));
        for (int s = 0; s < STEPS_PER_RESET; s++) rk4_step(c, dt);
    }
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s n [n ...]\n", argv[0]);
        return 2;
    }
    printf("%6s %10s %12s %14s %16s %22s %18s\n", "n", "springs", "us/step", "ns/particle", "ns/spring-eval",
           "checksum(16 steps)", "best ns/spring-eval");
    for (int arg = 1; arg < argc; arg++) {
        int n = atoi(argv[arg]);
        if (n < 3 || n > 2048) {
            fprintf(stderr, "error: n must be 3 to 2048; got %s\n", argv[arg]);
            return 2;
        }
        Cloth c;
        build(&c, n);

        /* Checksum after one batch of 16 steps from rest: the C# verify mode prints the same sum. */
        run_batch(&c, 1);
        double checksum = 0;
        for (int i = 0; i < c.dim; i++) checksum += c.state[i];

        /* Calibrate a batch of about 0.2 s, then time 7 batches. */
        long resets = 1;
        for (;;) {
            double t0 = now();
            run_batch(&c, resets);
            if (now() - t0 > 0.05) break;
            resets *= 2;
        }
        resets = resets * 4;
        enum { REPS = 7 };
        double per_step[REPS];
        for (int rep = 0; rep < REPS; rep++) {
            double t0 = now();
            run_batch(&c, resets);
            per_step[rep] = (now() - t0) / (resets * (double)STEPS_PER_RESET);
        }
        qsort(per_step, REPS, sizeof per_step[0], compare_doubles);
        double median = per_step[REPS / 2], best = per_step[0];
        printf("%6d %10d %12.2f %14.3f %16.3f %22.17g %18.3f\n", n, c.springs, median * 1e6, median * 1e9 / c.particles,
               median * 1e9 / (4.0 * c.springs), checksum, best * 1e9 / (4.0 * c.springs));
    }
    return 0;
}
