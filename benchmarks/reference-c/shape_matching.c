/*
 * The plain C reference of the library's rigid shape matching (src/ParticlePhysics/Bodies/ShapeMatching.Rigid.cs),
 * for the benchmark mode `bodies --c`: per substep and per body, the projection (the prediction's angular momentum,
 * a turn by the midpoint rule, the particles put on their goals) and the velocity pass (the covariance's rotation by
 * the warm-started extraction of Mueller et al. 2016, the rigid velocity field). The same operations in the same
 * order as the library, its own sin and cos included (fdlibm's kernels), so that one pass gives the same bits.
 * Body b's entries are b * per to b * per + per - 1, each naming its particle (any particles, as the library's
 * bodies). Built as a shared library by run.sh; no dependency beyond libm's sqrt.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct { double x, y, z; } vec;
typedef struct { double w, x, y, z; } quat;

typedef struct {
    int bodies, per;
    int *particles; /* entry k of body b (k from b per) is particle particles[k] */
    vec *rest, *goals, *momentum;
    quat *orientation, *predicted;
} sm_set;

void sm_reset(sm_set *s);

static vec v3(double x, double y, double z) { vec r = { x, y, z }; return r; }
static vec add(vec a, vec b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static vec sub(vec a, vec b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static vec scale(double s, vec a) { return v3(s * a.x, s * a.y, s * a.z); }
static vec divide(vec a, double s) { return v3(a.x / s, a.y / s, a.z / s); }
static double dot(vec a, vec b) { return (a.x * b.x) + (a.y * b.y) + (a.z * b.z); }
static double length_squared(vec a) { return (a.x * a.x) + (a.y * a.y) + (a.z * a.z); }
static vec cross(vec a, vec b) { return v3((a.y * b.z) - (a.z * b.y), (a.z * b.x) - (a.x * b.z), (a.x * b.y) - (a.y * b.x)); }
static vec at(const double *values, int i) { return v3(values[3 * i], values[3 * i + 1], values[3 * i + 2]); }
static void put(double *values, int i, vec a) { values[3 * i] = a.x; values[3 * i + 1] = a.y; values[3 * i + 2] = a.z; }

/* The library's DeterministicTrig: Cody-Waite reduction by pi/2 in three parts, fdlibm's kernels. */
static const double two_over_pi = 6.36619772367581382433e-01;
static const double half_pi1 = 1.57079632673412561417e+00, half_pi2 = 6.07710050630396597660e-11, half_pi3 = 2.02226624879595063154e-21;
static const double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03, s3 = -1.98412698298579493134e-04,
                    s4 = 2.75573137070700676789e-06, s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
static const double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03, c3 = 2.48015872894767294178e-05,
                    c4 = -2.75573143513906633035e-07, c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;

static int reduce(double x, double *r)
{
    if (!(x >= -1e15 && x <= 1e15)) { *r = NAN; return -1; }
    double scaled = x * two_over_pi;
    int64_t k = (int64_t)(scaled >= 0.0 ? scaled + 0.5 : scaled - 0.5);
    double kd = (double)k;
    *r = ((x - (kd * half_pi1)) - (kd * half_pi2)) - (kd * half_pi3);
    return (int)(k & 3);
}

static double sin_kernel(double r)
{
    double z = r * r;
    return r + (r * z * (s1 + (z * (s2 + (z * (s3 + (z * (s4 + (z * (s5 + (z * s6)))))))))));
}

static double cos_kernel(double r)
{
    double z = r * r;
    double tail = z * z * (c1 + (z * (c2 + (z * (c3 + (z * (c4 + (z * (c5 + (z * c6))))))))));
    return 1.0 - (0.5 * z) + tail;
}

static double select_quadrant(int quadrant, double s, double c)
{
    if (quadrant < 0) return NAN;
    double value = (quadrant & 1) ? c : s;
    return (quadrant & 2) ? -value : value;
}

static double own_sin(double x) { double r; int q = reduce(x, &r); return select_quadrant(q, sin_kernel(r), cos_kernel(r)); }
static double own_cos(double x) { double r; int q = reduce(x, &r); return q < 0 ? NAN : select_quadrant(q + 1, sin_kernel(r), cos_kernel(r)); }

static quat qmul(quat b, quat a)
{
    quat r = {
        (b.w * a.w) - (b.x * a.x) - (b.y * a.y) - (b.z * a.z),
        (b.w * a.x) + (b.x * a.w) + (b.y * a.z) - (b.z * a.y),
        (b.w * a.y) - (b.x * a.z) + (b.y * a.w) + (b.z * a.x),
        (b.w * a.z) + (b.x * a.y) - (b.y * a.x) + (b.z * a.w),
    };
    return r;
}

static quat from_rotation_vector(vec theta)
{
    double angle = sqrt(length_squared(theta)), c, s;
    if (angle < 1e-4) {
        double a2 = angle * angle;
        s = 0.5 - (a2 / 48.0);
        c = 1.0 - (a2 / 8.0) + (a2 * a2 / 384.0);
    } else {
        s = own_sin(0.5 * angle) / angle;
        c = own_cos(0.5 * angle);
    }
    quat q = { c, s * theta.x, s * theta.y, s * theta.z };
    return q;
}

static quat normalized(quat q)
{
    double norm = sqrt((q.w * q.w) + (q.x * q.x) + (q.y * q.y) + (q.z * q.z));
    if (!(norm > 0.0)) { quat one = { 1.0, 0.0, 0.0, 0.0 }; return one; }
    quat r = { q.w / norm, q.x / norm, q.y / norm, q.z / norm };
    return r;
}

static vec rotate_by(double w, vec u, vec v)
{
    vec t = scale(2.0, cross(u, v));
    return add(add(v, scale(w, t)), cross(u, t));
}

static vec rotate(quat q, vec v) { return rotate_by(q.w, v3(q.x, q.y, q.z), v); }
static vec rotate_inverse(quat q, vec v) { return rotate_by(q.w, v3(-q.x, -q.y, -q.z), v); }

/* The rest inertia tensor about the rest centre (xx, xy, xz, yy, yz, zz), as RestInertia.Of. */
typedef struct { double xx, xy, xz, yy, yz, zz; } inertia;

static inertia inertia_of(const vec *rest, const int *particles, const double *m, int first, int per, vec centre)
{
    double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
    for (int k = 0; k < per; k++) {
        double mi = m[particles[first + k]];
        vec d = sub(rest[first + k], centre);
        double dx2 = d.x * d.x, dy2 = d.y * d.y, dz2 = d.z * d.z;
        xx += mi * (dy2 + dz2);
        yy += mi * (dx2 + dz2);
        zz += mi * (dx2 + dy2);
        xy -= mi * d.x * d.y;
        xz -= mi * d.x * d.z;
        yz -= mi * d.y * d.z;
    }
    inertia r = { xx, xy, xz, yy, yz, zz };
    return r;
}

static vec angular_velocity(inertia t, quat q, vec momentum)
{
    vec b = rotate_inverse(q, momentum);
    double c00 = (t.yy * t.zz) - (t.yz * t.yz);
    double c01 = (t.xz * t.yz) - (t.xy * t.zz);
    double c02 = (t.xy * t.yz) - (t.xz * t.yy);
    double det = (t.xx * c00) + (t.xy * c01) + (t.xz * c02);
    if (!(det > 0.0)) return v3(0.0, 0.0, 0.0);
    double c11 = (t.xx * t.zz) - (t.xz * t.xz);
    double c12 = (t.xy * t.xz) - (t.xx * t.yz);
    double c22 = (t.xx * t.yy) - (t.xy * t.xy);
    vec y = v3(((c00 * b.x) + (c01 * b.y) + (c02 * b.z)) / det,
               ((c01 * b.x) + (c11 * b.y) + (c12 * b.z)) / det,
               ((c02 * b.x) + (c12 * b.y) + (c22 * b.z)) / det);
    return rotate(q, y);
}

/* One Newton step of the extraction: M omega = torque with M = tr(B) 1 - B, B_jk = sum_i r_i,j a_i,k. */
static int newton_step(vec r0, vec r1, vec r2, vec a0, vec a1, vec a2, double trace, vec t, vec *omega)
{
    double m00 = trace - ((r0.x * a0.x) + (r1.x * a1.x) + (r2.x * a2.x));
    double m01 = -((r0.x * a0.y) + (r1.x * a1.y) + (r2.x * a2.y));
    double m02 = -((r0.x * a0.z) + (r1.x * a1.z) + (r2.x * a2.z));
    double m10 = -((r0.y * a0.x) + (r1.y * a1.x) + (r2.y * a2.x));
    double m11 = trace - ((r0.y * a0.y) + (r1.y * a1.y) + (r2.y * a2.y));
    double m12 = -((r0.y * a0.z) + (r1.y * a1.z) + (r2.y * a2.z));
    double m20 = -((r0.z * a0.x) + (r1.z * a1.x) + (r2.z * a2.x));
    double m21 = -((r0.z * a0.y) + (r1.z * a1.y) + (r2.z * a2.y));
    double m22 = trace - ((r0.z * a0.z) + (r1.z * a1.z) + (r2.z * a2.z));
    double c00 = (m11 * m22) - (m12 * m21);
    double c01 = (m02 * m21) - (m01 * m22);
    double c02 = (m01 * m12) - (m02 * m11);
    double det = (m00 * c00) + (m10 * c01) + (m20 * c02);
    if (!(det > 0.0) || isinf(det)) return 0;
    double c10 = (m12 * m20) - (m10 * m22);
    double c11 = (m00 * m22) - (m02 * m20);
    double c12 = (m02 * m10) - (m00 * m12);
    double c20 = (m10 * m21) - (m11 * m20);
    double c21 = (m01 * m20) - (m00 * m21);
    double c22 = (m00 * m11) - (m01 * m10);
    *omega = v3(((c00 * t.x) + (c01 * t.y) + (c02 * t.z)) / det,
                ((c10 * t.x) + (c11 * t.y) + (c12 * t.z)) / det,
                ((c20 * t.x) + (c21 * t.y) + (c22 * t.z)) / det);
    return 1;
}

static quat extract(const double a[9], quat start)
{
    vec k0 = v3(a[0], a[3], a[6]), k1 = v3(a[1], a[4], a[7]), k2 = v3(a[2], a[5], a[8]);
    double eps = 1e-12 * (sqrt(length_squared(k0)) + sqrt(length_squared(k1)) + sqrt(length_squared(k2)));
    if (!(eps > 0.0)) return start;
    quat q = start;
    for (int k = 0; k < 24; k++) {
        vec r0 = rotate(q, v3(1.0, 0.0, 0.0)), r1 = rotate(q, v3(0.0, 1.0, 0.0)), r2 = rotate(q, v3(0.0, 0.0, 1.0));
        vec torque = add(add(cross(r0, k0), cross(r1, k1)), cross(r2, k2));
        double trace = dot(r0, k0) + dot(r1, k1) + dot(r2, k2);
        vec omega;
        if (!newton_step(r0, r1, r2, k0, k1, k2, trace, torque, &omega)) omega = divide(torque, fabs(trace) + eps);
        if (!(length_squared(omega) > 1e-15 * 1e-15)) break;
        q = normalized(qmul(from_rotation_vector(omega), q));
    }
    return q;
}

static void centres(const sm_set *s, int first, const double *x, const double *m, double *mass, vec *centre, vec *rest_centre)
{
    double total = 0.0;
    vec c = v3(0, 0, 0), r = v3(0, 0, 0);
    for (int k = first; k < first + s->per; k++) {
        int i = s->particles[k];
        total += m[i];
        c = add(c, scale(m[i], at(x, i)));
        r = add(r, scale(m[i], s->rest[k]));
    }
    *mass = total;
    *centre = divide(c, total);
    *rest_centre = divide(r, total);
}

static void project_rigid(sm_set *s, int b, double h, const double *x0, double *x, const double *m, const double *w)
{
    int first = b * s->per, end = first + s->per;
    double mass, mass0;
    vec c, rest_centre, c0, unused;
    centres(s, first, x, m, &mass, &c, &rest_centre);
    centres(s, first, x0, m, &mass0, &c0, &unused);
    double inverse_h = 1.0 / h;
    vec momentum = v3(0, 0, 0), velocity = v3(0, 0, 0);
    for (int k = first; k < end; k++) {
        int i = s->particles[k];
        vec start = at(x0, i);
        vec vi = scale(inverse_h, sub(at(x, i), start));
        momentum = add(momentum, scale(m[i], cross(sub(start, c0), vi)));
        velocity = add(velocity, scale(m[i], vi));
    }
    (void)velocity;
    quat q0 = s->orientation[b];
    inertia t = inertia_of(s->rest, s->particles, m, first, s->per, rest_centre);
    vec omega = angular_velocity(t, q0, momentum);
    quat half = normalized(qmul(from_rotation_vector(scale(0.5 * h, omega)), q0));
    omega = angular_velocity(t, half, momentum);
    quat q = normalized(qmul(from_rotation_vector(scale(h, omega)), q0));
    for (int k = first; k < end; k++) {
        int i = s->particles[k];
        vec goal = add(c, rotate(q, sub(s->rest[k], rest_centre)));
        s->goals[k] = goal;
        if (w[i] != 0.0) put(x, i, goal);
    }
    s->predicted[b] = q;
    s->momentum[b] = momentum;
}

static void solve_rigid_velocities(sm_set *s, int b, double h, const double *x0, const double *x, double *v, const double *m, const double *w)
{
    int first = b * s->per, end = first + s->per;
    double mass;
    vec c, rest_centre;
    centres(s, first, x, m, &mass, &c, &rest_centre);
    double inverse_h = 1.0 / h;
    vec velocity = v3(0, 0, 0), extra = v3(0, 0, 0);
    double a[9] = { 0 };
    for (int k = first; k < end; k++) {
        int i = s->particles[k];
        double mi = m[i];
        vec r = sub(at(x, i), c);
        vec vi = at(v, i);
        velocity = add(velocity, scale(mi, vi));
        extra = add(extra, scale(mi, cross(r, sub(vi, scale(inverse_h, sub(s->goals[k], at(x0, i)))))));
        vec p = scale(mi, r), q = sub(s->rest[k], rest_centre);
        a[0] += p.x * q.x; a[1] += p.x * q.y; a[2] += p.x * q.z;
        a[3] += p.y * q.x; a[4] += p.y * q.y; a[5] += p.y * q.z;
        a[6] += p.z * q.x; a[7] += p.z * q.y; a[8] += p.z * q.z;
    }
    velocity = divide(velocity, mass);
    quat q = extract(a, s->predicted[b]);
    vec omega = angular_velocity(inertia_of(s->rest, s->particles, m, first, s->per, rest_centre), q, add(s->momentum[b], extra));
    for (int k = first; k < end; k++) {
        int i = s->particles[k];
        if (w[i] != 0.0) put(v, i, add(velocity, cross(omega, sub(at(x, i), c))));
    }
    s->orientation[b] = q;
}

/* A set of `bodies` rigid bodies of `per` entries each: particle particles[e] at rest offset rest[3 e], orientations at rest. */
sm_set *sm_create(int bodies, int per, const int *particles, const double *rest)
{
    if (bodies < 1 || per < 1) return NULL;
    sm_set *s = calloc(1, sizeof *s);
    size_t n = (size_t)bodies * (size_t)per;
    s->bodies = bodies;
    s->per = per;
    s->particles = malloc(n * sizeof(int));
    s->rest = malloc(n * sizeof(vec));
    s->goals = malloc(n * sizeof(vec));
    s->momentum = calloc((size_t)bodies, sizeof(vec));
    s->orientation = malloc((size_t)bodies * sizeof(quat));
    s->predicted = malloc((size_t)bodies * sizeof(quat));
    for (size_t k = 0; k < n; k++) {
        s->particles[k] = particles[k];
        s->rest[k] = v3(rest[3 * k], rest[3 * k + 1], rest[3 * k + 2]);
    }
    sm_reset(s);
    return s;
}

void sm_reset(sm_set *s)
{
    quat one = { 1.0, 0.0, 0.0, 0.0 };
    for (int b = 0; b < s->bodies; b++) { s->orientation[b] = one; s->predicted[b] = one; }
}

/* `passes` substeps' worth of the set's two calls on the same arrays: the projection, then the velocity pass. */
void sm_run(sm_set *s, double h, const double *x0, double *x, double *v, const double *m, const double *w, int passes)
{
    for (int p = 0; p < passes; p++) {
        for (int b = 0; b < s->bodies; b++) project_rigid(s, b, h, x0, x, m, w);
        for (int b = 0; b < s->bodies; b++) solve_rigid_velocities(s, b, h, x0, x, v, m, w);
    }
}

void sm_destroy(sm_set *s)
{
    if (!s) return;
    free(s->particles); free(s->rest); free(s->goals); free(s->momentum); free(s->orientation); free(s->predicted);
    free(s);
}
