/*
 * A lean plain C xpbd of the course's cloth (issue 29): what a C programmer writes for this one cloth, to hold the
 * library's spring projection to when its springs have no damping. The same cloth as cloth_xpbd.c (an n x n grid of
 * spacing r = 1 / (n - 1) in y = 0, 1 kg, corners (0, 0) and (0, n - 1) pinned, structural, shear and bend springs of
 * k = 50 N/m, drag 0.01, gravity 9.81) and the same substep (the prediction, one pass over the springs, v = (x - x0) / h),
 * but written for this cloth alone:
 *   - no axial damping (c = 0): dlambda = -k h^2 C / (k h^2 w + 1), the start positions are never read;
 *   - twelve structured colour batches instead of a greedy colouring: each of the six spring families (along a row,
 *     along a column, the two diagonals, and the bend springs i..i+2 along a row and along a column) in two colours,
 *     by the parity of the row or column (or of its half for the bend springs), so no two springs of a batch share a
 *     particle;
 *   - separate arrays (first, second, k h^2, L) instead of an array of structs.
 * Its projection order differs from the library's, so its state is another (equally valid) Gauss-Seidel sweep's: the
 * comparison is of cost only. Timing as cloth_xpbd.c: one simulated second (60 frames of 1/60 s, 10 substeps) from rest.
 * Usage: cloth_xpbd_lean n [n ...]; build/libcloth_xpbd_lean.so exports lean_create, lean_reset, lean_step,
 * lean_checksum, lean_springs and lean_destroy for the benchmarks' xpbd mode (--lean).
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { STEPS_PER_SECOND = 60, BATCHES = 12 };

typedef struct {
    int n, particles, springs;
    int *first, *second; /* batch order */
    double *k, *stiff, *rest; /* k (N/m), k h^2, L in batch order */
    int starts[BATCHES + 1];
    double h_prepared;
    double *mass, *inverse_mass, *initial, *x, *v, *x0;
    double drag, gravity;
} Lean;

static void *checked_calloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size);
    if (!p) {
        fprintf(stderr, "error: out of memory\n");
        exit(1);
    }
    return p;
}

/* The batch of spring (a, b) of family f: two colours per family. */
static int batch_of(int family, int row, int col)
{
    switch (family) {
    case 0: return col % 2;               /* (row, col) - (row, col + 1) */
    case 1: return 2 + row % 2;           /* (row, col) - (row + 1, col) */
    case 2: return 4 + row % 2;           /* (row, col) - (row + 1, col + 1) */
    case 3: return 6 + row % 2;           /* (row, col + 1) - (row + 1, col) */
    case 4: return 8 + (col / 2) % 2;     /* (row, col) - (row, col + 2) */
    default: return 10 + (row / 2) % 2;  /* (row, col) - (row + 2, col) */
    }
}

static void build(Lean *c, int n)
{
    const double r = 1.0 / (n - 1), k = 50, diagonal = r * sqrt(2.0);
    const int capacity = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n > 2 ? n - 2 : 0);
    memset(c, 0, sizeof *c);
    c->n = n;
    c->particles = n * n;
    c->first = checked_calloc(capacity, sizeof(int));
    c->second = checked_calloc(capacity, sizeof(int));
    c->k = checked_calloc(capacity, sizeof(double));
    c->stiff = checked_calloc(capacity, sizeof(double));
    c->rest = checked_calloc(capacity, sizeof(double));
    c->mass = checked_calloc(c->particles, sizeof(double));
    c->inverse_mass = checked_calloc(c->particles, sizeof(double));
    c->initial = checked_calloc(6 * (size_t)c->particles, sizeof(double));
    c->x = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->v = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->x0 = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->drag = 0.01;
    c->gravity = 9.81;
    for (int i = 0; i < c->particles; i++) {
        c->initial[3 * i] = (i % n) * r;
        c->initial[3 * i + 2] = (i / n) * r;
        c->mass[i] = 1.0 / c->particles;
        c->inverse_mass[i] = (i == 0 || i == n - 1) ? 0.0 : 1.0 / c->mass[i];
    }
    /* Two passes: count each batch, then place each spring (family by family, row by row) in its batch. */
    int count[BATCHES] = { 0 }, next[BATCHES];
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            c->starts[0] = 0;
            for (int b = 0; b < BATCHES; b++) c->starts[b + 1] = c->starts[b] + count[b];
            memcpy(next, c->starts, sizeof next);
        }
        for (int family = 0; family < 6; family++) {
            for (int row = 0; row < n; row++) {
                for (int col = 0; col < n; col++) {
                    const int i = row * n + col;
                    int a = -1, b = -1;
                    double rest = r;
                    switch (family) {
                    case 0: if (col + 1 < n) { a = i; b = i + 1; } break;
                    case 1: if (row + 1 < n) { a = i; b = i + n; } break;
                    case 2: if (row + 1 < n && col + 1 < n) { a = i; b = i + n + 1; rest = diagonal; } break;
                    case 3: if (row + 1 < n && col + 1 < n) { a = i + 1; b = i + n; rest = diagonal; } break;
                    case 4: if (col + 2 < n) { a = i; b = i + 2; rest = 2 * r; } break;
                    default: if (row + 2 < n) { a = i; b = i + 2 * n; rest = 2 * r; } break;
                    }
                    if (a < 0) continue;
                    const int batch = batch_of(family, row, col);
                    if (pass == 0) {
                        count[batch]++;
                        continue;
                    }
                    const int s = next[batch]++;
                    c->first[s] = a;
                    c->second[s] = b;
                    c->k[s] = k;
                    c->rest[s] = rest;
                }
            }
        }
    }
    c->springs = c->starts[BATCHES];
    c->h_prepared = -1;
}

static void reset(Lean *c)
{
    const size_t m = 3 * (size_t)c->particles;
    memcpy(c->x, c->initial, m * sizeof(double));
    memcpy(c->v, c->initial + m, m * sizeof(double));
}

static void project(Lean *c)
{
    double *restrict x = c->x;
    const double *restrict w = c->inverse_mass, *restrict stiff = c->stiff, *restrict rest = c->rest;
    const int *restrict first = c->first, *restrict second = c->second;
    for (int b = 0; b < BATCHES; b++) {
        for (int s = c->starts[b]; s < c->starts[b + 1]; s++) {
            const int i = 3 * first[s], j = 3 * second[s];
            const double wi = w[first[s]], wj = w[second[s]], wsum = wi + wj;
            if (wsum == 0.0) continue;
            const double dx = x[i] - x[j], dy = x[i + 1] - x[j + 1], dz = x[i + 2] - x[j + 2];
            const double squared = dx * dx + dy * dy + dz * dz;
            if (squared == 0.0) continue;
            const double l = sqrt(squared), inverse = 1.0 / l;
            const double dlambda = -stiff[s] * (l - rest[s]) / (stiff[s] * wsum + 1.0) * inverse;
            const double cx = dlambda * dx, cy = dlambda * dy, cz = dlambda * dz;
            x[i] += wi * cx; x[i + 1] += wi * cy; x[i + 2] += wi * cz;
            x[j] -= wj * cx; x[j + 1] -= wj * cy; x[j + 2] -= wj * cz;
        }
    }
}

static void step(Lean *c, double dt, int substeps)
{
    const double h = dt / substeps, inverse_h = 1.0 / h, drag = -c->drag, g = -c->gravity;
    const int particles = c->particles;
    double *restrict x = c->x, *restrict v = c->v, *restrict x0 = c->x0;
    const double *restrict w = c->inverse_mass, *restrict m = c->mass;
    if (h != c->h_prepared) {
        for (int s = 0; s < c->springs; s++) c->stiff[s] = c->k[s] * (h * h);
        c->h_prepared = h;
    }
    for (int sub = 0; sub < substeps; sub++) {
        for (int i = 0; i < particles; i++) {
            const int o = 3 * i;
            const double wi = w[i];
            const double vx = v[o] + h * (drag * v[o] * wi);
            const double vy = v[o + 1] + h * ((drag * v[o + 1] + m[i] * g) * wi);
            const double vz = v[o + 2] + h * (drag * v[o + 2] * wi);
            x0[o] = x[o]; x0[o + 1] = x[o + 1]; x0[o + 2] = x[o + 2];
            v[o] = vx; v[o + 1] = vy; v[o + 2] = vz;
            x[o] += h * vx; x[o + 1] += h * vy; x[o + 2] += h * vz;
        }
        project(c);
        for (int i = 0; i < particles; i++) {
            if (w[i] == 0.0) continue;
            const int o = 3 * i;
            v[o] = (x[o] - x0[o]) * inverse_h;
            v[o + 1] = (x[o + 1] - x0[o + 1]) * inverse_h;
            v[o + 2] = (x[o + 2] - x0[o + 2]) * inverse_h;
        }
    }
}

static double checksum(const Lean *c)
{
    double sum = 0;
    for (int k = 0; k < 3 * c->particles; k++) sum += c->x[k];
    for (int k = 0; k < 3 * c->particles; k++) sum += c->v[k];
    return sum;
}

static void destroy(Lean *c)
{
    free(c->first); free(c->second); free(c->k); free(c->stiff); free(c->rest); free(c->mass);
    free(c->inverse_mass); free(c->initial); free(c->x); free(c->v); free(c->x0);
}

void *lean_create(int n)
{
    if (n < 3 || n > 2048) return NULL;
    Lean *c = checked_calloc(1, sizeof *c);
    build(c, n);
    reset(c);
    return c;
}
void lean_reset(void *cloth) { reset(cloth); }
void lean_step(void *cloth, double dt, int substeps, int steps)
{
    for (int s = 0; s < steps; s++) step(cloth, dt, substeps);
}
double lean_checksum(void *cloth) { return checksum(cloth); }
int lean_springs(void *cloth) { return ((Lean *)cloth)->springs; }
void lean_destroy(void *cloth)
{
    if (!cloth) return;
    destroy(cloth);
    free(cloth);
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s n [n ...]\n", argv[0]);
        return 2;
    }
    printf("%6s %10s %14s %14s %22s\n", "n", "springs", "best ms/sim-s", "ns/projection", "checksum(1 s)");
    for (int arg = 1; arg < argc; arg++) {
        const int n = atoi(argv[arg]);
        if (n < 3 || n > 2048) {
            fprintf(stderr, "error: n must be 3 to 2048; got %s\n", argv[arg]);
            return 2;
        }
        Lean c;
        build(&c, n);
        reset(&c);
        step(&c, 1.0 / STEPS_PER_SECOND, 10);
        double best = 1e300, sum = 0;
        for (int rep = 0; rep < 9; rep++) {
            reset(&c);
            const double t0 = now();
            for (int s = 0; s < STEPS_PER_SECOND; s++) step(&c, 1.0 / STEPS_PER_SECOND, 10);
            const double t = now() - t0;
            if (t < best) best = t;
            sum = checksum(&c);
        }
        printf("%6d %10d %14.3f %14.3f %22.17g\n", n, c.springs, best * 1e3, best * 1e9 / (STEPS_PER_SECOND * 10.0 * c.springs), sum);
        destroy(&c);
    }
    return 0;
}
