/* element_skeleton.c -- the rocking library inside an FE time stepper, in one page. Read it first.
 *
 * Your FE code keeps its state, its integrator and its trial / commit / revert cycle; the library
 * decides, at an event, which joints open and which way (rocking_opening_model) and the velocities
 * after a joint slams shut (rocking_impact_model). Each step below:
 *   1. a trial step from the committed state (your integrator; here Newmark, average acceleration);
 *   2. events in the trial: an IMPACT is an open DOF back through zero; an OPENING is a closed
 *      interface whose contact reaction has the wrong sign (rocking_check_configuration);
 *   3. on an event: revert and halve the step until it lands on the event (within HMIN), call the
 *      model, write its answer (statuses, v = B v+) into the host, commit; otherwise commit.
 * M~ = BtMB and p~ = Btp on the 2n interface DOFs come from rocking_column_mass_matrix here; an
 * element with its own nodal mass matrix M and transformation B calls rocking_reduce(M, B, p)
 * (docs/opensees.md 1). Settling, ground motion and sliding are left out (docs/opensees.md 2).
 *
 * The model: thesis 4.2 (SAMPLE_* of rocking_samples.h, generated from src/samples.rs), two granite
 * blocks, the upper one released at 0.153 rad. One EVENT line per event; tests/c_abi.rs checks them
 * against the thesis and the Rust driver. Build against an installed library (make install):
 *   cc -std=c99 element_skeleton.c $(pkg-config --cflags --libs rocking) -lm */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "rocking.h"
#include "rocking_samples.h"

#define NB SAMPLE_FREE_N_BLOCKS /* blocks = interfaces */
#define ND (2 * NB)             /* interface DOFs: [phi_check_0 .. , phi_hat_0 ..] */
#define DT 1e-4                 /* the host's time step [s] */
#define HMIN 1e-10              /* events are located to this [s] */
#define T_END 0.25
#define GRAVITY 9.81

static const double W[NB] = SAMPLE_FREE_WIDTH, H[NB] = SAMPLE_FREE_HEIGHT;
static const double MASS[NB] = SAMPLE_FREE_BLOCK_MASS, CONTACT[NB] = SAMPLE_FREE_CONTACT_WIDTH;

/* The host's state of the element: committed and trial copies of it. */
typedef struct {
    double t, phi[ND], rate[ND];
    int8_t status[NB]; /* -1 open about the right corner, 0 closed, +1 open about the left */
} State;

static int ok(int32_t code, const char *what) { /* every call: code, static text, detail */
    if (code != ROCKING_OK)
        fprintf(stderr, "%s failed: %s (%s)\n", what, rocking_error_message(code), rocking_last_error_message());
    return code == ROCKING_OK;
}

static int dof(const State *s, int k) { return s->status[k] < 0 ? k : NB + k; } /* open DOF */

/* M~ and p~ in the current geometry (no ground motion here: a_g = 0). A trial that overshoots a
 * closure (a DOF past zero: rejected below) is evaluated in the geometry of the closure. */
static int interface_system(const State *s, double M[ND * ND], double q[ND]) {
    double phi[ND];
    int i;
    for (i = 0; i < ND; i++) phi[i] = i < NB ? fmin(s->phi[i], 0.0) : fmax(s->phi[i], 0.0);
    return ok(rocking_column_mass_matrix(NB, W, H, MASS, NULL, CONTACT, phi, 0.0, GRAVITY, M, q),
              "rocking_column_mass_matrix");
}

/* Accelerations of the open DOFs: M_FF a_F = q_F (M_FF is positive definite; zero elsewhere). */
static int accelerations(const State *s, double a[ND]) {
    double M[ND * ND], q[ND], A[NB][NB + 1];
    int f[NB], n = 0, i, j, k;
    if (!interface_system(s, M, q)) return 0;
    memset(a, 0, ND * sizeof a[0]);
    for (k = 0; k < NB; k++) if (s->status[k] != 0) f[n++] = dof(s, k);
    for (i = 0; i < n; i++) {
        for (j = 0; j < n; j++) A[i][j] = M[f[i] * ND + f[j]];
        A[i][n] = q[f[i]];
    }
    for (k = 0; k < n; k++) /* Gauss elimination, then back substitution */
        for (i = k + 1; i < n; i++)
            for (j = n; j >= k; j--) A[i][j] -= A[i][k] / A[k][k] * A[k][j];
    for (i = n - 1; i >= 0; i--) {
        double x = A[i][n];
        for (j = i + 1; j < n; j++) x -= A[i][j] * a[f[j]];
        a[f[i]] = x / A[i][i];
    }
    return 1;
}

/* The host's integrator: one Newmark step (average acceleration), fixed-point iterations. */
static int trial_step(const State *c, double h, State *tr) {
    double a0[ND], a1[ND];
    int i, it;
    *tr = *c;
    tr->t = c->t + h;
    if (!accelerations(c, a0)) return 0;
    memcpy(a1, a0, sizeof a1);
    for (it = 0; it < 3; it++) {
        for (i = 0; i < ND; i++) tr->phi[i] = c->phi[i] + h * c->rate[i] + h * h / 4 * (a0[i] + a1[i]);
        if (!accelerations(tr, a1)) return 0;
    }
    for (i = 0; i < ND; i++) tr->rate[i] = c->rate[i] + h / 2 * (a0[i] + a1[i]);
    return 1;
}

/* Write back v = B v+: velocity and rotation rate of each block's centre, from the interface
 * rates and the pivots and centres in the current geometry (what the host sets on its nodes). */
static void write_back(const State *s) {
    double top[2] = {0.0, 0.0}, angle = 0.0, pivot[ND][2], c[NB][2];
    int j, k;
    for (k = 0; k < NB; k++) {
        double b = CONTACT[k] / 2, ca = cos(angle), sa = sin(angle), turn = s->phi[k] + s->phi[NB + k];
        double *p = pivot[s->status[k] < 0 ? k : NB + k], base[2];
        pivot[k][0] = top[0] + b * ca, pivot[k][1] = top[1] + b * sa;           /* right corner */
        pivot[NB + k][0] = top[0] - b * ca, pivot[NB + k][1] = top[1] - b * sa; /* left corner */
        base[0] = p[0] + cos(turn) * (top[0] - p[0]) - sin(turn) * (top[1] - p[1]);
        base[1] = p[1] + sin(turn) * (top[0] - p[0]) + cos(turn) * (top[1] - p[1]);
        angle += turn;
        c[k][0] = base[0] - sin(angle) * H[k] / 2, c[k][1] = base[1] + cos(angle) * H[k] / 2;
        top[0] = base[0] - sin(angle) * H[k], top[1] = base[1] + cos(angle) * H[k];
    }
    for (j = 0; j < NB; j++) {
        double v[2] = {0.0, 0.0}, omega = 0.0;
        for (k = 0; k <= j; k++) {
            int a = dof(s, k);
            double w = s->status[k] != 0 ? s->rate[a] : 0.0;
            v[0] -= w * (c[j][1] - pivot[a][1]), v[1] += w * (c[j][0] - pivot[a][0]), omega += w;
        }
        printf("  block %d: v = (%+.4f, %+.4f) m/s, omega = %+.4f rad/s\n", j, v[0], v[1], omega);
    }
}

/* Events in a trial: an open DOF through zero (impact; returns its interface), or a closed
 * interface that must open (opening; *opening = 1). */
static int find_event(const State *tr, int *impact, int *opening) {
    double M[ND * ND], q[ND];
    uint8_t holds = 1;
    int k;
    *impact = -1;
    for (k = 0; k < NB; k++)
        if ((tr->status[k] < 0 && tr->phi[k] > 0) || (tr->status[k] > 0 && tr->phi[NB + k] < 0)) *impact = k;
    if (!interface_system(tr, M, q)) return 0;
    if (!ok(rocking_check_configuration(NB, M, q, tr->status, 0.0, &holds, NULL, NULL), "check_configuration"))
        return 0;
    *opening = !holds;
    return 1;
}

static int on_impact(State *s, int k, const RockingOptions *o) {
    double M[ND * ND], q[ND];
    s->phi[dof(s, k)] = 0.0; /* land exactly on the closure */
    return interface_system(s, M, q) &&
           ok(rocking_impact_model(NB, M, s->status, s->rate, (size_t)k, o, NULL), "rocking_impact_model");
}

/* At the event the violated reaction is zero: judge the opening a little past it (SPEC 5a). */
static int on_opening(State *s, const RockingOptions *o) {
    static const double ladder[] = {0.0, 1e-3, 1e-2, 1e-1, 1.0};
    RockingReport rep;
    unsigned e;
    int i;
    for (e = 0; e < sizeof ladder / sizeof ladder[0]; e++) {
        State ahead = *s;
        double M[ND * ND], q[ND], acc[ND];
        for (i = 0; i < ND; i++) ahead.phi[i] += ladder[e] * DT * s->rate[i];
        if (!interface_system(&ahead, M, q) ||
            !ok(rocking_opening_model(NB, M, q, s->status, acc, o, &rep), "rocking_opening_model"))
            return 0;
        if (rep.changed) return 1; /* new DOFs start at zero angle and rate */
    }
    fprintf(stderr, "no opening found past the event at t = %.9f\n", s->t);
    return 0;
}

int main(void) {
    RockingOptions options = {SAMPLE_FREE_N_IMPACTS, ROCKING_SOLVER_AUTO, 1e-12};
    State committed, trial;
    double h = DT;
    int k, impact, opening, events = 0;
    long trials = 0, reverts = 0;
    printf("rocking %s (ABI %u): element skeleton, thesis 4.2\n", rocking_version(), rocking_abi_version());
    if (rocking_abi_version() != ROCKING_ABI_VERSION) { /* a library of another ABI: stop */
        fprintf(stderr, "librocking has ABI %u, this program was built for ABI %d\n", rocking_abi_version(),
                ROCKING_ABI_VERSION);
        return 1;
    }
    memset(&committed, 0, sizeof committed);
    for (k = 0; k < NB; k++) { /* initial tilt: > 0 about the left corner, < 0 about the right */
        static const double tilt[NB] = SAMPLE_FREE_INITIAL_ANGLES;
        committed.status[k] = (int8_t)(tilt[k] > 0 ? 1 : tilt[k] < 0 ? -1 : 0);
        if (tilt[k] != 0) committed.phi[dof(&committed, k)] = tilt[k];
    }
    while (committed.t < T_END) {
        trials++;
        if (!trial_step(&committed, h, &trial) || !find_event(&trial, &impact, &opening)) return 1;
        if ((impact >= 0 || opening) && h > HMIN) { /* revert: bracket the event */
            h /= 2, reverts++;
            continue;
        }
        if (impact >= 0 || opening) {
            int8_t before[NB];
            memcpy(before, trial.status, sizeof before);
            if (impact >= 0 ? !on_impact(&trial, impact, &options) : !on_opening(&trial, &options)) return 1;
            for (k = 0; k < NB && impact < 0; k++) if (trial.status[k] != before[k]) break;
            printf("EVENT kind=%s t=%.9f interface=%d status=%+d,%+d\n", impact >= 0 ? "impact" : "opening",
                   trial.t, impact >= 0 ? impact : k, trial.status[0], trial.status[1]);
            write_back(&trial);
            events++, h = DT;
        }
        committed = trial; /* commit */
    }
    printf("done: %d events by t = %.2f s, %ld trial steps, %ld reverted\n", events, T_END, trials, reverts);
    return 0;
}
