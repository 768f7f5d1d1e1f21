/* An FE-style transient analysis of rocking columns that delegates every opening and impact
 * decision to the rocking library, organised the way an OpenSees transient analysis is:
 *
 *   - a Domain of nodes with lumped masses: three mass points per rigid block on its axis
 *     (bottom, centre, top; thesis Appendix C), so that mass, centre and moment of inertia are
 *     reproduced; nodal DOFs node by node (x, y), as OpenSees numbers them;
 *   - a transformation B (nodal displacement rates from the interface DOF rates, thesis Eq. C2)
 *     rebuilt from the current geometry at every evaluation, as OpenSees's Transformation
 *     constraint handler would rebuild its T matrix; the reduced system BᵀMB, Bᵀp comes from
 *     rocking_reduce (Appendix C, Eq. C6 and C8);
 *   - Newmark's average acceleration method (γ = 1/2, β = 1/4) on the open DOFs, the nonlinear
 *     geometry handled by fixed-point iteration on the acceleration (the "algorithm");
 *   - trial / commit / revert-to-last-commit with step halving to land on events: a trial step
 *     that contains an event is reverted and halved until it is shorter than H_MIN, then
 *     committed, and the event is handled at that state:
 *       opening: rocking_check_configuration says a closed interface's reaction has the
 *                inadmissible sign -> rocking_opening_model (judged just past the event, where
 *                the violated reaction is already non-zero: SPEC §5 trap (a));
 *       impact:  an open DOF has come back through zero (and only that: SPEC §5 trap (b)) ->
 *                rocking_impact_model.
 *
 * Scenes (hard-coded; run with no arguments; exit status 0 when every self-check passes):
 *   a  single block released from a tilt, free rocking: Housner's velocity ratio at every impact
 *      and the exact (energy-integral) times between impacts and amplitudes;
 *   b  single block under a half-sine pulse: the exact opening time;
 *   c  two-block granite column of thesis 4.2 (0.1 x 0.3 m, contact width 96 mm), the upper block
 *      released at 0.153 rad, two consecutive impacts per closing (the thesis's model);
 *   d  three-block granite column of thesis 4.3 (0.1 x 0.2 m, 2 x 2 mm chamfers -> contact width
 *      96 mm) on a one-period sine pulse of the table displacement (period 0.6 s, 45 mm); the
 *      rigid model overturns it (see scene_d).
 *
 * Output: human-readable lines, plus machine-readable ones for tests/harness_vs_driver.rs:
 *   EVENT scene=<s> kind=<opening|impact|settled> t=<s> interface=<k> before=<st,..>
 *         after=<st,..> ke_before=<J> ke_after=<J>
 *   RESULT scene=<s> stop=<duration|overturned> t_end=<s> impacts=<n> openings=<n>
 *          peak=<rad,..> configs=<st,..;st,..;..>
 *   CHECK <name> value=<x> expected=<y> tol=<z> ok|FAIL
 *
 * What it does not do (the driver does): the friction and tension checks of thesis 3.3 (a column
 * that would slide is not detected here), and the exact velocity terms (this is thesis Eq. 6,
 * M_FF phi''_F = q_F, as BᵀMB / Bᵀp give it).
 *
 * The column model (mass points, geometry, B, the reduction), the scenes' type, the Newmark and
 * event pieces, the trial / commit / revert step control (transient) and the CHECK lines are in
 * rocking_column.h, shared with stiff_blocks.c; this file keeps its state, events and handlers.
 *
 * C99, only rocking.h, rocking_column.h and the C library. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "rocking.h"

#define MAXB 4                    /* blocks */
#include "rocking_column.h"

#define MAXEV 4096                /* events kept per scene */

/* ------------------------------------------------------------------------------------------ */
/* Domain: the Column of rocking_column.h (blocks, nodes, lumped masses)                        */
/* ------------------------------------------------------------------------------------------ */

/* The reduced system of the current geometry (Appendix C): M = BᵀMB (2n x 2n), q = Bᵀp, with B
 * rebuilt from the geometry at phi. Returns the library's code. */
static int32_t assemble(const Column *d, const double *phi, double ag, double *M, double *q,
                        Geometry *g) {
    double B[MAXND * MAXD];
    column_geometry(d, phi, NULL, g);
    column_transformation(d, g, B);
    return column_reduce(d, B, 2 * d->nb, ag, M, q);
}

/* Kinetic energy 1/2 vᵀMv of the rates v in the metric M (nd x nd). */
static double kinetic(int nd, const double *M, const double *v) {
    double e = 0.0;
    int i, j;
    for (i = 0; i < nd; i++)
        for (j = 0; j < nd; j++) e += 0.5 * v[i] * M[j * nd + i] * v[j];
    return e;
}

/* ------------------------------------------------------------------------------------------ */
/* Scenes and the analysis                                                                      */
/* ------------------------------------------------------------------------------------------ */

/* State of the analysis: committed or trial (the same layout, as OpenSees keeps both). */
typedef struct {
    double t;
    double phi[MAXD], rate[MAXD], acc[MAXD];
    int8_t status[MAXB];
    double M[MAXD * MAXD], q[MAXD]; /* reduced system at (t, phi) */
    Geometry g;
} State;

typedef struct {
    int kind;               /* 0 opening, 1 impact, 2 settled */
    double t;
    int interface;
    int8_t before[MAXB], after[MAXB];
    double v_before, v_after; /* impact: rate of the closing DOF before, of its new DOF after */
    double ke_before, ke_after;
} Event;

typedef struct {
    const Scene *s;
    Column d;
    State c;                 /* last committed state */
    State tr, prev;          /* trial state; the commit before the last */
    long steps;              /* committed steps */
    RockingOptions opts;
    double h_min;
    double peak[MAXB];
    int overturned;
    int n_events, n_impacts, n_openings;
    Event ev[MAXEV];
    double last_impact[MAXB];
    double opening_quiet_until; /* see handle_opening */
    double tip_energy;      /* smallest potential energy that tips a part of the straight column */
    int failed;             /* a library call failed */
} Analysis;

/* Accelerations of the configuration at the state: M_FF a_F = q_F, zero elsewhere. */
static int accelerations(int n, State *st) {
    int idx[MAXD], nf = free_rotations(n, st->status, idx), i;
    double r[MAXD], x[MAXD];
    for (i = 0; i < 2 * n; i++) st->acc[i] = 0.0;
    for (i = 0; i < nf; i++) r[i] = st->q[idx[i]];
    if (nf && solve_sub(2 * n, st->M, NULL, idx, nf, r, x)) return 1;
    for (i = 0; i < nf; i++) st->acc[idx[i]] = x[i];
    return 0;
}

static int library_ok(Analysis *A, int32_t code, const char *what) {
    if (code == ROCKING_OK) return 1;
    fprintf(stderr, "scene %s: %s failed: %s (%s)\n", A->s->name, what, rocking_error_message(code),
            rocking_last_error_message());
    A->failed = 1;
    return 0;
}

/* One Newmark (average acceleration) trial step of length h from the committed state, the
 * nonlinear geometry by fixed-point iteration on the acceleration. */
static int newmark_trial(Analysis *A, double h, State *tr) {
    int n = A->d.nb, nd = 2 * n, idx[MAXD], nf, it;
    const State *c = &A->c;
    double ag;
    *tr = *c;
    tr->t = c->t + h;
    ag = ground(A->s, tr->t);
    nf = free_rotations(n, c->status, idx);
    for (it = 0; it < 100; it++) {
        double change = 0.0, scale = 1.0, old[MAXD];
        newmark_displacements(nf, idx, h, c->phi, c->rate, c->acc, tr->acc, tr->phi);
        if (!library_ok(A, assemble(&A->d, tr->phi, ag, tr->M, tr->q, &tr->g), "rocking_reduce"))
            return 1;
        memcpy(old, tr->acc, sizeof old);
        if (accelerations(n, tr)) {
            fprintf(stderr, "scene %s: reduced mass matrix not positive definite\n", A->s->name);
            A->failed = 1;
            return 1;
        }
        iteration_change(nd, tr->acc, old, &change, &scale);
        if (change <= 1e-13 * scale) break;
    }
    newmark_rates(nf, idx, h, c->rate, c->acc, tr->acc, tr->rate);
    return 0;
}

/* Events in a trial step. Returns 0 none, 1 impact (interface in *k), 2 opening, 3 overturning. */
static int detect(Analysis *A, const State *tr, int *k_out) {
    int n = A->d.nb, k;
    /* impact: an open DOF came back through zero, moving towards it (SPEC §5 trap (b)) */
    k = impact_crossing(n, A->c.status, A->c.phi, tr->phi, tr->rate);
    if (k >= 0) {
        *k_out = k;
        return 1;
    }
    /* opening: the eccentricity test as reaction signs on the closed interfaces */
    if (tr->t > A->opening_quiet_until && any_closed(n, tr->status)) {
        uint8_t holds = 1;
        if (!library_ok(A, rocking_check_configuration((size_t)n, tr->M, tr->q, tr->status, 0.0,
                                                       &holds, NULL, NULL),
                        "rocking_check_configuration"))
            return -1;
        if (!holds) return 2;
    }
    /* overturning: the centre of mass of the part above an open interface beyond its pivot */
    k = overturning(&A->d, tr->status, &tr->g);
    if (k >= 0) {
        *k_out = k;
        return 3;
    }
    return 0;
}

static void record(Analysis *A, int kind, double t, int k, const int8_t *before, double ke0,
                   double ke1, double v0, double v1) {
    Event *e;
    if (kind == 1) A->n_impacts++;
    if (kind == 0) A->n_openings++;
    if (A->n_events >= MAXEV) return;
    e = &A->ev[A->n_events++];
    e->kind = kind;
    e->t = t;
    e->interface = k;
    memcpy(e->before, before, MAXB);
    memcpy(e->after, A->c.status, MAXB);
    e->ke_before = ke0;
    e->ke_after = ke1;
    e->v_before = v0;
    e->v_after = v1;
}

/* Impact at interface k inside the committed step from `prev` to A->c (at most H_MIN long):
 * interpolate to the crossing, set the DOF to exactly zero, hand the decision to the library. */
static void handle_impact(Analysis *A, const State *prev, int k) {
    int n = A->d.nb, nd = 2 * n;
    int a = open_dof(n, k, A->c.status);
    double frac = prev->phi[a] / (prev->phi[a] - A->c.phi[a]);
    int8_t before[MAXB];
    RockingReport rep;
    double v_before, v_after = 0.0;
    State *c = &A->c;
    memcpy(before, c->status, MAXB);
    c->t = prev->t + frac * (c->t - prev->t);
    interpolate(nd, frac, prev->phi, c->phi);
    interpolate(nd, frac, prev->rate, c->rate);
    c->phi[a] = 0.0;
    v_before = c->rate[a];
    if (!library_ok(A, assemble(&A->d, c->phi, ground(A->s, c->t), c->M, c->q, &c->g), "rocking_reduce"))
        return;
    if (!library_ok(A, rocking_impact_model((size_t)n, c->M, c->status, c->rate, (size_t)k, &A->opts, &rep),
                    "rocking_impact_model"))
        return;
    if (c->status[k] != 0) v_after = c->rate[open_dof(n, k, c->status)];
    record(A, 1, c->t, k, before, rep.kinetic_before, rep.kinetic_after, v_before, v_after);
    /* settling (see settles): the interface closed for good, the rates projected onto the rest */
    if (c->status[k] != 0 &&
        settles(rep.kinetic_after, A->tip_energy, c->t, A->last_impact[k], A->s->dt)) {
        int8_t b2[MAXB];
        double ke0 = kinetic(nd, c->M, c->rate);
        memcpy(b2, c->status, MAXB);
        c->status[k] = 0;
        project_rates(n, nd, c->M, c->status, c->rate);
        record(A, 2, c->t, k, b2, ke0, kinetic(nd, c->M, c->rate), 0.0, 0.0);
    }
    A->last_impact[k] = c->t;
    accelerations(n, c);
}

/* Opening at the committed state, just past the event: the opening model asked on BᵀMB, Bᵀp of
 * the state extrapolated along OPENING_LADDER (SPEC §5 trap (a), see rocking_column.h) until it
 * opens something. */
static void handle_opening(Analysis *A) {
    int n = A->d.nb, k, l;
    int8_t before[MAXB];
    State *c = &A->c;
    memcpy(before, c->status, MAXB);
    for (l = 0; l < OPENING_RUNGS; l++) {
        double eps = OPENING_LADDER[l] * A->s->dt, phi[MAXD], M[MAXD * MAXD], q[MAXD];
        int changed;
        Geometry g;
        extrapolate(2 * n, eps, c->phi, c->rate, c->acc, phi);
        if (!library_ok(A, assemble(&A->d, phi, ground(A->s, c->t + eps), M, q, &g), "rocking_reduce"))
            return;
        if (!library_ok(A, opening_model(n, M, q, c->status, &A->opts, &changed),
                        "rocking_opening_model"))
            return;
        if (changed) break;
    }
    if (l == OPENING_RUNGS) {
        /* nothing opens within a step: go on, and do not ask again before the grid */
        A->opening_quiet_until = c->t + A->s->dt;
        return;
    }
    k = start_openings(n, before, c->status, c->phi, c->rate);
    accelerations(n, c);
    record(A, 0, c->t, k, before, 0.0, 0.0, 0.0, 0.0);
}

/* transient()'s hooks (rocking_column.h). The trial step: Newmark, then the event in it. */
static int trial_step(void *an, double h, int *k) {
    Analysis *A = an;
    return newmark_trial(A, h, &A->tr) ? -1 : detect(A, &A->tr, k);
}

/* The commit: the trial becomes the committed state, and its event is handled there. */
static int commit_step(void *an, int ev, int k) {
    Analysis *A = an;
    A->prev = A->c;
    A->c = A->tr;
    if (++A->steps > 50000000) {
        fprintf(stderr, "scene %s: too many steps\n", A->s->name);
        return -1;
    }
    if (ev == 1) handle_impact(A, &A->prev, k);
    if (ev == 2) handle_opening(A);
    track_peaks(A->d.nb, &A->c.g, A->peak);
    if (ev == 3) A->overturned = 1;
    return ev == 3;
}

/* The transient analysis of a scene: analyze(duration / dt) with event-driven step subdivision
 * (transient() in rocking_column.h). */
static int analyze(Analysis *A, const Scene *s) {
    int n = s->nb, k;
    memset(A, 0, sizeof *A);
    A->s = s;
    column_init(&A->d, n, s->width, s->height, s->mass, s->contact[0] > 0.0 ? s->contact : NULL);
    A->opts = scene_options(s);
    A->h_min = s->dt * ldexp(1.0, -30);
    for (k = 0; k < n; k++) A->last_impact[k] = -1.0;
    A->opening_quiet_until = -1.0;
    A->tip_energy = column_tip_energy(&A->d);
    /* initial state: at rest, tilted as the scene says */
    initial_configuration(s, A->c.status, A->c.phi);
    if (!library_ok(A, assemble(&A->d, A->c.phi, ground(s, 0.0), A->c.M, A->c.q, &A->c.g), "rocking_reduce"))
        return 1;
    accelerations(n, &A->c);
    track_peaks(n, &A->c.g, A->peak);
    return transient(A, trial_step, commit_step, &A->c.t, &A->failed, s->dt, s->duration, A->h_min);
}

/* ------------------------------------------------------------------------------------------ */
/* Exact single-block rocking (energy integral) for the self-checks                            */
/* ------------------------------------------------------------------------------------------ */

/* Time for a block (slenderness alpha, p^2 = m g R / I_O) released at rest at tilt theta0 to
 * reach theta = 0: T = ∫ dθ / sqrt(2 p² (cos(α − θ0) − cos(α − θ))), with θ = θ0 (1 − s²) to
 * remove the endpoint singularity and the difference of cosines written as a product of sines
 * (no cancellation). Composite Simpson on a smooth integrand, 2000 panels. */
static double fall_time(double alpha, double p2, double theta0) {
    int N = 2000, i;
    double sum = 0.0;
    for (i = 0; i <= N; i++) {
        double s = (double)i / N, f;
        if (i == 0) {
            f = 2.0 * theta0 / sqrt(2.0 * p2 * sin(alpha - theta0) * theta0);
        } else {
            double th = theta0 * (1.0 - s * s);
            double g = 2.0 * sin(alpha - 0.5 * (th + theta0)) * sin(0.5 * theta0 * s * s);
            f = 2.0 * theta0 * s / sqrt(2.0 * p2 * g);
        }
        sum += f * ((i == 0 || i == N) ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum / (3.0 * N);
}

/* Amplitude reached by a block leaving theta = 0 at rate omega. */
static double amplitude(double alpha, double p2, double omega) {
    return alpha - acos(cos(alpha) + omega * omega / (2.0 * p2));
}

/* ------------------------------------------------------------------------------------------ */
/* Reporting                                                                                    */
/* ------------------------------------------------------------------------------------------ */

static void report(const Analysis *A) {
    const Scene *s = A->s;
    int n = s->nb, i, k;
    char b0[64], b1[64];
    char configs[8192];
    size_t used = 0;
    printf("\n== scene %s: %s\n", s->name, s->title);
    for (i = 0; i < A->n_events; i++) {
        const Event *e = &A->ev[i];
        statuses(b0, sizeof b0, e->before, n);
        statuses(b1, sizeof b1, e->after, n);
        if (i < 40 || i >= A->n_events - 3)
            printf("  %-8s t = %9.6f s  interface %d  {%s} -> {%s}\n", KIND[e->kind], e->t,
                   e->interface, b0, b1);
        else if (i == 40)
            printf("  ...\n");
        printf("EVENT scene=%s kind=%s t=%.9f interface=%d before=%s after=%s ke_before=%.9g "
               "ke_after=%.9g\n",
               s->name, KIND[e->kind], e->t, e->interface, b0, b1, e->ke_before, e->ke_after);
    }
    /* configuration sequence: the initial one, then the one after every event */
    configs[0] = '\0';
    {
        int8_t init[MAXB] = {0};
        for (k = 0; k < n; k++)
            init[k] = initial_status(s->initial[k]);
        statuses(b0, sizeof b0, init, n);
        used += (size_t)snprintf(configs + used, sizeof configs - used, "%s", b0);
    }
    for (i = 0; i < A->n_events && used + 64 < sizeof configs; i++) {
        statuses(b1, sizeof b1, A->ev[i].after, n);
        used += (size_t)snprintf(configs + used, sizeof configs - used, ";%s", b1);
    }
    printf("  %d impacts, %d openings, %s at t = %.6f s; peak block rotations [rad]:", A->n_impacts,
           A->n_openings, A->overturned ? "OVERTURNED" : "end", A->c.t);
    for (k = 0; k < n; k++) printf(" %.6f", A->peak[k]);
    printf("\nRESULT scene=%s stop=%s t_end=%.9f impacts=%d openings=%d peak=", s->name,
           A->overturned ? "overturned" : "duration", A->c.t, A->n_impacts, A->n_openings);
    for (k = 0; k < n; k++) printf("%s%.9f", k ? "," : "", A->peak[k]);
    printf(" configs=%s\n", configs);
}

/* ------------------------------------------------------------------------------------------ */
/* Scenes                                                                                       */
/* ------------------------------------------------------------------------------------------ */

/* BᵀMB and Bᵀp through the three mass points equal the library's closed form (SPEC §1). */
static void check_reduction(void) {
    double w[2] = {0.1, 0.1}, h[2] = {0.3, 0.3}, m[2] = {16.2, 16.2}, cw[2] = {0.096, 0.096};
    double phi[4] = {-0.02, 0.0, 0.0, 0.15}, Mr[16], qr[4], Mc[16], qc[4], err = 0.0, scale = 0.0;
    Column d;
    Geometry g;
    int i;
    column_init(&d, 2, w, h, m, cw);
    if (assemble(&d, phi, 1.3, Mr, qr, &g) != ROCKING_OK ||
        rocking_column_mass_matrix(2, w, h, m, NULL, cw, phi, 1.3, GRAVITY, Mc, qc) != ROCKING_OK) {
        fprintf(stderr, "reduction check: %s\n", rocking_last_error_message());
        checks_failed++;
        return;
    }
    for (i = 0; i < 16; i++) {
        err = fmax(err, fabs(Mr[i] - Mc[i]));
        scale = fmax(scale, fabs(Mc[i]));
    }
    for (i = 0; i < 4; i++) err = fmax(err, fabs(qr[i] - qc[i]) * scale / (fabs(qc[0]) + 1.0));
    check("reduction_BtMB_equals_closed_form_rel", err / scale, 0.0, 1e-12);
}

static int scene_a(void) {
    static Analysis A;
    /* 0.2 x 0.6 m block (h/b = 3), released at rest tilted 0.15 rad about its left corner */
    Scene s = {"a", "single block 0.2 x 0.6 m, free rocking from 0.15 rad (Housner, 1 impact)",
               1, {0.2}, {0.6}, {100.0}, {0.0}, {0.15}, 0.0, 1.0, 0, 1, 1e-3, 3.0};
    double b = 0.1, hh = 0.3, R = sqrt(b * b + hh * hh), alpha = atan(b / hh);
    double p2 = GRAVITY * R / (4.0 / 3.0 * R * R); /* m g R / I_O, I_O = 4/3 m R² */
    double mu = (2 * hh * hh - b * b) / (2 * hh * hh + 2 * b * b);
    /* Newmark's error over one fall is about (p dt)² t / 12 (period elongation of the average
     * acceleration rule; the rocking equation is an inverted pendulum of rate p); the time
     * tolerance is ten times that, summed over the impacts checked. */
    double p = sqrt(p2), t_exact = 0.0, tol_t, theta = 0.15;
    int i, checked = 0;
    if (analyze(&A, &s)) return 1;
    report(&A);
    printf("  Housner: mu = (2h²-b²)/(2h²+2b²) = %.6f, p = %.4f 1/s, alpha = %.4f rad\n", mu, p, alpha);
    for (i = 0; i < A.n_events && checked < 8; i++) {
        const Event *e = &A.ev[i];
        char name[64];
        if (e->kind != 1) break;
        t_exact += (checked == 0 ? 1.0 : 2.0) * fall_time(alpha, p2, theta);
        tol_t = 10.0 * p2 * s.dt * s.dt * t_exact / 12.0;
        snprintf(name, sizeof name, "a_impact%d_velocity_ratio", checked + 1);
        check(name, e->v_after / e->v_before, mu, 1e-9);
        snprintf(name, sizeof name, "a_impact%d_time", checked + 1);
        check(name, e->t, t_exact, tol_t);
        if (checked == 0) printf("  quarter period (exact, energy integral): %.9f s\n", t_exact);
        theta = amplitude(alpha, p2, fabs(e->v_after)); /* next amplitude, from the exact energy */
        checked++;
    }
    check("a_peak_rotation", A.peak[0], 0.15, 1e-12);
    check("a_impacts_checked", checked, 8, 0);
    return 0;
}

static int scene_b(void) {
    static Analysis A;
    /* the same block on a half-sine pulse of 1.5 g tan(delta), half period 0.3 s: it rocks
     * (it overturns with t_p = 0.5 s) */
    double ap = 1.5 * GRAVITY / 3.0;
    Scene s = {"b", "single block 0.2 x 0.6 m, half-sine pulse 1.5 g tan(delta), t_p = 0.3 s",
               1, {0.2}, {0.6}, {100.0}, {0.0}, {0.0}, 0.0, 0.3, 1, 1, 1e-3, 3.0};
    double t_open;
    s.amp = ap;
    if (analyze(&A, &s)) return 1;
    report(&A);
    /* the block lifts when a_g = g b/h: exact time t_p/pi asin(1/1.5) */
    t_open = s.half_period / PI * asin(GRAVITY / 3.0 / ap);
    if (A.n_events > 0 && A.ev[0].kind == 0) {
        check("b_opening_time", A.ev[0].t, t_open, 2.0 * A.h_min + 1e-12);
        /* ground pushes right: the inertial force tips the block over its left corner (+1) */
        check("b_opening_status", A.ev[0].after[0], 1, 0);
    } else {
        check("b_first_event_is_opening", 0, 1, 0);
    }
    return 0;
}

static int scene_c(void) {
    static Analysis A;
    /* thesis 4.2: granite (2700 kg/m³) 0.1 x 0.3 x 0.2 m -> 16.2 kg, contact width 96 mm,
     * two consecutive impacts per closing (the thesis's model for this test). The upper block is
     * released at 0.153 rad about its RIGHT corner (phĭ_1 = -0.153, tilted clockwise): that is
     * the orientation in which the thesis's description reads literally (the lower block then
     * opens clockwise, the upper one rotates counter-clockwise after its impact). */
    Scene s = {"c", "two granite blocks 0.1 x 0.3 m (thesis 4.2), upper released at 0.153 rad",
               2, {0.1, 0.1}, {0.3, 0.3}, {16.2, 16.2}, {0.096, 0.096}, {0.0, -0.153},
               0.0, 1.0, 0, 2, 1e-3, 1.5};
    /* The thesis prints its simulation's times to the millisecond (Fig. 29b, Wilson theta, step
     * and event location not given): the first three events are asserted in kind, configuration
     * and time within 5 ms (what we get is within 3 ms, see docs/opensees.md). */
    static const struct { int kind, interface; int8_t after[2]; double t; } thesis[3] = {
        {0, 0, {-1, -1}, 0.13},  /* lower interface opens, lower block clockwise */
        {1, 1, {-1, +1}, 0.187}, /* upper block impacts, then rotates counter-clockwise */
        {1, 0, {+1, +1}, 0.193}, /* lower block impacts the base, then counter-clockwise */
    };
    int i;
    if (analyze(&A, &s)) return 1;
    report(&A);
    printf("  thesis 4.2 (Fig. 29b): lower interface opens (lower block clockwise) at 0.13 s, upper\n"
           "  block impacts at 0.187 s, lower block impacts the base at 0.193 s\n");
    for (i = 0; i < 3; i++) {
        char name[64];
        const Event *e = &A.ev[i];
        int same = i < A.n_events && e->kind == thesis[i].kind && e->interface == thesis[i].interface &&
                   e->after[0] == thesis[i].after[0] && e->after[1] == thesis[i].after[1];
        snprintf(name, sizeof name, "c_event%d_as_thesis", i + 1);
        check(name, same, 1, 0);
        snprintf(name, sizeof name, "c_event%d_time_vs_thesis", i + 1);
        check(name, i < A.n_events ? e->t : -1.0, thesis[i].t, 5e-3);
    }
    return 0;
}

static int scene_d(void) {
    static Analysis A;
    /* thesis 4.3: three granite blocks 0.1 x 0.2 x 0.3 m -> 16.2 kg, 2 x 2 mm chamfers -> contact
     * width 96 mm; table displacement d = D sin(2 pi t / T), D = 45 mm, T = 0.6 s, one period:
     * a_g = -D (2 pi / T)² sin(2 pi t / T), two half sines of 4.935 m/s² starting towards -x.
     * Fig. 31 (the measured table motion) is not in the text; this is the literal reading of
     * "close to a sine pulse with period 0.6 s and amplitude 45 mm". Under it the rigid model
     * overturns the column as one body within 0.27 s (it does so down to 0.4 of the amplitude;
     * below 0.32 it does not rock at all), whereas the shaking-table column survived: the scene
     * stays as the hardest one for the event logic (an opening, then static tipping). */
    double D = 0.045, T = 0.6, w2 = (2 * PI / T) * (2 * PI / T);
    Scene s = {"d", "three granite blocks 0.1 x 0.2 m (thesis 4.3), sine pulse T = 0.6 s, 45 mm",
               3, {0.1, 0.1, 0.1}, {0.2, 0.2, 0.2}, {16.2, 16.2, 16.2}, {0.096, 0.096, 0.096},
               {0.0, 0.0, 0.0}, 0.0, 0.3, 2, 2, 1e-3, 2.0};
    s.amp = -D * w2;
    if (analyze(&A, &s)) return 1;
    report(&A);
    return 0;
}

int main(void) {
    int failures = 0;
    printf("rocking %s (ABI %u): OpenSees-style harness\n", rocking_version(), rocking_abi_version());
    if (rocking_abi_version() != ROCKING_ABI_VERSION) {
        fprintf(stderr, "library ABI does not match the header\n");
        return 1;
    }
    check_reduction();
    failures += scene_a();
    failures += scene_b();
    failures += scene_c();
    failures += scene_d();
    failures += checks_failed;
    printf("\n%s\n", failures ? "FAILED" : "harness: all self-checks passed");
    return failures ? 1 : 0;
}
