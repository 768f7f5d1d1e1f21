/* Stiff ELASTIC blocks coupled to the rocking library (issue 6, the thesis's failed coupling).
 *
 * The FE-style analysis of opensees_style_harness.c (three mass points per block on its axis,
 * B rebuilt from the current geometry, rocking_reduce, Newmark average acceleration, commit /
 * revert with step halving onto events, every opening and impact decision through the library),
 * with each block made axially ELASTIC: the block's centre and top mass points (and everything
 * resting on the block) ride on an axial spring above its base mass point. Generalised
 * coordinates:
 *
 *   phi (2n)  interface rotations, the library's DOFs: the rigid-body placement of every block;
 *   e   (n)   axial stretch of block k's spring (along block k's current axis).
 *
 * J = [B | C] maps their rates to the nodal velocities (C: the unit axial vector of block k on
 * its centre and top nodes and on every node above); the FE program's full system is
 * JᵀMJ (rocking_reduce with 3n columns), Jᵀp, plus the spring forces -K e on the e rows.
 * K_k = m_k,above (r p_k)², p_k = sqrt(g / (alpha R_k)) the block's rocking frequency and
 * m_k,above the mass the spring carries, so that the axial frequency is r p_k, r = 100, 1000,
 * 10 000. The springs start unstressed: gravity is applied at t = 0 as an FE transient analysis
 * without a static preload step does (the axial vibration has the amplitude of the static
 * compression). Newmark's average acceleration is implicit in K (no damping), dt = 1e-4 s.
 *
 * Two couplings, differing ONLY in the load the library's decisions are judged on:
 *   naive  (the thesis's coupling): the interface forces the FE program has at hand, the total,
 *          vibrating ones: q = Bᵀp - (BᵀMC) ë, i.e. the rigid-DOF rows of the full equations with
 *          the elastic inertia moved to the right: the library's reactions λ = M̃ a - q are then
 *          the FE model's actual contact reactions, spring ringing included;
 *   recipe (docs/opensees.md section 6): the rigid-body question on the rigid-body system:
 *          M̃ = BᵀMB and q = Bᵀp (gravity and ground inertia; elastic forces and elastic
 *          inertia excluded), with the rigid coordinates phi and their rates phi'. The library's
 *          impact rates are written back to phi' only; e, e' are left to the FE program.
 * Both use the same mass matrix, the same integrator and the same impact handling.
 *
 * Scenes: a single block 0.2 x 0.6 m free rocking from 0.15 rad; b the same block under a
 * half-sine pulse 1.5 g tan(delta), t_p = 0.3 s; c thesis 4.2 (two granite blocks 0.1 x 0.3 m,
 * 16.2 kg, contact width 96 mm, upper block released at -0.153 rad, two impacts per closing).
 * Each runs rigid (no e DOFs, as the harness), then naive and recipe for r = 100, 1000, 10000.
 *
 * Output: EVENT / RESULT lines as the harness (scene name <s>_rigid, <s>_naive_r<r>,
 * <s>_recipe_r<r>), a CHATTER line per run, CHECK lines; exit 0 when every check passes.
 *
 * The rigid column model (mass points, geometry, B, the reduction), the scenes' type, the Newmark
 * and event pieces, the trial / commit / revert step control (transient) and the CHECK lines are
 * the harness's, in rocking_column.h; this file adds the axial DOFs and the two couplings.
 *
 * C99, only rocking.h, rocking_column.h and the C library. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "rocking.h"

#define MAXB 2                    /* blocks */
#define MAXQ (3 * MAXB)           /* generalised DOFs: 2n rotations + n axial */
#include "rocking_column.h"

#define MAXEV 4096                /* events kept per run */

enum { RIGID = 0, NAIVE = 1, RECIPE = 2 };
static const char *MODE[] = {"rigid", "naive", "recipe"};

/* ------------------------------------------------------------------------------------------ */
/* Domain: the Column of rocking_column.h and an axial spring in each block                     */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
    Column col;                   /* blocks, mass points, nodal masses (the harness's model) */
    int ne;                       /* axial DOFs (0 rigid, nb elastic) */
    double K[MAXB];               /* axial spring stiffness of each block */
} Domain;

static void domain_init(Domain *d, int nb, const double *w, const double *h, const double *m,
                        const double *contact_width, double ratio) {
    int k, i;
    memset(d, 0, sizeof *d);
    column_init(&d->col, nb, w, h, m, contact_width);
    d->ne = ratio > 0.0 ? nb : 0;
    /* K_k = (mass carried by the spring) (ratio p_k)² */
    for (k = 0; k < d->ne; k++) {
        double R = 0.5 * sqrt(w[k] * w[k] + h[k] * h[k]), p = sqrt(GRAVITY / (4.0 / 3.0 * R));
        double carried = 0.0;
        for (i = 3 * k + 1; i < d->col.n_nodes; i++) carried += d->col.node_mass[i];
        d->K[k] = carried * (ratio * p) * (ratio * p);
    }
}

static int nq_of(const Domain *d) { return 2 * d->col.nb + d->ne; }

/* J = [B | C] (nodal DOFs x (2n + ne), column-major): B of rocking_column.h (Eq. C2), then C. */
static void jacobian(const Domain *d, const Geometry *g, double *J) {
    int n = d->col.nb, rows = 2 * d->col.n_nodes, i, k;
    column_transformation(&d->col, g, J);
    for (k = 0; k < d->ne; k++) {
        double *c = J + (2 * n + k) * rows;
        for (i = 0; i < d->col.n_nodes; i++) {
            int moved = i > 3 * k; /* centre and top of block k, every node above */
            c[2 * i] = moved ? -sin(g->angle[k]) : 0.0;
            c[2 * i + 1] = moved ? cos(g->angle[k]) : 0.0;
        }
    }
}

/* Full generalised system JᵀMJ, Jᵀp at (phi, e) (the geometry stretched by e when the blocks are
 * elastic); the spring forces are added by the caller. */
static int32_t assemble(const Domain *d, const double *phi, const double *e, double ag, double *Mf,
                        double *qf, Geometry *g) {
    double J[MAXND * MAXQ];
    column_geometry(&d->col, phi, d->ne ? e : NULL, g);
    jacobian(d, g, J);
    return column_reduce(&d->col, J, nq_of(d), ag, Mf, qf);
}

/* ------------------------------------------------------------------------------------------ */
/* Scenes, state, analysis                                                                      */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
    double t;
    double phi[MAXD], rate[MAXD], acc[MAXD];
    double e[MAXB], ed[MAXB], edd[MAXB];
    int8_t status[MAXB];
    double Mf[MAXQ * MAXQ], qf[MAXQ]; /* full system at (t, phi, e), spring forces not in qf */
    Geometry g;
} State;

typedef struct {
    int kind; /* 0 opening, 1 impact, 2 settled */
    double t;
    int interface;
    int8_t after[MAXB];
} Event;

typedef struct {
    const Scene *s;
    int mode;
    double ratio;
    Domain d;
    State c;
    State tr, prev;      /* trial state; the commit before the last */
    RockingOptions opts;
    double h_min, tip_energy, opening_quiet_until;
    double peak[MAXB];
    double last_impact[MAXB];
    int overturned, failed, n_events, n_impacts, n_openings;
    long declined;       /* check said "must open", the opening model kept the configuration */
    long checks_fired;   /* trial steps whose reaction test fired (each costs a revert) */
    long steps;
    Event ev[MAXEV];
} Analysis;

/* Free generalised DOFs: the open rotation of each open interface, then every axial DOF. */
static int free_dofs(const Domain *d, const int8_t *status, int *idx) {
    int n = d->col.nb, k, nf = free_rotations(n, status, idx);
    for (k = 0; k < d->ne; k++) idx[nf++] = 2 * n + k;
    return nf;
}

/* The library's matrix M̃ = BᵀMB: the rotation block of the full matrix. */
static void rigid_matrix(const Domain *d, const double *Mf, double *M) {
    int n2 = 2 * d->col.nb, nq = nq_of(d), i, j;
    for (j = 0; j < n2; j++)
        for (i = 0; i < n2; i++) M[j * n2 + i] = Mf[j * nq + i];
}

/* The load the library's decisions are judged on (see the header comment). */
static void decision_load(const Analysis *A, const double *Mf, const double *qf, const double *edd,
                          double *q) {
    int n2 = 2 * A->d.col.nb, nq = nq_of(&A->d), i, k;
    for (i = 0; i < n2; i++) {
        q[i] = qf[i];
        if (A->mode == NAIVE)
            for (k = 0; k < A->d.ne; k++) q[i] -= Mf[(n2 + k) * nq + i] * edd[k];
    }
}

/* Accelerations at a state: (M_FF + c K) x = q_F - K e_pred on the free DOFs (c = h²/4 inside a
 * Newmark step with the predictor e_pred; c = 0 and e_pred = e at a state). */
static int solve_acc(const Analysis *A, State *st, double c, const double *e_pred) {
    const Domain *d = &A->d;
    int n = d->col.nb, idx[MAXQ], nf = free_dofs(d, st->status, idx), i, nr = nf - d->ne;
    double r[MAXQ], x[MAXQ], diag[MAXQ];
    for (i = 0; i < 2 * n; i++) st->acc[i] = 0.0;
    for (i = 0; i < nf; i++) {
        r[i] = st->qf[idx[i]];
        diag[i] = 0.0;
        if (i >= nr) {
            int k = idx[i] - 2 * n;
            r[i] -= d->K[k] * e_pred[k];
            diag[i] = c * d->K[k];
        }
    }
    if (A->mode == RECIPE && d->ne) {
        /* the rigid part alone: M̃_FF a_F = q_F; then the elastic rows given a_F */
        if (nr && solve_sub(nq_of(d), st->Mf, NULL, idx, nr, r, x)) return 1;
        for (i = nr; i < nf; i++) {
            int j;
            for (j = 0; j < nr; j++) r[i] -= st->Mf[idx[j] * nq_of(d) + idx[i]] * x[j];
        }
        if (solve_sub(nq_of(d), st->Mf, diag + nr, idx + nr, nf - nr, r + nr, x + nr)) return 1;
    } else if (nf && solve_sub(nq_of(d), st->Mf, diag, idx, nf, r, x)) {
        return 1;
    }
    for (i = 0; i < nf; i++) {
        if (i < nr)
            st->acc[idx[i]] = x[i];
        else
            st->edd[idx[i] - 2 * n] = x[i];
    }
    return 0;
}

static int library_ok(Analysis *A, int32_t code, const char *what) {
    if (code == ROCKING_OK) return 1;
    fprintf(stderr, "%s/%s/r%g: %s failed: %s (%s)\n", A->s->name, MODE[A->mode], A->ratio, what,
            rocking_error_message(code), rocking_last_error_message());
    A->failed = 1;
    return 0;
}

/* One Newmark (average acceleration) trial step of length h from the committed state: the
 * rotations as the harness's, the axial DOFs with their predictor e_pred (implicit in K). */
static int newmark_trial(Analysis *A, double h, State *tr) {
    const Domain *d = &A->d;
    int n = d->col.nb, idx[MAXQ], nf, it, k;
    const State *c = &A->c;
    double ag, e_pred[MAXB];
    *tr = *c;
    tr->t = c->t + h;
    ag = ground(A->s, tr->t);
    nf = free_dofs(d, c->status, idx) - d->ne;
    for (k = 0; k < d->ne; k++) e_pred[k] = c->e[k] + h * c->ed[k] + 0.25 * h * h * c->edd[k];
    for (it = 0; it < 100; it++) {
        double change = 0.0, scale = 1.0, old[MAXD], olde[MAXB];
        newmark_displacements(nf, idx, h, c->phi, c->rate, c->acc, tr->acc, tr->phi);
        for (k = 0; k < d->ne; k++) tr->e[k] = e_pred[k] + 0.25 * h * h * tr->edd[k];
        if (!library_ok(A, assemble(d, tr->phi, tr->e, ag, tr->Mf, tr->qf, &tr->g), "rocking_reduce"))
            return 1;
        memcpy(old, tr->acc, sizeof old);
        memcpy(olde, tr->edd, sizeof olde);
        if (solve_acc(A, tr, 0.25 * h * h, e_pred)) {
            fprintf(stderr, "%s: mass matrix not positive definite\n", A->s->name);
            A->failed = 1;
            return 1;
        }
        iteration_change(2 * n, tr->acc, old, &change, &scale);
        iteration_change(d->ne, tr->edd, olde, &change, &scale);
        if (change <= 1e-12 * scale) break;
    }
    for (k = 0; k < d->ne; k++) {
        tr->e[k] = e_pred[k] + 0.25 * h * h * tr->edd[k];
        tr->ed[k] = c->ed[k] + 0.5 * h * (c->edd[k] + tr->edd[k]);
    }
    newmark_rates(nf, idx, h, c->rate, c->acc, tr->acc, tr->rate);
    return 0;
}

/* Events in a trial step (as the harness's; the opening test on the decision load). 0 none,
 * 1 impact (*k_out), 2 opening, 3 overturning. */
static int detect(Analysis *A, const State *tr, int *k_out) {
    int n = A->d.col.nb, k;
    k = impact_crossing(n, A->c.status, A->c.phi, tr->phi, tr->rate);
    if (k >= 0) {
        *k_out = k;
        return 1;
    }
    if (tr->t > A->opening_quiet_until && any_closed(n, tr->status)) {
        uint8_t holds = 1;
        double M[MAXD * MAXD], q[MAXD];
        rigid_matrix(&A->d, tr->Mf, M);
        decision_load(A, tr->Mf, tr->qf, tr->edd, q);
        if (!library_ok(A, rocking_check_configuration((size_t)n, M, q, tr->status, 0.0, &holds,
                                                       NULL, NULL),
                        "rocking_check_configuration"))
            return -1;
        if (!holds) {
            A->checks_fired++;
            return 2;
        }
    }
    k = overturning(&A->d.col, tr->status, &tr->g);
    if (k >= 0) {
        *k_out = k;
        return 3;
    }
    return 0;
}

static void record(Analysis *A, int kind, double t, int k) {
    Event *e;
    if (kind == 1) A->n_impacts++;
    if (kind == 0) A->n_openings++;
    if (A->n_events >= MAXEV) return;
    e = &A->ev[A->n_events++];
    e->kind = kind;
    e->t = t;
    e->interface = k;
    memcpy(e->after, A->c.status, MAXB);
}

static void handle_impact(Analysis *A, const State *prev, int k) {
    int n = A->d.col.nb, n2 = 2 * n;
    int a = open_dof(n, k, A->c.status);
    double frac = prev->phi[a] / (prev->phi[a] - A->c.phi[a]), M[MAXD * MAXD];
    RockingReport rep;
    State *c = &A->c;
    c->t = prev->t + frac * (c->t - prev->t);
    interpolate(n2, frac, prev->phi, c->phi);
    interpolate(n2, frac, prev->rate, c->rate);
    interpolate(A->d.ne, frac, prev->e, c->e);
    interpolate(A->d.ne, frac, prev->ed, c->ed);
    c->phi[a] = 0.0;
    if (!library_ok(A, assemble(&A->d, c->phi, c->e, ground(A->s, c->t), c->Mf, c->qf, &c->g),
                    "rocking_reduce"))
        return;
    rigid_matrix(&A->d, c->Mf, M);
    /* the rigid-body rates go to the library, its rates come back to phi' only; e, e' stay */
    if (!library_ok(A, rocking_impact_model((size_t)n, M, c->status, c->rate, (size_t)k, &A->opts, &rep),
                    "rocking_impact_model"))
        return;
    record(A, 1, c->t, k);
    if (c->status[k] != 0 &&
        settles(rep.kinetic_after, A->tip_energy, c->t, A->last_impact[k], A->s->dt)) {
        c->status[k] = 0;
        project_rates(n, nq_of(&A->d), c->Mf, c->status, c->rate);
        record(A, 2, c->t, k);
    }
    A->last_impact[k] = c->t;
    solve_acc(A, c, 0.0, c->e);
}

/* Opening at the committed state, just past the event (the harness's ladder, see
 * rocking_column.h), on the rigid matrix and the decision load. */
static void handle_opening(Analysis *A) {
    int n = A->d.col.nb, k, l;
    int8_t before[MAXB];
    State *c = &A->c;
    memcpy(before, c->status, MAXB);
    for (l = 0; l < OPENING_RUNGS; l++) {
        double eps = OPENING_LADDER[l] * A->s->dt, phi[MAXD], e[MAXB], Mf[MAXQ * MAXQ], qf[MAXQ];
        double M[MAXD * MAXD], q[MAXD];
        int changed;
        Geometry g;
        extrapolate(2 * n, eps, c->phi, c->rate, c->acc, phi);
        extrapolate(A->d.ne, eps, c->e, c->ed, c->edd, e);
        if (!library_ok(A, assemble(&A->d, phi, e, ground(A->s, c->t + eps), Mf, qf, &g),
                        "rocking_reduce"))
            return;
        rigid_matrix(&A->d, Mf, M);
        decision_load(A, Mf, qf, c->edd, q);
        if (!library_ok(A, opening_model(n, M, q, c->status, &A->opts, &changed),
                        "rocking_opening_model"))
            return;
        if (changed) break;
    }
    if (l == OPENING_RUNGS) {
        A->declined++;
        A->opening_quiet_until = c->t + A->s->dt;
        return;
    }
    k = start_openings(n, before, c->status, c->phi, c->rate);
    solve_acc(A, c, 0.0, c->e);
    record(A, 0, c->t, k);
}

/* transient()'s hooks (rocking_column.h). The trial step: Newmark, then the event in it. */
static int trial_step(void *an, double h, int *k) {
    Analysis *A = an;
    return newmark_trial(A, h, &A->tr) ? -1 : detect(A, &A->tr, k);
}

/* The commit: the trial becomes the committed state, and its event is handled there; a run whose
 * event log is full (runaway chatter) stops there and is reported. */
static int commit_step(void *an, int ev, int k) {
    Analysis *A = an;
    A->prev = A->c;
    A->c = A->tr;
    if (++A->steps > 20000000) {
        fprintf(stderr, "%s: too many steps\n", A->s->name);
        return -1;
    }
    if (ev == 1) handle_impact(A, &A->prev, k);
    if (ev == 2) handle_opening(A);
    track_peaks(A->d.col.nb, &A->c.g, A->peak);
    if (ev == 3) A->overturned = 1;
    return ev == 3 || A->n_events >= MAXEV;
}

static int analyze(Analysis *A, const Scene *s, int mode, double ratio) {
    int n = s->nb, k;
    memset(A, 0, sizeof *A);
    A->s = s;
    A->mode = mode;
    A->ratio = ratio;
    domain_init(&A->d, n, s->width, s->height, s->mass, s->contact[0] > 0.0 ? s->contact : NULL,
                mode == RIGID ? 0.0 : ratio);
    A->opts = scene_options(s);
    A->h_min = s->dt * ldexp(1.0, -30);
    for (k = 0; k < n; k++) A->last_impact[k] = -1.0;
    A->opening_quiet_until = -1.0;
    A->tip_energy = column_tip_energy(&A->d.col);
    initial_configuration(s, A->c.status, A->c.phi);
    if (!library_ok(A, assemble(&A->d, A->c.phi, A->c.e, ground(s, 0.0), A->c.Mf, A->c.qf, &A->c.g),
                    "rocking_reduce"))
        return 1;
    solve_acc(A, &A->c, 0.0, A->c.e);
    track_peaks(n, &A->c.g, A->peak);
    return transient(A, trial_step, commit_step, &A->c.t, &A->failed, s->dt, s->duration, A->h_min);
}

/* ------------------------------------------------------------------------------------------ */
/* Reporting and checks                                                                         */
/* ------------------------------------------------------------------------------------------ */

static void run_name(char *buf, size_t len, const Analysis *A) {
    if (A->mode == RIGID)
        snprintf(buf, len, "%s_rigid", A->s->name);
    else
        snprintf(buf, len, "%s_%s_r%.0f", A->s->name, MODE[A->mode], A->ratio);
}

static void report(const Analysis *A) {
    int n = A->s->nb, i, k;
    char name[64], b1[64];
    run_name(name, sizeof name, A);
    for (i = 0; i < A->n_events; i++) {
        const Event *e = &A->ev[i];
        statuses(b1, sizeof b1, e->after, n);
        printf("EVENT scene=%s kind=%s t=%.9f interface=%d after=%s\n", name, KIND[e->kind], e->t,
               e->interface, b1);
    }
    printf("RESULT scene=%s stop=%s t_end=%.9f impacts=%d openings=%d events=%d peak=", name,
           A->failed ? "failed" : A->n_events >= MAXEV ? "too_many_events"
                                : A->overturned        ? "overturned"
                                                       : "duration",
           A->c.t, A->n_impacts, A->n_openings, A->n_events);
    for (k = 0; k < n; k++) printf("%s%.9f", k ? "," : "", A->peak[k]);
    printf("\n");
}

/* Number of decisions that differ from the rigid run: events beyond the common prefix of the
 * two sequences (kind, interface, configuration) on both sides, plus declined openings. */
static long spurious(const Analysis *A, const Analysis *R) {
    int i = 0;
    while (i < A->n_events && i < R->n_events && A->ev[i].kind == R->ev[i].kind &&
           A->ev[i].interface == R->ev[i].interface &&
           memcmp(A->ev[i].after, R->ev[i].after, MAXB) == 0)
        i++;
    return (long)(A->n_events - i) + (long)(R->n_events - i) + A->declined;
}

static int same_sequence(const Analysis *A, const Analysis *R) {
    int i;
    if (A->n_events != R->n_events || A->overturned != R->overturned) return 0;
    for (i = 0; i < A->n_events; i++)
        if (A->ev[i].kind != R->ev[i].kind || A->ev[i].interface != R->ev[i].interface ||
            memcmp(A->ev[i].after, R->ev[i].after, MAXB) != 0)
            return 0;
    return 1;
}

static double max_time_diff(const Analysis *A, const Analysis *R) {
    int i;
    double m = 0.0;
    for (i = 0; i < A->n_events && i < R->n_events; i++) m = fmax(m, fabs(A->ev[i].t - R->ev[i].t));
    return m;
}

static double max_peak_rel(const Analysis *A, const Analysis *R) {
    int k;
    double m = 0.0;
    for (k = 0; k < A->s->nb; k++) m = fmax(m, fabs(A->peak[k] - R->peak[k]) / fmax(R->peak[k], 1e-12));
    return m;
}

static Analysis rigid_run, runs[2][3];

static int scene(const Scene *s) {
    static const double ratios[3] = {100.0, 1000.0, 10000.0};
    int m, r;
    char name[96];
    if (analyze(&rigid_run, s, RIGID, 0.0)) return 1;
    report(&rigid_run);
    for (m = 0; m < 2; m++) {
        for (r = 0; r < 3; r++) {
            Analysis *A = &runs[m][r];
            analyze(A, s, m == 0 ? NAIVE : RECIPE, ratios[r]);
            report(A);
            run_name(name, sizeof name, A);
            printf("CHATTER scene=%s mode=%s ratio=%.0f events=%d rigid_events=%d declined=%ld "
                   "checks_fired=%ld spurious=%ld same_sequence=%d max_dt=%.3e peak_rel=%.3e "
                   "stop=%s\n",
                   s->name, MODE[A->mode], ratios[r], A->n_events, rigid_run.n_events, A->declined,
                   A->checks_fired, spurious(A, &rigid_run), same_sequence(A, &rigid_run),
                   max_time_diff(A, &rigid_run), max_peak_rel(A, &rigid_run),
                   A->failed ? "failed" : A->n_events >= MAXEV ? "too_many_events"
                                        : A->overturned        ? "overturned"
                                                               : "duration");
        }
    }
    /* the recipe: no chatter, the rigid sequence, peaks converging */
    for (r = 0; r < 3; r++) {
        const Analysis *A = &runs[1][r];
        snprintf(name, sizeof name, "%s_recipe_r%.0f_same_sequence_as_rigid", s->name, ratios[r]);
        check(name, same_sequence(A, &rigid_run) && !A->failed, 1, 0);
        snprintf(name, sizeof name, "%s_recipe_r%.0f_spurious_decisions", s->name, ratios[r]);
        check(name, (double)spurious(A, &rigid_run), 0, 0);
    }
    snprintf(name, sizeof name, "%s_recipe_r10000_peak_rel_vs_rigid", s->name);
    check(name, max_peak_rel(&runs[1][2], &rigid_run), 0, 1e-2);
    return 0;
}

int main(void) {
    int failures = 0;
    double ap = 1.5 * GRAVITY / 3.0;
    /* the harness's scenes a, b, c at dt = 1e-4 s */
    Scene a = {"a", "single block 0.2 x 0.6 m, free rocking from 0.15 rad (Housner, 1 impact)",
               1, {0.2}, {0.6}, {100.0}, {0.0}, {0.15}, 0.0, 1.0, 0, 1, 1e-4, 3.0};
    Scene b = {"b", "single block 0.2 x 0.6 m, half-sine pulse 1.5 g tan(delta), t_p = 0.3 s",
               1, {0.2}, {0.6}, {100.0}, {0.0}, {0.0}, 0.0, 0.3, 1, 1, 1e-4, 3.0};
    Scene c = {"c", "two granite blocks 0.1 x 0.3 m (thesis 4.2), upper released at 0.153 rad",
               2, {0.1, 0.1}, {0.3, 0.3}, {16.2, 16.2}, {0.096, 0.096}, {0.0, -0.153},
               0.0, 1.0, 0, 2, 1e-4, 1.5};
    b.amp = ap;
    printf("rocking %s (ABI %u): stiff elastic blocks\n", rocking_version(), rocking_abi_version());
    if (rocking_abi_version() != ROCKING_ABI_VERSION) {
        fprintf(stderr, "library ABI does not match the header\n");
        return 1;
    }
    failures += scene(&a);
    failures += scene(&b);
    failures += scene(&c);
    failures += checks_failed;
    printf("\n%s\n", failures ? "FAILED" : "stiff blocks: all self-checks passed");
    return failures ? 1 : 0;
}
