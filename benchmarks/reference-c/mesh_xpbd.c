/*
 * Plain C reference of a mesh cloth's xpbd projections (issue 29): the constant-strain membrane and the quadratic
 * bending as the library projects them (MembraneProjection.cs, BendingProjection.cs), written as flat C and compiled
 * with gcc -O3, to hold the library's projections to. The caller (the benchmarks' mesh-cloth mode) hands over the
 * elements as the library's IMembraneElements.CopyTriangles and IBendingElements.CopyElements give them; this file
 * colours them as ElementColouring.cs does (greedy in index order, stable by colour), so it projects them in the
 * library's order with the library's expressions, operand for operand (gcc in ISO C mode does not contract a * b + c),
 * and the positions after a pass agree with the library's to the last bit. What it leaves out is what a C programmer
 * leaves out: a triangle is 3 corners and the 8 values the projection reads (p, q, r, s, the compliances alpha_11,
 * alpha_12, alpha_33 over h^2, and gamma = tau / h), and there are no spans, checks or runner.
 * Membrane, per triangle (see MembraneProjection.cs for the derivation): F = [F1 F2] from the rest-edge inverse,
 * c = (E_xx, E_yy, 2 E_xy) (+ gamma grad c . (x - x0)), the 3 x 3 system ((1 + gamma) A + alpha / h^2) dlambda = -c by
 * cofactors, x_a += w_a grad_a c^T dlambda. Bending, per element of up to 6 particles and 3 weight rows b_k:
 * (s h^2 B + I) dlambda = -s h^2 c per coordinate, x_v += w_v sum_k b_kv dlambda_k.
 * Exports mesh_create, mesh_prepare, mesh_project and mesh_destroy (build/libmesh_xpbd.so, built by run.sh).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SLOTS = 6, COMPONENTS = 3 };

typedef struct {
    int a, b, c;
    double p, q, r, s;
    double c11, c12, c33, gamma;
} Triangle;

typedef struct {
    int triangles, elements;
    Triangle *tri;
    double *area, *mu, *lambda, *tau; /* per triangle, colour order: what mesh_prepare reads */
    int *slots;
    double *weights, *stiffness, *scaled;
} Mesh;

static void *checked_calloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size);
    if (!p) {
        fprintf(stderr, "error: out of memory\n");
        exit(1);
    }
    return p;
}

/* ElementColouring.cs: each element, in index order, takes the smallest colour free at all its particles; the order is
 * the elements sorted by colour, stable. */
static void colour(const int *particles, int stride, int count, int particle_count, int *order)
{
    int *start = checked_calloc(particle_count + 1, sizeof(int)), *fill = checked_calloc(particle_count, sizeof(int));
    for (int k = 0; k < stride * count; k++)
        if (particles[k] >= 0) start[particles[k] + 1]++;
    for (int p = 0; p < particle_count; p++) start[p + 1] += start[p];
    int *at = checked_calloc(start[particle_count], sizeof(int));
    for (int k = 0; k < stride * count; k++) {
        int p = particles[k];
        if (p >= 0) at[start[p] + fill[p]++] = k / stride;
    }
    int *colour_of = checked_calloc(count, sizeof(int)), *taken = checked_calloc(count + 1, sizeof(int));
    int colours = 0;
    for (int e = 0; e < count; e++) {
        for (int v = 0; v < stride; v++) {
            int p = particles[stride * e + v];
            if (p < 0) continue;
            for (int a = start[p]; a < start[p + 1]; a++)
                if (at[a] < e) taken[colour_of[at[a]]] = e + 1;
        }
        int c = 0;
        while (taken[c] == e + 1) c++;
        colour_of[e] = c;
        if (c + 1 > colours) colours = c + 1;
    }
    int *starts = checked_calloc(colours + 1, sizeof(int)), *next = checked_calloc(colours, sizeof(int));
    for (int e = 0; e < count; e++) starts[colour_of[e] + 1]++;
    for (int c = 0; c < colours; c++) starts[c + 1] += starts[c];
    for (int e = 0; e < count; e++) order[starts[colour_of[e]] + next[colour_of[e]]++] = e;
    free(start); free(fill); free(at); free(colour_of); free(taken); free(starts); free(next);
}

void *mesh_create(int particles, int triangles, const int *corners, const double *parameters, int elements,
                  const int *slots, const double *weights, const double *stiffness)
{
    Mesh *m = checked_calloc(1, sizeof *m);
    m->triangles = triangles;
    m->elements = elements;
    m->tri = checked_calloc(triangles, sizeof(Triangle));
    m->area = checked_calloc(triangles, sizeof(double));
    m->mu = checked_calloc(triangles, sizeof(double));
    m->lambda = checked_calloc(triangles, sizeof(double));
    m->tau = checked_calloc(triangles, sizeof(double));
    int *order = checked_calloc(triangles > elements ? triangles : elements, sizeof(int));
    colour(corners, 3, triangles, particles, order);
    for (int k = 0; k < triangles; k++) {
        const int e = order[k];
        const double *v = parameters + 8 * e;
        Triangle *t = &m->tri[k];
        t->a = corners[3 * e];
        t->b = corners[3 * e + 1];
        t->c = corners[3 * e + 2];
        t->p = v[0]; t->q = v[1]; t->r = v[2]; t->s = v[3];
        m->area[k] = v[4]; m->mu[k] = v[5]; m->lambda[k] = v[6]; m->tau[k] = v[7];
    }
    colour(slots, SLOTS, elements, particles, order);
    m->slots = checked_calloc(SLOTS * (size_t)elements, sizeof(int));
    m->weights = checked_calloc(SLOTS * COMPONENTS * (size_t)elements, sizeof(double));
    m->stiffness = checked_calloc(elements, sizeof(double));
    m->scaled = checked_calloc(elements, sizeof(double));
    for (int k = 0; k < elements; k++) {
        const int e = order[k];
        memcpy(m->slots + SLOTS * k, slots + SLOTS * e, SLOTS * sizeof(int));
        memcpy(m->weights + SLOTS * COMPONENTS * k, weights + SLOTS * COMPONENTS * e, SLOTS * COMPONENTS * sizeof(double));
        m->stiffness[k] = stiffness[e];
    }
    free(order);
    return m;
}

/* The compliances over h^2 and gamma of the triangles, s h^2 of the elements: MembraneProjection.Prepare. */
void mesh_prepare(void *mesh, double h)
{
    Mesh *m = mesh;
    const double hh = h * h;
    for (int k = 0; k < m->triangles; k++) {
        Triangle *t = &m->tri[k];
        const double mu = m->mu[k], lambda = m->lambda[k];
        const double scale = 1.0 / (m->area[k] * hh * 4.0 * mu * (mu + lambda));
        t->c11 = scale * (2.0 * mu + lambda);
        t->c12 = -scale * lambda;
        t->c33 = 1.0 / (m->area[k] * hh * mu);
        t->gamma = m->tau[k] / h;
    }
    for (int e = 0; e < m->elements; e++) m->scaled[e] = m->stiffness[e] * hh;
}

static inline void move(double *restrict x, int i, double w, double bx, double by, double ux, double uy, double uz,
                        double vx, double vy, double vz)
{
    if (w == 0.0) return;
    x[i] += w * (bx * ux + by * vx);
    x[i + 1] += w * (bx * uy + by * vy);
    x[i + 2] += w * (bx * uz + by * vz);
}

static void project_membrane(const Mesh *m, double *restrict x, const double *restrict x0, const double *restrict w)
{
    for (int k = 0; k < m->triangles; k++) {
        const Triangle *t = &m->tri[k];
        const double w0 = w[t->a], w1 = w[t->b], w2 = w[t->c];
        if (w0 == 0.0 && w1 == 0.0 && w2 == 0.0) continue;
        const int i0 = 3 * t->a, i1 = 3 * t->b, i2 = 3 * t->c;
        const double p = t->p, q = t->q, r = t->r, s = t->s;
        const double ax = x[i1] - x[i0], ay = x[i1 + 1] - x[i0 + 1], az = x[i1 + 2] - x[i0 + 2];
        const double bx = x[i2] - x[i0], by = x[i2 + 1] - x[i0 + 1], bz = x[i2 + 2] - x[i0 + 2];
        const double f1x = p * ax + r * bx, f1y = p * ay + r * by, f1z = p * az + r * bz;
        const double f2x = q * ax + s * bx, f2y = q * ay + s * by, f2z = q * az + s * bz;
        const double n11 = f1x * f1x + f1y * f1y + f1z * f1z;
        const double n22 = f2x * f2x + f2y * f2y + f2z * f2z;
        const double n12 = f1x * f2x + f1y * f2y + f1z * f2z;
        double c1 = 0.5 * (n11 - 1.0), c2 = 0.5 * (n22 - 1.0), c3 = n12;
        const double gamma = t->gamma;
        if (gamma != 0.0) {
            const double mx = x[i1] - x0[i1] - (x[i0] - x0[i0]), my = x[i1 + 1] - x0[i1 + 1] - (x[i0 + 1] - x0[i0 + 1]),
                         mz = x[i1 + 2] - x0[i1 + 2] - (x[i0 + 2] - x0[i0 + 2]);
            const double nx = x[i2] - x0[i2] - (x[i0] - x0[i0]), ny = x[i2 + 1] - x0[i2 + 1] - (x[i0 + 1] - x0[i0 + 1]),
                         nz = x[i2 + 2] - x0[i2 + 2] - (x[i0 + 2] - x0[i0 + 2]);
            const double d1x = p * mx + r * nx, d1y = p * my + r * ny, d1z = p * mz + r * nz;
            const double d2x = q * mx + s * nx, d2y = q * my + s * ny, d2z = q * mz + s * nz;
            c1 += gamma * (f1x * d1x + f1y * d1y + f1z * d1z);
            c2 += gamma * (f2x * d2x + f2y * d2y + f2z * d2z);
            c3 += gamma * (f1x * d2x + f1y * d2y + f1z * d2z + f2x * d1x + f2y * d1y + f2z * d1z);
        }
        const double b0x = -(p + r), b0y = -(q + s);
        const double pxx = w0 * b0x * b0x + w1 * p * p + w2 * r * r;
        const double pyy = w0 * b0y * b0y + w1 * q * q + w2 * s * s;
        const double pxy = w0 * b0x * b0y + w1 * p * q + w2 * r * s;
        const double g = 1.0 + gamma;
        const double m11 = g * pxx * n11 + t->c11, m22 = g * pyy * n22 + t->c11, m12 = g * pxy * n12 + t->c12;
        const double m13 = g * (pxx * n12 + pxy * n11), m23 = g * (pxy * n22 + pyy * n12);
        const double m33 = g * (pxx * n22 + 2.0 * pxy * n12 + pyy * n11) + t->c33;
        const double k11 = m22 * m33 - m23 * m23, k12 = m13 * m23 - m12 * m33, k13 = m12 * m23 - m13 * m22;
        const double k22 = m11 * m33 - m13 * m13, k23 = m12 * m13 - m11 * m23, k33 = m11 * m22 - m12 * m12;
        const double det = m11 * k11 + m12 * k12 + m13 * k13;
        if (!(det > 0.0) || det > DBL_MAX) continue;
        const double inverse = -1.0 / det;
        const double l1 = inverse * (k11 * c1 + k12 * c2 + k13 * c3);
        const double l2 = inverse * (k12 * c1 + k22 * c2 + k23 * c3);
        const double l3 = inverse * (k13 * c1 + k23 * c2 + k33 * c3);
        const double ux = l1 * f1x + l3 * f2x, uy = l1 * f1y + l3 * f2y, uz = l1 * f1z + l3 * f2z;
        const double vx = l2 * f2x + l3 * f1x, vy = l2 * f2y + l3 * f1y, vz = l2 * f2z + l3 * f1z;
        move(x, i0, w0, b0x, b0y, ux, uy, uz, vx, vy, vz);
        move(x, i1, w1, p, q, ux, uy, uz, vx, vy, vz);
        move(x, i2, w2, r, s, ux, uy, uz, vx, vy, vz);
    }
}

static void project_bending(const Mesh *m, double *restrict x, const double *restrict w)
{
    for (int e = 0; e < m->elements; e++) {
        const double sh = m->scaled[e];
        if (sh == 0.0) continue;
        const int *slot = m->slots + SLOTS * e;
        const double *weight = m->weights + SLOTS * COMPONENTS * e;
        double b11 = 0, b12 = 0, b13 = 0, b22 = 0, b23 = 0, b33 = 0;
        double c[9] = { 0 };
        int free_particle = 0;
        for (int v = 0; v < SLOTS; v++) {
            const int particle = slot[v];
            if (particle < 0) break;
            const double k1 = weight[v], k2 = weight[SLOTS + v], k3 = weight[2 * SLOTS + v];
            const int o = 3 * particle;
            const double px = x[o], py = x[o + 1], pz = x[o + 2];
            c[0] += k1 * px; c[1] += k1 * py; c[2] += k1 * pz;
            c[3] += k2 * px; c[4] += k2 * py; c[5] += k2 * pz;
            c[6] += k3 * px; c[7] += k3 * py; c[8] += k3 * pz;
            const double wv = w[particle];
            if (wv != 0.0) {
                free_particle = 1;
                b11 += wv * k1 * k1; b12 += wv * k1 * k2; b13 += wv * k1 * k3;
                b22 += wv * k2 * k2; b23 += wv * k2 * k3; b33 += wv * k3 * k3;
            }
        }
        if (!free_particle) continue;
        const double m11 = sh * b11 + 1.0, m12 = sh * b12, m13 = sh * b13;
        const double m22 = sh * b22 + 1.0, m23 = sh * b23, m33 = sh * b33 + 1.0;
        const double k11 = m22 * m33 - m23 * m23, k12 = m13 * m23 - m12 * m33, k13 = m12 * m23 - m13 * m22;
        const double k22 = m11 * m33 - m13 * m13, k23 = m12 * m13 - m11 * m23, k33 = m11 * m22 - m12 * m12;
        const double det = m11 * k11 + m12 * k12 + m13 * k13;
        if (!(det >= 1.0) || det > DBL_MAX) continue;
        const double scale = -sh / det;
        for (int d = 0; d < 3; d++) {
            const double r1 = c[d], r2 = c[3 + d], r3 = c[6 + d];
            c[d] = scale * (k11 * r1 + k12 * r2 + k13 * r3);
            c[3 + d] = scale * (k12 * r1 + k22 * r2 + k23 * r3);
            c[6 + d] = scale * (k13 * r1 + k23 * r2 + k33 * r3);
        }
        for (int v = 0; v < SLOTS; v++) {
            const int particle = slot[v];
            if (particle < 0) break;
            const double wv = w[particle];
            if (wv == 0.0) continue;
            const double k1 = wv * weight[v], k2 = wv * weight[SLOTS + v], k3 = wv * weight[2 * SLOTS + v];
            const int o = 3 * particle;
            x[o] += k1 * c[0] + k2 * c[3] + k3 * c[6];
            x[o + 1] += k1 * c[1] + k2 * c[4] + k3 * c[7];
            x[o + 2] += k1 * c[2] + k2 * c[5] + k3 * c[8];
        }
    }
}

/* passes x (the membrane, then the bending); which = 1 the membrane only, 2 the bending only, 3 both. */
void mesh_project(void *mesh, double *x, const double *x0, const double *w, int passes, int which)
{
    const Mesh *m = mesh;
    for (int k = 0; k < passes; k++) {
        if (which & 1) project_membrane(m, x, x0, w);
        if (which & 2) project_bending(m, x, w);
    }
}

void mesh_destroy(void *mesh)
{
    Mesh *m = mesh;
    if (!m) return;
    free(m->tri); free(m->area); free(m->mu); free(m->lambda); free(m->tau);
    free(m->slots); free(m->weights); free(m->stiffness); free(m->scaled);
    free(m);
}
