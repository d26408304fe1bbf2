/*
 * Plain C reference of xpbd on the course's cloth (issue 13): what the C# library's xpbd should cost when written
 * as flat double arrays and compiled with gcc -O3, and the same cloth to the last bit.
 *
 * Same system as ParticlePhysics' ClothScenario with its defaults (see cloth_rk4.c): an n x n grid of spacing
 * r = 1 / (n - 1) in the plane y = 0, total mass 1 kg, corners (0, 0) and (0, n - 1) pinned (inverse mass 0),
 * structural, shear and bend springs (k = 50 N/m, c = 0.05 N s/m) in the builder's order, linear drag 0.01 and
 * gravity 9.81. Same algorithm as Xpbd.cs with SpringProjection.cs, one pass per substep: each step of dt is split
 * into S substeps of h = dt / S; each substep, from (x0, v0):
 *   a = (-lambda v0 + m g) / m (0 for a pinned particle); v = v0 + h a; x = x0 + h v     (the prediction)
 *   every spring once, in the library's order (ConstraintColouring.cs, ConstraintPartition.cs): the springs
 *   coloured greedily in spring order and sorted by colour; the particles split into P parts of contiguous indices
 *   (strips of rows); first the even parts, each with its springs (both ends in it, or one in it and one in an odd
 *   part) in colour order, then the odd parts, each with its springs in colour order:
 *     C = l - L, u = (x_i - x_j) / l, w = w_i + w_j,
 *     dlambda = -(k h^2 C + c h u . ((x_i - x0_i) - (x_j - x0_j))) / ((k h^2 + c h) w + 1),
 *     x_i += w_i dlambda u, x_j -= w_j dlambda u  (skipped when w = 0 or l = 0)
 *   v = (x - x0) / h for every particle that is not pinned.
 * The expressions are the library's, operand for operand, and gcc in ISO C mode does not contract a * b + c into a
 * fused multiply-add, so the states agree bit for bit (the checksum below is the one the C# verify mode prints).
 * Written as C is written: the prediction in one pass per particle, the springs as one array of structs in projection
 * order (ends, k h^2, c h, L), which is what a C programmer does with the substep fixed. One core: the order is what
 * lets the library split a pass over two or more cores in two hand-offs and still compute these bits.
 *
 * Timing: one simulated second (60 steps of 1/60 s, 10 substeps each) from rest per repetition, so a long run
 * measures a falling, swinging cloth as a game sees it. Seven timed batches of about 0.2 s: the median and the best.
 * Usage: cloth_xpbd [--substeps S] n [n ...]      times each n, prints one line per n
 *        cloth_xpbd --run STEPS n                 runs STEPS steps once and prints the checksum (for callgrind)
 * The shared library built from this file (run.sh) exports xpbd_create, xpbd_reset, xpbd_step, xpbd_checksum,
 * xpbd_state and xpbd_destroy, which the BenchmarkDotNet comparison calls in-process.
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { STEPS_PER_SECOND = 60 };

typedef struct {
    int first, second; /* particle indices */
    double stiff;      /* k h^2 */
    double damp;       /* c h */
    double rest;       /* L */
} Spring;

typedef struct {
    int n, particles, springs, colours, parts;
    int *first, *second;   /* in the builder's order */
    double *params;        /* k, L, c per spring, builder's order */
    int *order;            /* projection order: spring indices */
    Spring *projected;     /* in projection order, for the current h */
    double h_prepared;
    double *mass, *inverse_mass;
    double *initial, *x, *v, *x0;
    double drag, gravity;
} Cloth;

static void *checked_calloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size);
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

/* Greedy colouring of the springs in index order, then a stable counting sort by colour: ConstraintColouring.cs. */
static void colour(Cloth *c)
{
    const int count = c->springs, particles = c->particles;
    int *start = checked_calloc(particles + 1, sizeof(int)), *fill = checked_calloc(particles, sizeof(int));
    for (int s = 0; s < count; s++) {
        start[c->first[s] + 1]++;
        start[c->second[s] + 1]++;
    }
    for (int p = 0; p < particles; p++) start[p + 1] += start[p];
    int *at = checked_calloc(start[particles], sizeof(int));
    for (int s = 0; s < count; s++) {
        at[start[c->first[s]] + fill[c->first[s]]++] = s;
        at[start[c->second[s]] + fill[c->second[s]]++] = s;
    }
    int *colour_of = checked_calloc(count, sizeof(int)), *taken = checked_calloc(count + 1, sizeof(int));
    int colours = 0;
    for (int s = 0; s < count; s++) {
        int ends[2] = { c->first[s], c->second[s] };
        for (int e = 0; e < 2; e++) {
            for (int a = start[ends[e]]; a < start[ends[e] + 1]; a++) {
                if (at[a] < s) taken[colour_of[at[a]]] = s + 1;
            }
        }
        int k = 0;
        while (taken[k] == s + 1) k++;
        colour_of[s] = k;
        if (k + 1 > colours) colours = k + 1;
    }
    int *starts = checked_calloc(colours + 1, sizeof(int)), *next = checked_calloc(colours, sizeof(int));
    for (int s = 0; s < count; s++) starts[colour_of[s] + 1]++;
    for (int k = 0; k < colours; k++) starts[k + 1] += starts[k];
    for (int s = 0; s < count; s++) c->order[starts[colour_of[s]] + next[colour_of[s]]++] = s;
    c->colours = colours;
    free(start); free(fill); free(at); free(colour_of); free(taken); free(starts); free(next);
}

/* The part counts tried, largest first, and what a partition must meet: ConstraintPartition.cs. */
static const int part_candidates[] = { 24, 12, 8, 4 };
enum { MIN_PARTICLES_PER_PART = 256, MAX_SEAM_SHARE_DIVISOR = 4 };

/* Reorders c->order (the colour order) into one group per part, the even parts (each with its seams, the springs from
 * it to an odd part) then the odd ones, each group in colour order (a stable distribution). Returns 0, leaving
 * c->order as it was, if a spring joins two parts of the same parity, if the seams are more than a quarter of the
 * springs, or if the seams of two even parts reach one particle. */
static int partition(Cloth *c, int parts)
{
    const int count = c->springs, particles = c->particles, half = parts / 2;
    int *part_of = checked_calloc(particles, sizeof(int)), *reached_by = checked_calloc(particles, sizeof(int));
    int *group_of = checked_calloc(count, sizeof(int)), *starts = checked_calloc(parts + 1, sizeof(int));
    int *by_colour = checked_calloc(count, sizeof(int));
    int seams = 0, accepted = 1;
    for (int p = 0; p < parts; p++) {
        int begin = (int)((long long)particles * p / parts), end = (int)((long long)particles * (p + 1) / parts);
        for (int i = begin; i < end; i++) part_of[i] = p;
    }
    for (int i = 0; i < particles; i++) reached_by[i] = -1;
    for (int s = 0; s < count && accepted; s++) {
        int a = part_of[c->first[s]], b = part_of[c->second[s]], part = a;
        if (a != b) {
            int even = a % 2 == 0 ? a : b, odd_end = a % 2 == 0 ? c->second[s] : c->first[s];
            if ((a - b) % 2 == 0 || (reached_by[odd_end] >= 0 && reached_by[odd_end] != even)) accepted = 0;
            reached_by[odd_end] = even;
            part = even;
            seams++;
        }
        group_of[s] = part % 2 == 0 ? part / 2 : half + part / 2; /* the even parts first, then the odd ones */
    }
    if (accepted && (long long)seams * MAX_SEAM_SHARE_DIVISOR > count) accepted = 0;
    if (accepted) {
        for (int s = 0; s < count; s++) starts[group_of[s] + 1]++;
        for (int g = 0; g < parts; g++) starts[g + 1] += starts[g];
        memcpy(by_colour, c->order, count * sizeof(int));
        for (int k = 0; k < count; k++) c->order[starts[group_of[by_colour[k]]]++] = by_colour[k];
    }
    free(part_of); free(reached_by); free(group_of); free(starts); free(by_colour);
    return accepted;
}

static void build(Cloth *c, int n)
{
    const double r = 1.0 / (n - 1), k = 50, damping = 0.05, diagonal = r * sqrt(2.0);
    int capacity = 2 * n * (n - 1) + 2 * (n - 1) * (n - 1) + 2 * n * (n > 2 ? n - 2 : 0);
    memset(c, 0, sizeof *c);
    c->n = n;
    c->particles = n * n;
    c->first = checked_calloc(capacity, sizeof(int));
    c->second = checked_calloc(capacity, sizeof(int));
    c->params = checked_calloc(3 * (size_t)capacity, sizeof(double));
    c->order = checked_calloc(capacity, sizeof(int));
    c->projected = checked_calloc(capacity, sizeof(Spring));
    c->mass = checked_calloc(c->particles, sizeof(double));
    c->inverse_mass = checked_calloc(c->particles, sizeof(double));
    c->initial = checked_calloc(6 * (size_t)c->particles, sizeof(double));
    c->x = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->v = checked_calloc(3 * (size_t)c->particles, sizeof(double));
    c->x0 = checked_calloc(3 * (size_t)c->particles, sizeof(double));
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
    colour(c);
    c->parts = 1;
    for (size_t k = 0; k < sizeof part_candidates / sizeof part_candidates[0]; k++) {
        int parts = part_candidates[k];
        if (c->particles / parts >= MIN_PARTICLES_PER_PART && partition(c, parts)) {
            c->parts = parts;
            break;
        }
    }
    c->h_prepared = -1;
}

static void reset(Cloth *c)
{
    const size_t m = 3 * (size_t)c->particles;
    memcpy(c->x, c->initial, m * sizeof(double));
    memcpy(c->v, c->initial + m, m * sizeof(double));
}

/* The springs in projection order with k h^2 and c h for this substep (the same products the library forms per
 * spring). */
static void prepare(Cloth *c, double h)
{
    for (int s = 0; s < c->springs; s++) {
        int o = c->order[s];
        Spring *p = &c->projected[s];
        p->first = c->first[o];
        p->second = c->second[o];
        p->stiff = c->params[3 * o] * (h * h);
        p->rest = c->params[3 * o + 1];
        p->damp = c->params[3 * o + 2] * h;
    }
    c->h_prepared = h;
}

static void project(Cloth *c)
{
    double *restrict x = c->x;
    const double *restrict x0 = c->x0, *restrict w = c->inverse_mass;
    const Spring *restrict springs = c->projected;
    const int count = c->springs;
    for (int s = 0; s < count; s++) {
        const Spring *p = &springs[s];
        const int i = 3 * p->first, j = 3 * p->second;
        const double wi = w[p->first], wj = w[p->second], wsum = wi + wj;
        if (wsum == 0.0) continue;
        double dx = x[i] - x[j], dy = x[i + 1] - x[j + 1], dz = x[i + 2] - x[j + 2];
        double mx = (x[i] - x0[i]) - (x[j] - x0[j]);
        double my = (x[i + 1] - x0[i + 1]) - (x[j + 1] - x0[j + 1]);
        double mz = (x[i + 2] - x0[i + 2]) - (x[j + 2] - x0[j + 2]);
        double squared = dx * dx + dy * dy + dz * dz;
        if (squared == 0.0) continue;
        double l = sqrt(squared), inverse = 1.0 / l;
        double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
        double moved = ux * mx + uy * my + uz * mz;
        double dlambda = -(p->stiff * (l - p->rest) + p->damp * moved) / ((p->stiff + p->damp) * wsum + 1.0);
        double cx = dlambda * ux, cy = dlambda * uy, cz = dlambda * uz;
        x[i] += wi * cx; x[i + 1] += wi * cy; x[i + 2] += wi * cz;
        x[j] -= wj * cx; x[j + 1] -= wj * cy; x[j + 2] -= wj * cz;
    }
}

static void xpbd_step_cloth(Cloth *c, double dt, int substeps)
{
    const double h = dt / substeps, inverse_h = 1.0 / h, drag = -c->drag, g = -c->gravity;
    const int particles = c->particles;
    double *restrict x = c->x, *restrict v = c->v, *restrict x0 = c->x0;
    const double *restrict w = c->inverse_mass, *restrict m = c->mass;
    if (h != c->h_prepared) prepare(c, h);
    for (int sub = 0; sub < substeps; sub++) {
        /* Prediction: the library's forces (0 + (-lambda) v, then + m g on y), a = F w, v += h a, x = x0 + h v. */
        for (int i = 0; i < particles; i++) {
            const int o = 3 * i;
            const double wi = w[i];
            double fx = 0.0 + drag * v[o], fy = (0.0 + drag * v[o + 1]) + m[i] * g, fz = 0.0 + drag * v[o + 2];
            double vx = v[o] + h * (fx * wi), vy = v[o + 1] + h * (fy * wi), vz = v[o + 2] + h * (fz * wi);
            x0[o] = x[o]; x0[o + 1] = x[o + 1]; x0[o + 2] = x[o + 2];
            v[o] = vx; v[o + 1] = vy; v[o + 2] = vz;
            x[o] += h * vx; x[o + 1] += h * vy; x[o + 2] += h * vz;
        }
        project(c);
        for (int i = 0; i < particles; i++) {
            if (w[i] == 0.0) continue; /* a pinned particle keeps its velocity */
            const int o = 3 * i;
            v[o] = (x[o] - x0[o]) * inverse_h;
            v[o + 1] = (x[o + 1] - x0[o + 1]) * inverse_h;
            v[o + 2] = (x[o + 2] - x0[o + 2]) * inverse_h;
        }
    }
}

static double checksum(const Cloth *c)
{
    /* The sum of the state [x | v] in order, as the C# verify mode sums it. */
    double sum = 0;
    for (int k = 0; k < 3 * c->particles; k++) sum += c->x[k];
    for (int k = 0; k < 3 * c->particles; k++) sum += c->v[k];
    return sum;
}

/* The in-process interface for the BenchmarkDotNet comparison (P/Invoke). */
void *xpbd_create(int n)
{
    if (n < 3 || n > 2048) return NULL;
    Cloth *c = checked_calloc(1, sizeof *c);
    build(c, n);
    reset(c);
    return c;
}
void xpbd_reset(void *cloth) { reset(cloth); }
void xpbd_step(void *cloth, double dt, int substeps, int steps)
{
    for (int s = 0; s < steps; s++) xpbd_step_cloth(cloth, dt, substeps);
}
double xpbd_checksum(void *cloth) { return checksum(cloth); }
void xpbd_state(void *cloth, double *out) /* [x | v], 6 n^2 values */
{
    const Cloth *c = cloth;
    memcpy(out, c->x, 3 * (size_t)c->particles * sizeof(double));
    memcpy(out + 3 * (size_t)c->particles, c->v, 3 * (size_t)c->particles * sizeof(double));
}
int xpbd_springs(void *cloth) { return ((Cloth *)cloth)->springs; }
int xpbd_colours(void *cloth) { return ((Cloth *)cloth)->colours; }
void xpbd_destroy(void *cloth)
{
    Cloth *c = cloth;
    if (!c) return;
    free(c->first); free(c->second); free(c->params); free(c->order); free(c->projected); free(c->mass);
    free(c->inverse_mass); free(c->initial); free(c->x); free(c->v); free(c->x0);
    free(c);
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

static void simulate_seconds(Cloth *c, long seconds, int substeps)
{
    for (long r = 0; r < seconds; r++) {
        reset(c);
        for (int s = 0; s < STEPS_PER_SECOND; s++) xpbd_step_cloth(c, 1.0 / STEPS_PER_SECOND, substeps);
    }
}

static int parse_n(const char *text)
{
    char *end;
    long n = strtol(text, &end, 10);
    if (*end != '\0' || n < 3 || n > 2048) {
        fprintf(stderr, "error: n must be a whole number from 3 to 2048; got %s\n", text);
        exit(2);
    }
    return (int)n;
}

int main(int argc, char **argv)
{
    int substeps = 10, arg = 1;
    if (argc >= 4 && strcmp(argv[1], "--run") == 0) {
        char *end;
        long steps = strtol(argv[2], &end, 10);
        if (*end != '\0' || steps < 0 || steps > 1000000) {
            fprintf(stderr, "error: STEPS must be a whole number from 0 to 1000000; got %s\n", argv[2]);
            return 2;
        }
        Cloth c;
        build(&c, parse_n(argv[3]));
        reset(&c);
        for (long s = 0; s < steps; s++) xpbd_step_cloth(&c, 1.0 / STEPS_PER_SECOND, substeps);
        printf("n = %d (P = %d): %ld steps, checksum %.17g\n", c.n, c.parts, steps, checksum(&c));
        return 0;
    }
    if (argc >= 3 && strcmp(argv[1], "--substeps") == 0) {
        substeps = atoi(argv[2]);
        if (substeps < 1 || substeps > 1000) {
            fprintf(stderr, "error: substeps must be 1 to 1000; got %s\n", argv[2]);
            return 2;
        }
        arg = 3;
    }
    if (arg >= argc) {
        fprintf(stderr, "usage: %s [--substeps S] n [n ...] | --run STEPS n\n", argv[0]);
        return 2;
    }
    printf("%6s %10s %8s %14s %14s %22s %14s\n", "n", "springs", "colours", "ms/sim-s", "ns/projection",
           "checksum(1 s)", "best ms/sim-s");
    for (; arg < argc; arg++) {
        Cloth c;
        build(&c, parse_n(argv[arg]));

        /* Checksum after one simulated second from rest: the C# verify mode prints the same sum. */
        simulate_seconds(&c, 1, substeps);
        double sum = checksum(&c);

        /* Calibrate a batch of about 0.2 s, then time 7 batches. */
        long seconds = 1;
        for (;;) {
            double t0 = now();
            simulate_seconds(&c, seconds, substeps);
            if (now() - t0 > 0.05) break;
            seconds *= 2;
        }
        seconds *= 4;
        enum { REPS = 7 };
        double per_second[REPS];
        for (int rep = 0; rep < REPS; rep++) {
            double t0 = now();
            simulate_seconds(&c, seconds, substeps);
            per_second[rep] = (now() - t0) / seconds;
        }
        qsort(per_second, REPS, sizeof per_second[0], compare_doubles);
        double median = per_second[REPS / 2], best = per_second[0];
        double projections = (double)STEPS_PER_SECOND * substeps * c.springs;
        printf("%6d %10d %8d %14.3f %14.3f %22.17g %14.3f\n", c.n, c.springs, c.colours, median * 1e3,
               median * 1e9 / projections, sum, best * 1e3);
        free(c.first); free(c.second); free(c.params); free(c.order); free(c.projected); free(c.mass);
        free(c.inverse_mass); free(c.initial); free(c.x); free(c.v); free(c.x0);
    }
    return 0;
}
