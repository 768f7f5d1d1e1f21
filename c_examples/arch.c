/* A voussoir arch through the constrained entry points (SPEC section 9, issue 15).
 *
 * 1. Without constraints and with one closing flag the constrained models are the column's:
 *    the thesis's two-block impact (one and two consecutive impacts) and an opening give the
 *    same bytes as rocking_impact_model / rocking_opening_model.
 * 2. A semicircular arch, R = 5 m, t = 0.75 m (t/R = 0.15), 20 voussoirs, from
 *    rocking_arch_system: at rest under gravity and a horizontal ground acceleration the opening
 *    model (no reaction test in a loop) starts the arch moving exactly at the collapse multiplier
 *    of limit analysis with hinges at the joints, lambda = 0.148875 (tests/arch_statics.rs,
 *    computed there from mechanisms and thrust lines), with its four hinges: joints 3 and 15 on
 *    the intrados (status -1), 9 and 20 on the extrados (status +1).
 * 3. That mechanism swinging back: the four hinges close together (one impact call with four
 *    flags); the rates after satisfy G v = 0 and the kinetic energy does not rise.
 * 4. A bad call is refused with a code and a message, and nothing is written.
 *
 * Build: cc -std=c99 -Iinclude c_examples/arch.c -Ltarget/release -lrocking -lm -o arch
 * Exit status 0 when every check passes. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "rocking.h"
#include "rocking_samples.h"

#define VOUSSOIRS 20
#define NJ (VOUSSOIRS + 1)
#define ND (2 * NJ)
#define GRAVITY 9.81
/* The limit-analysis collapse multiplier of this arch (tests/arch_statics.rs, onset_table). */
#define LAMBDA_LIMIT_ANALYSIS 0.148875

static double mass[ND * ND], load[ND], g[3 * ND];

static int fail(const char *what, int32_t code) {
    fprintf(stderr, "%s: %s (%s)\n", what, rocking_error_message(code), rocking_last_error_message());
    return 1;
}

/* 1. The column's answers, byte for byte. */
static int column_equivalence(void) {
    double width[2] = SAMPLE_IMPACT_WIDTH, height[2] = SAMPLE_IMPACT_HEIGHT;
    double block_mass[2] = SAMPLE_IMPACT_BLOCK_MASS, m2[16], q2[4];
    int failures = 0;
    uint32_t n_impacts;
    int32_t code = rocking_column_mass_matrix(2, width, height, block_mass, NULL, NULL, NULL, -0.5 * GRAVITY,
                                              GRAVITY, m2, q2);
    if (code != ROCKING_OK) return fail("column mass matrix", code);
    for (n_impacts = 1; n_impacts <= 2; n_impacts++) {
        RockingOptions options = {0, ROCKING_SOLVER_AUTO, 1e-12};
        int8_t s1[2] = SAMPLE_IMPACT_STATUS, s2[2] = SAMPLE_IMPACT_STATUS;
        double v1[4] = SAMPLE_IMPACT_VELOCITY, v2[4] = SAMPLE_IMPACT_VELOCITY;
        uint8_t flags[2] = {0, 0};
        RockingReport r1, r2;
        int32_t c1, c2;
        options.n_impacts = n_impacts;
        flags[SAMPLE_IMPACT_CLOSING] = 1;
        memset(&r1, 0, sizeof r1);
        memset(&r2, 0, sizeof r2);
        c1 = rocking_impact_model(2, m2, s1, v1, SAMPLE_IMPACT_CLOSING, &options, &r1);
        c2 = rocking_impact_model_constrained(2, m2, 0, NULL, s2, v2, flags, &options, &r2);
        if (c1 != ROCKING_OK || c2 != ROCKING_OK) return fail("two-block impact", c1 ? c1 : c2);
        if (memcmp(s1, s2, sizeof s1) || memcmp(v1, v2, sizeof v1) || memcmp(&r1, &r2, sizeof r1)) {
            printf("%u impact(s): constrained != column\n", n_impacts);
            failures++;
        } else {
            printf("%u impact(s), no constraints: the column's answer byte for byte (rates %.4f, %.4f)\n",
                   n_impacts, v2[0], v2[1]);
        }
    }
    {
        int8_t s1[2] = {0, 0}, s2[2] = {0, 0};
        double a1[4], a2[4];
        RockingReport r1, r2;
        int32_t c1, c2;
        memset(&r1, 0, sizeof r1);
        memset(&r2, 0, sizeof r2);
        c1 = rocking_opening_model(2, m2, q2, s1, a1, NULL, &r1);
        c2 = rocking_opening_model_constrained(2, m2, q2, 0, NULL, NULL, s2, a2, NULL, &r2);
        if (c1 != ROCKING_OK || c2 != ROCKING_OK) return fail("two-block opening", c1 ? c1 : c2);
        if (memcmp(s1, s2, sizeof s1) || memcmp(a1, a2, sizeof a1) || memcmp(&r1, &r2, sizeof r1)) {
            printf("opening: constrained != column\n");
            failures++;
        } else {
            printf("opening under 0.5 g, no constraints: the column's answer byte for byte (status {%d, %d})\n",
                   s2[0], s2[1]);
        }
    }
    return failures;
}

static const RockingArch ARCH = {5.0, 0.75, 3.14159265358979323846, VOUSSOIRS, 2000.0, 1.0};

/* The opening model from rest under the horizontal acceleration lambda g (pushing +x, i.e.
 * a_g = -lambda g): returns 1 if the arch moves. */
static int opens(double lambda, int8_t *status, double *acc, int32_t *code) {
    RockingReport report;
    int j;
    *code = rocking_arch_system(&ARCH, NJ, NULL, NULL, -lambda * GRAVITY, GRAVITY, mass, load, g, NULL);
    if (*code != ROCKING_OK) return 0;
    for (j = 0; j < NJ; j++) status[j] = 0;
    *code = rocking_opening_model_constrained(NJ, mass, load, 3, g, NULL, status, acc, NULL, &report);
    return *code == ROCKING_OK && report.changed;
}

int main(void) {
    int failures = 0, j, row;
    int8_t status[NJ], before[NJ];
    double acc[ND], velocity[ND], lo = 0.0, hi = 0.5, k_before = 0.0;
    uint8_t closing[NJ];
    RockingReport report;
    int32_t code;
    const int want_joint[4] = {3, 9, 15, 20}, want_status[4] = {-1, 1, -1, 1};

    if (rocking_abi_version() != ROCKING_ABI_VERSION) {
        fprintf(stderr, "library ABI does not match the header\n");
        return 1;
    }
    failures += column_equivalence();

    /* 2. Onset by bisection on lambda. */
    if (opens(lo, status, acc, &code) || code != ROCKING_OK) return fail("arch at rest under gravity", code);
    if (!opens(hi, status, acc, &code)) return fail("arch under 0.5 g", code);
    while (hi - lo > 1e-9) {
        double mid = 0.5 * (lo + hi);
        if (opens(mid, status, acc, &code)) {
            hi = mid;
        } else {
            if (code != ROCKING_OK) return fail("onset", code);
            lo = mid;
        }
    }
    printf("onset: lambda = %.6f (limit analysis %.6f) %s\n", hi, LAMBDA_LIMIT_ANALYSIS,
           fabs(hi - LAMBDA_LIMIT_ANALYSIS) <= 5e-7 ? "ok" : "MISMATCH");
    failures += fabs(hi - LAMBDA_LIMIT_ANALYSIS) > 5e-7;
    /* Just above the onset: the collapse mechanism. (Well above it the best mechanism may have
     * more hinges: at 1.2 lambda this arch opens five.) */
    opens(LAMBDA_LIMIT_ANALYSIS * (1.0 + 1e-6), status, acc, &code);
    printf("hinges just above the onset:");
    for (j = 0; j < NJ; j++)
        if (status[j]) printf(" joint %d (%s)", j, status[j] < 0 ? "intrados" : "extrados");
    printf("\n");
    for (j = 0; j < 4; j++) failures += status[want_joint[j]] != want_status[j];
    {
        int open = 0;
        for (j = 0; j < NJ; j++) open += status[j] != 0;
        failures += open != 4;
    }

    /* 3. The mechanism swinging back: its accelerations from rest are a velocity of the
     * mechanism (G a = 0); reversed (and scaled), all four hinges move back towards zero
     * together. */
    for (j = 0; j < ND; j++) acc[j] *= 1e6;
    for (j = 0; j < ND; j++) velocity[j] = -acc[j];
    for (j = 0; j < NJ; j++) closing[j] = status[j] != 0;
    memcpy(before, status, sizeof status);
    code = rocking_impact_model_constrained(NJ, mass, 3, g, status, velocity, closing, NULL, &report);
    if (code != ROCKING_OK) return fail("four hinges closing", code);
    k_before = report.kinetic_before;
    printf("four hinges close: kinetic energy %.4g -> %.4g J (%.1f %% lost); after:", k_before,
           report.kinetic_after, 100.0 * (1.0 - report.kinetic_after / k_before));
    for (j = 0; j < NJ; j++)
        if (status[j]) printf(" joint %d (%+d)", j, status[j]);
    printf("\n");
    failures += report.kinetic_after > k_before * (1.0 + 1e-12);
    for (row = 0; row < 3; row++) {
        double gv = 0.0, scale = 0.0;
        for (j = 0; j < ND; j++) {
            gv += g[row * ND + j] * velocity[j];
            scale += fabs(g[row * ND + j] * velocity[j]);
        }
        if (fabs(gv) > 1e-10 * (scale + 1e-300)) {
            printf("closure row %d after the impact: %g\n", row, gv);
            failures++;
        }
    }
    for (j = 0; j < NJ; j++)
        if (before[j] != 0 && status[j] == before[j]) {
            printf("joint %d kept its corner through the impact\n", j);
            failures++;
        }

    /* 4. A flag other than 0 or 1: refused, nothing written. */
    {
        int8_t s[NJ];
        double v[ND];
        memcpy(s, before, sizeof s);
        for (j = 0; j < ND; j++) v[j] = -acc[j];
        memcpy(velocity, v, sizeof v);
        closing[3] = 2;
        code = rocking_impact_model_constrained(NJ, mass, 3, g, s, v, closing, NULL, NULL);
        if (code != ROCKING_ERR_INVALID_CLOSING_INTERFACE || memcmp(s, before, sizeof s) ||
            memcmp(v, velocity, sizeof v)) {
            printf("bad closing flag not refused cleanly (code %d)\n", code);
            failures++;
        } else {
            printf("bad call refused: %s\n", rocking_last_error_message());
        }
    }
    printf("%s\n", failures ? "FAILED" : "arch: all checks passed");
    return failures ? 1 : 0;
}
