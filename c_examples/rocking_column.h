/* What the FE-style C examples share: opensees_style_harness.c (rigid blocks) and stiff_blocks.c
 * (the same analysis with axially elastic blocks) model a column of blocks the same way and
 * handle its events the same way; this header holds that common part once.
 *
 *   - the scenes and their ground acceleration;
 *   - the column model: three lumped mass points per block on its axis (thesis Appendix C), the
 *     current geometry from the interface DOF angles (large rotations, optionally axial
 *     stretches), the transformation B (Eq. C2) and the reduction BᵀMB, Bᵀp through
 *     rocking_reduce (Eq. C6, C8);
 *   - the dense algebra (Cholesky on a sub-matrix) and the interface DOF bookkeeping;
 *   - the pieces of the Newmark step (average acceleration) and of the event handling (impact
 *     crossing, overturning, settling, the opening ladder of SPEC §5 trap (a)) that do not depend
 *     on a program's state layout;
 *   - the transient analysis itself: trial / commit / revert with step halving onto events;
 *   - the self-check and status reporting.
 *
 * Each program keeps its own state, analysis and event records (the elastic program carries the
 * axial DOFs and the mode of coupling), its Newmark iteration, its event handlers and the two
 * hooks through which transient() calls them.
 *
 * Use: #define MAXB (the most blocks a column has) and, when the program's generalised DOFs are
 * more than the 2 MAXB interface DOFs, MAXQ (their most), then #include "rocking_column.h".
 * Header-only: every function is static and used by both programs (with -Wall -Werror an unused
 * one would not compile). C99, only rocking.h and the C library. */
#ifndef ROCKING_COLUMN_H
#define ROCKING_COLUMN_H

#include <math.h>
#include <stdio.h>
#include <string.h>
#include "rocking.h"

#ifndef MAXB
#error "define MAXB (the most blocks a column has) before including rocking_column.h"
#endif
#define MAXD (2 * MAXB)           /* interface DOFs */
#define MAXNODES (3 * MAXB)       /* mass nodes */
#define MAXND (2 * MAXNODES)      /* nodal DOFs */
#ifndef MAXQ
#define MAXQ MAXD                 /* generalised DOFs: the interface DOFs unless the program adds */
#endif
#define PI 3.14159265358979323846
#define GRAVITY 9.81

/* ------------------------------------------------------------------------------------------ */
/* Scenes                                                                                       */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
    const char *name;
    const char *title;
    int nb;
    double width[MAXB], height[MAXB], mass[MAXB], contact[MAXB]; /* contact[0] == 0: default */
    double initial[MAXB];   /* initial angle per interface: < 0 right corner, > 0 left corner */
    /* ground acceleration a(t) = amp * sin(pi t / half_period) for 0 <= t <= lobes*half_period */
    double amp, half_period;
    int lobes;
    uint32_t n_impacts;     /* consecutive impacts per closing (1 = Housner) */
    double dt, duration;
} Scene;

static double ground(const Scene *s, double t) {
    if (s->lobes == 0 || t < 0.0 || t > s->lobes * s->half_period) return 0.0;
    return s->amp * sin(PI * t / s->half_period);
}

/* The library's options for a scene: its impacts per closing, the automatic solver, the
 * recommended tolerance of the admissibility tests. */
static RockingOptions scene_options(const Scene *s) {
    RockingOptions o;
    memset(&o, 0, sizeof o);
    o.n_impacts = s->n_impacts;
    o.solver = 0;
    o.tolerance = 1e-12;
    return o;
}

/* ------------------------------------------------------------------------------------------ */
/* Column: blocks, nodes, lumped masses (thesis Appendix C)                                     */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
    int nb;                       /* blocks = interfaces */
    double width[MAXB], height[MAXB], mass[MAXB], inertia[MAXB];
    double half_contact[MAXB];    /* b_k of interface k (under block k) */
    double base_y[MAXB];          /* height of interface k in the straight column */
    int n_nodes;
    double node_ref[MAXNODES][2]; /* reference (straight) coordinates */
    double node_mass[MAXNODES];
    int node_block[MAXNODES];
    double nodal_mass[MAXND * MAXND]; /* lumped: diagonal, column-major */
} Column;

/* Builds the column of nb blocks (widths w, heights h, masses m) with three mass points per block
 * on its axis (bottom, centre, top): the ends carry I / (2 (h/2)^2), the centre the rest, so that
 * mass, centre and moment of inertia are reproduced (Appendix C). Nodal DOFs node by node (x, y),
 * as OpenSees numbers them. contact_width may be NULL (min of the widths). */
static void column_init(Column *d, int nb, const double *w, const double *h, const double *m,
                        const double *contact_width) {
    int k, i, nd;
    double y = 0.0;
    memset(d, 0, sizeof *d);
    d->nb = nb;
    for (k = 0; k < nb; k++) {
        double half, end;
        d->width[k] = w[k];
        d->height[k] = h[k];
        d->mass[k] = m[k];
        d->inertia[k] = m[k] * (w[k] * w[k] + h[k] * h[k]) / 12.0;
        if (contact_width) {
            d->half_contact[k] = 0.5 * contact_width[k];
        } else {
            d->half_contact[k] = 0.5 * (k == 0 ? w[0] : fmin(w[k - 1], w[k]));
        }
        d->base_y[k] = y;
        half = 0.5 * h[k];
        end = d->inertia[k] / (2.0 * half * half);
        for (i = 0; i < 3; i++) {
            int n = 3 * k + i;
            d->node_ref[n][0] = 0.0;
            d->node_ref[n][1] = y + half * i;
            d->node_mass[n] = (i == 1) ? m[k] - 2.0 * end : end;
            d->node_block[n] = k;
        }
        y += h[k];
    }
    d->n_nodes = 3 * nb;
    nd = 2 * d->n_nodes;
    for (i = 0; i < d->n_nodes; i++) {
        d->nodal_mass[(2 * i) * nd + 2 * i] = d->node_mass[i];
        d->nodal_mass[(2 * i + 1) * nd + 2 * i + 1] = d->node_mass[i];
    }
}

/* Smallest potential energy that tips a part of the straight column: m_above g (R - y_c) over the
 * interfaces (the scale of the settling rule, see settles). */
static double column_tip_energy(const Column *d) {
    double tip = INFINITY;
    int k, j;
    for (k = 0; k < d->nb; k++) {
        double m = 0.0, my = 0.0, b = d->half_contact[k];
        for (j = k; j < d->nb; j++) {
            m += d->mass[j];
            my += d->mass[j] * (d->base_y[j] + 0.5 * d->height[j] - d->base_y[k]);
        }
        my /= m;
        tip = fmin(tip, m * GRAVITY * (sqrt(b * b + my * my) - my));
    }
    return tip;
}

/* Current geometry from the interface DOF angles (large rotations): interface k turns everything
 * above it by phi[k] + phi[n+k] about its right corner (phi[k] != 0) or its left corner. */
typedef struct {
    double pivot[MAXD][2];        /* pivot of each DOF: right corners, then left corners */
    double node[MAXNODES][2];     /* current node positions */
    double angle[MAXB];           /* absolute block rotations */
} Geometry;

/* The geometry at phi and the axial stretches e (NULL: rigid blocks). A stretch e_k lengthens
 * block k between its base node and its centre: the reference column above is taller by e_k, and
 * the rotations turn it with the blocks. */
static void column_geometry(const Column *d, const double *phi, const double *e, Geometry *g) {
    int n = d->nb, k, i;
    double ca = 1.0, sa = 0.0, alpha = 0.0, t[2] = {0.0, 0.0}, shift = 0.0;
    for (k = 0; k < n; k++) {
        double b = d->half_contact[k], y = d->base_y[k] + shift, theta = phi[k] + phi[n + k];
        double ek = e ? e[k] : 0.0;
        /* corners of interface k belong to the block below (the ground for k = 0) */
        g->pivot[k][0] = ca * b - sa * y + t[0];
        g->pivot[k][1] = sa * b + ca * y + t[1];
        g->pivot[n + k][0] = -ca * b - sa * y + t[0];
        g->pivot[n + k][1] = -sa * b + ca * y + t[1];
        if (theta != 0.0) {
            const double *p = phi[k] != 0.0 ? g->pivot[k] : g->pivot[n + k];
            double ct = cos(theta), st = sin(theta), dx = t[0] - p[0], dy = t[1] - p[1];
            /* x -> P + R(theta) (R(alpha) X + t - P) */
            t[0] = p[0] + ct * dx - st * dy;
            t[1] = p[1] + st * dx + ct * dy;
            alpha += theta;
            ca = cos(alpha);
            sa = sin(alpha);
        }
        g->angle[k] = alpha;
        for (i = 3 * k; i < 3 * k + 3; i++) {
            double X = d->node_ref[i][0], Y = d->node_ref[i][1] + shift + (i > 3 * k ? ek : 0.0);
            g->node[i][0] = ca * X - sa * Y + t[0];
            g->node[i][1] = sa * X + ca * Y + t[1];
        }
        shift += ek;
    }
}

/* Transformation B (Eq. C2; nodal DOFs x interface DOFs, column-major, 2 n_nodes rows): a
 * rotation rate about the pivot P of DOF a moves every node r above interface k = a mod n at
 * z x (r - P). Writes the first 2n columns of B. */
static void column_transformation(const Column *d, const Geometry *g, double *B) {
    int n = d->nb, rows = 2 * d->n_nodes, a, i;
    for (a = 0; a < 2 * n; a++) {
        int k = a % n;
        for (i = 0; i < d->n_nodes; i++) {
            int above = d->node_block[i] >= k;
            B[a * rows + 2 * i] = above ? -(g->node[i][1] - g->pivot[a][1]) : 0.0;
            B[a * rows + 2 * i + 1] = above ? (g->node[i][0] - g->pivot[a][0]) : 0.0;
        }
    }
}

/* The reduced system of a transformation J (2 n_nodes x ncols, column-major; B, or B with the
 * program's own columns after it): M = JᵀMJ (ncols x ncols), q = Jᵀp, with the nodal loads
 * p = (-m a_g, -m g) of the ground acceleration and gravity (Eq. C6 and C8, through
 * rocking_reduce). Returns the library's code. */
static int32_t column_reduce(const Column *d, const double *J, int ncols, double ag, double *M,
                             double *q) {
    double p[MAXND];
    int i;
    for (i = 0; i < d->n_nodes; i++) {
        p[2 * i] = -d->node_mass[i] * ag;
        p[2 * i + 1] = -d->node_mass[i] * GRAVITY;
    }
    return rocking_reduce((size_t)(2 * d->n_nodes), (size_t)ncols, d->nodal_mass, J, p, M, q);
}

/* ------------------------------------------------------------------------------------------ */
/* Small dense algebra                                                                          */
/* ------------------------------------------------------------------------------------------ */

/* Solves A_sub x = r by Cholesky, A_sub the nf x nf sub-matrix on the DOFs idx of the column-major
 * matrix A (leading dimension ld), plus diag[i] on its diagonal (diag may be NULL).
 * Returns 0, or 1 if not positive definite. */
static int solve_sub(int ld, const double *A, const double *diag, const int *idx, int nf,
                     const double *r, double *x) {
    double L[MAXQ * MAXQ], y[MAXQ];
    int i, j, k;
    for (i = 0; i < nf; i++) {
        for (j = 0; j <= i; j++) {
            double s = A[idx[j] * ld + idx[i]];
            if (diag && i == j) s += diag[i];
            for (k = 0; k < j; k++) s -= L[i * MAXQ + k] * L[j * MAXQ + k];
            if (i == j) {
                if (!(s > 0.0)) return 1;
                L[i * MAXQ + i] = sqrt(s);
            } else {
                L[i * MAXQ + j] = s / L[j * MAXQ + j];
            }
        }
    }
    for (i = 0; i < nf; i++) {
        double s = r[i];
        for (k = 0; k < i; k++) s -= L[i * MAXQ + k] * y[k];
        y[i] = s / L[i * MAXQ + i];
    }
    for (i = nf - 1; i >= 0; i--) {
        double s = y[i];
        for (k = i + 1; k < nf; k++) s -= L[k * MAXQ + i] * x[k];
        x[i] = s / L[i * MAXQ + i];
    }
    return 0;
}

/* ------------------------------------------------------------------------------------------ */
/* Interface DOFs and configurations (SPEC §1: [phĭ_0 .. phĭ_{n-1}, phî_0 .. phî_{n-1}])        */
/* ------------------------------------------------------------------------------------------ */

/* The DOF interface k rotates on when open: phĭ_k (k) for status -1, phî_k (n + k) otherwise. */
static int open_dof(int n, int k, const int8_t *status) { return status[k] < 0 ? k : n + k; }

/* Free DOFs of a configuration: the open DOF of each open interface. */
static int free_rotations(int n, const int8_t *status, int *idx) {
    int k, nf = 0;
    for (k = 0; k < n; k++)
        if (status[k] != 0) idx[nf++] = open_dof(n, k, status);
    return nf;
}

/* Status of an interface released at this angle: -1 right corner, +1 left corner, 0 closed. */
static int8_t initial_status(double angle) {
    return (int8_t)(angle < 0.0 ? -1 : angle > 0.0 ? 1 : 0);
}

/* The scene's initial configuration and angles (phi zero on entry): at rest, tilted as it says. */
static void initial_configuration(const Scene *s, int8_t *status, double *phi) {
    int n = s->nb, k;
    for (k = 0; k < n; k++) {
        status[k] = initial_status(s->initial[k]);
        if (s->initial[k] < 0.0) phi[k] = s->initial[k];
        if (s->initial[k] > 0.0) phi[n + k] = s->initial[k];
    }
}

/* ------------------------------------------------------------------------------------------ */
/* Newmark's average acceleration method (γ = 1/2, β = 1/4)                                     */
/* ------------------------------------------------------------------------------------------ */

/* Trial displacements on the DOFs idx from the committed x0, v0, a0 and the trial acceleration a:
 * x = x0 + h v0 + h²/4 (a0 + a). */
static void newmark_displacements(int nf, const int *idx, double h, const double *x0,
                                  const double *v0, const double *a0, const double *a, double *x) {
    int i;
    for (i = 0; i < nf; i++) {
        int j = idx[i];
        x[j] = x0[j] + h * v0[j] + 0.25 * h * h * (a0[j] + a[j]);
    }
}

/* Trial rates on the DOFs idx: v = v0 + h/2 (a0 + a). */
static void newmark_rates(int nf, const int *idx, double h, const double *v0, const double *a0,
                          const double *a, double *v) {
    int i;
    for (i = 0; i < nf; i++) {
        int j = idx[i];
        v[j] = v0[j] + 0.5 * h * (a0[j] + a[j]);
    }
}

/* Fixed-point iteration on the acceleration: folds the change of a[0..n) from old into *change
 * and its size into *scale (the iteration stops when change <= tolerance * scale). */
static void iteration_change(int n, const double *a, const double *old, double *change,
                             double *scale) {
    int i;
    for (i = 0; i < n; i++) {
        *change = fmax(*change, fabs(a[i] - old[i]));
        *scale = fmax(*scale, fabs(a[i]));
    }
}

/* ------------------------------------------------------------------------------------------ */
/* Events                                                                                       */
/* ------------------------------------------------------------------------------------------ */

/* Impact in a step from phi0 (configuration status) to (phi1, rate1): an open DOF came back
 * through zero, moving towards it (SPEC §5 trap (b): a DOF that has just opened at exactly zero
 * and moves away is not an impact). Returns the interface crossing first in the step, or -1. */
static int impact_crossing(int n, const int8_t *status, const double *phi0, const double *phi1,
                           const double *rate1) {
    double first = 2.0;
    int which = -1, k;
    for (k = 0; k < n; k++) {
        int a = open_dof(n, k, status);
        double sgn = status[k] < 0 ? -1.0 : 1.0;
        if (status[k] == 0) continue;
        if (sgn * phi1[a] < 0.0 && sgn * rate1[a] < 0.0) {
            double frac = phi0[a] / (phi0[a] - phi1[a]);
            if (frac < first) {
                first = frac;
                which = k;
            }
        }
    }
    return which;
}

/* Overturning: the first open interface with the centre of mass of the part above it beyond its
 * pivot (in the geometry g), or -1. */
static int overturning(const Column *d, const int8_t *status, const Geometry *g) {
    int n = d->nb, k, j;
    for (k = 0; k < n; k++) {
        double mx = 0.0, mm = 0.0;
        const double *p;
        if (status[k] == 0) continue;
        p = g->pivot[open_dof(n, k, status)];
        for (j = 3 * k; j < d->n_nodes; j++) {
            mx += d->node_mass[j] * g->node[j][0];
            mm += d->node_mass[j];
        }
        mx /= mm;
        if ((status[k] > 0 && mx < p[0]) || (status[k] < 0 && mx > p[0])) return k;
    }
    return -1;
}

/* Whether a configuration has a closed interface (an opening is possible). */
static int any_closed(int n, const int8_t *status) {
    int k;
    for (k = 0; k < n; k++)
        if (status[k] == 0) return 1;
    return 0;
}

/* x = x0 + frac (x - x0) on n values: the state at a fraction of the step from x0 to x. */
static void interpolate(int n, double frac, const double *x0, double *x) {
    int i;
    for (i = 0; i < n; i++) x[i] = x0[i] + frac * (x[i] - x0[i]);
}

/* Settling (a rule of these programs, as the driver's): impacts of shrinking amplitude accumulate
 * in finite time (Zeno); when the kinetic energy left after an impact is negligible next to the
 * tip energy, or two impacts at the interface come closer than four steps, the interface is
 * closed for good. */
static int settles(double kinetic_after, double tip_energy, double t, double last_impact,
                   double dt) {
    return kinetic_after < 1e-6 * tip_energy || t - last_impact < 4.0 * dt;
}

/* Kinetic-metric projection of the rotation rates onto the configuration's open DOFs (what
 * remains of the motion when an interface is closed for good): M_FF v_F = (M v)_F, M the
 * interface-DOF block of a matrix of leading dimension ld; the closed DOFs' rates become 0. */
static void project_rates(int n, int ld, const double *M, const int8_t *status, double *rate) {
    int idx[MAXD], nf = free_rotations(n, status, idx), i, j;
    double r[MAXD], x[MAXD];
    for (i = 0; i < nf; i++) {
        r[i] = 0.0;
        for (j = 0; j < 2 * n; j++) r[i] += M[j * ld + idx[i]] * rate[j];
    }
    if (nf) solve_sub(ld, M, NULL, idx, nf, r, x);
    for (i = 0; i < 2 * n; i++) rate[i] = 0.0;
    for (i = 0; i < nf; i++) rate[idx[i]] = x[i];
}

/* The opening model is judged a little past the event (SPEC §5 trap (a)): at the committed state
 * the violated reaction is only ~1e-11 (the event was located to H_MIN), and there the library's
 * enumeration solver still prefers the current configuration (its criterion beats the opening
 * ones only by a relative ~1e-22, below the enumeration's 1e-14 tie margin) while
 * rocking_check_configuration already says "must open". So, as the Rust driver does, the state is
 * extrapolated by eps = OPENING_LADDER[l] steps and the model asked again there, rung by rung,
 * until it opens something. */
#define OPENING_RUNGS 5
static const double OPENING_LADDER[OPENING_RUNGS] = {0.0, 1e-3, 1e-2, 1e-1, 1.0};

/* The opening model on the system (M, q) of the configuration status (interface DOFs): when it
 * opens something (its report says changed), status takes the new configuration and *changed is
 * set. Returns the library's code. */
static int32_t opening_model(int n, const double *M, const double *q, int8_t *status,
                             const RockingOptions *opts, int *changed) {
    int8_t st[MAXB];
    double acc[MAXD];
    RockingReport rep;
    int32_t code;
    memcpy(st, status, MAXB);
    code = rocking_opening_model((size_t)n, M, q, st, acc, opts, &rep);
    *changed = code == ROCKING_OK && rep.changed;
    if (*changed) memcpy(status, st, MAXB);
    return code;
}

/* out = x + eps v + eps²/2 a on n values: the state extrapolated by eps. */
static void extrapolate(int n, double eps, const double *x, const double *v, const double *a,
                        double *out) {
    int i;
    for (i = 0; i < n; i++) out[i] = x[i] + eps * v[i] + 0.5 * eps * eps * a[i];
}

/* After an opening from the configuration before: the interfaces that opened start at zero
 * angle and rate. Returns the first of them (n if none). */
static int start_openings(int n, const int8_t *before, const int8_t *status, double *phi,
                          double *rate) {
    int k, first = n;
    for (k = 0; k < n; k++) {
        if (before[k] == 0 && status[k] != 0) {
            phi[k] = phi[n + k] = 0.0;
            rate[k] = rate[n + k] = 0.0;
            if (first == n) first = k;
        }
    }
    return first;
}

/* Peak absolute rotation of every block so far. */
static void track_peaks(int n, const Geometry *g, double *peak) {
    int k;
    for (k = 0; k < n; k++) peak[k] = fmax(peak[k], fabs(g->angle[k]));
}

/* ------------------------------------------------------------------------------------------ */
/* The transient analysis: trial / commit / revert with step halving onto events                */
/* ------------------------------------------------------------------------------------------ */

/* The program's side of transient(), on its own analysis `an` (the programs' states differ),
 * which keeps a committed state, a trial state and the commit before the last:
 *   trial(an, h, &k):      a Newmark trial step of length h from the committed state, and the
 *                          event in it: 0 none, 1 impact, 2 opening, 3 overturning (for 1 and 3
 *                          the interface in k), < 0 when the step failed;
 *   commit(an, event, k):  commits the trial step and handles its event at that state: 0 go
 *                          on, 1 stop (overturned, or the program's own reason), < 0 failed. */
typedef int (*TrialStep)(void *an, double h, int *k);
typedef int (*CommitStep)(void *an, int event, int k);

/* The transient analysis, OpenSees's analyze(duration / dt) with event-driven step subdivision:
 * trial steps go to the next multiple of dt; a trial step that contains an event is reverted to
 * the last commit and halved until it is no longer than h_min (H_MIN), then committed, and the
 * event is handled at that state. *t is the committed time and *failed the program's flag of a
 * failed library call, both read after every hook. Returns 1 when a hook failed, else *failed. */
static int transient(void *an, TrialStep trial, CommitStep commit, const double *t,
                     const int *failed, double dt, double duration, double h_min) {
    while (*t < duration - 1e-12 && !*failed) {
        double target = fmin((floor(*t / dt + 1e-6) + 1.0) * dt, duration);
        double h = target - *t;
        while (*t < target - 1e-15 && !*failed) {
            int k = -1, ev = trial(an, h, &k), stop;
            if (ev < 0) return 1;
            if (ev != 0 && h > h_min) { /* revert to the last commit, subdivide */
                h *= 0.5;
                continue;
            }
            stop = commit(an, ev, k);
            if (stop < 0) return 1;
            if (stop) return *failed;
            h = target - *t;
        }
    }
    return *failed;
}

/* ------------------------------------------------------------------------------------------ */
/* Reporting and self-checks                                                                    */
/* ------------------------------------------------------------------------------------------ */

static const char *KIND[] = {"opening", "impact", "settled"}; /* event kinds 0, 1, 2 */

/* "+1,0,-1": a configuration as the EVENT and RESULT lines print it. */
static void statuses(char *buf, size_t len, const int8_t *st, int n) {
    size_t used = 0;
    int k;
    buf[0] = '\0';
    for (k = 0; k < n && used < len; k++) {
        int w = snprintf(buf + used, len - used, "%s%+d", k ? "," : "", st[k]);
        if (w < 0) break;
        used += (size_t)w;
    }
}

static int checks_failed = 0;

/* A self-check: prints a CHECK line, counts a failure in checks_failed. */
static void check(const char *name, double value, double expected, double tol) {
    int ok = fabs(value - expected) <= tol;
    printf("CHECK %s value=%.10g expected=%.10g tol=%.3g %s\n", name, value, expected, tol,
           ok ? "ok" : "FAIL");
    if (!ok) checks_failed++;
}

#endif /* ROCKING_COLUMN_H */
