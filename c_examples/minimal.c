/* The thesis's two-block impact (section 3.2.3, Eq. 10-11; SPEC section 8) through rocking.h alone.
 *
 * Two granite blocks 0.1 x 0.3 m, 15 kg. The lower block is at rest; the upper one rotates
 * about its left corner and closes at 1 rad/s. Expected: both interfaces open about their right
 * corners at -0.1079 and -0.5965 rad/s (25.6 % of the kinetic energy lost); with two consecutive
 * impacts, -0.0539 and -0.7983 rad/s (13.9 % lost).
 *
 * Build: cc -std=c99 -Iinclude c_examples/minimal.c -Ltarget/release -lrocking -o minimal
 * Exit status 0 when every number matches. */
#include <math.h>
#include <stdio.h>
#include "rocking.h"
#include "rocking_samples.h" /* the inputs and the thesis's numbers, from src/samples.rs */

static int check(const char *what, double got, double want, double tol) {
    int ok = fabs(got - want) <= tol;
    printf("%-34s %10.4f  (thesis %8.4f) %s\n", what, got, want, ok ? "ok" : "MISMATCH");
    return ok ? 0 : 1;
}

static int impact(uint32_t n_impacts, double v0, double v1, double loss) {
    double width[2] = SAMPLE_IMPACT_WIDTH, height[2] = SAMPLE_IMPACT_HEIGHT;
    double mass_kg[2] = SAMPLE_IMPACT_BLOCK_MASS, mass[16];
    int8_t status[2] = SAMPLE_IMPACT_STATUS;      /* lower closed, upper open about its left corner */
    double velocity[4] = SAMPLE_IMPACT_VELOCITY;  /* phi_hat_1 closing at 1 rad/s */
    RockingOptions options = {n_impacts, ROCKING_SOLVER_AUTO, 1e-12};
    RockingReport report;
    int failures = 0;
    int32_t code = rocking_column_mass_matrix(2, width, height, mass_kg, NULL, NULL, NULL, 0.0, 9.81, mass, NULL);
    if (code != ROCKING_OK) {
        fprintf(stderr, "mass matrix: %s (%s)\n", rocking_error_message(code), rocking_last_error_message());
        return 1;
    }
    failures += check("M[0][2] (thesis Eq. 10)", mass[2], SAMPLE_EQ10_M02, 5e-4);
    code = rocking_impact_model(2, mass, status, velocity, SAMPLE_IMPACT_CLOSING, &options, &report);
    if (code != ROCKING_OK) {
        fprintf(stderr, "impact: %s (%s)\n", rocking_error_message(code), rocking_last_error_message());
        return 1;
    }
    printf("%u impact(s): status after = {%d, %d}, solver %u, %llu configurations\n", n_impacts, status[0],
           status[1], report.solver, (unsigned long long)report.configurations_examined);
    failures += (status[0] != -1 || status[1] != -1);
    failures += check("rate of interface 0 [rad/s]", velocity[0], v0, 5e-5);
    failures += check("rate of interface 1 [rad/s]", velocity[1], v1, 5e-5);
    failures += check("kinetic energy lost [%]", 100.0 * (1.0 - report.kinetic_after / report.kinetic_before), loss, 0.05);
    return failures;
}

int main(void) {
    int failures = 0;
    int8_t bad_status[2] = {0, 0};
    double dummy_mass[16] = {0}, dummy_v[4] = {0};
    printf("rocking %s, ABI %u (header ABI %d)\n", rocking_version(), rocking_abi_version(), ROCKING_ABI_VERSION);
    if (rocking_abi_version() != ROCKING_ABI_VERSION) {
        fprintf(stderr, "library ABI does not match the header\n");
        return 1;
    }
    failures += impact(1, SAMPLE_IMPACT1_RATE0, SAMPLE_IMPACT1_RATE1, SAMPLE_IMPACT1_LOSS);
    failures += impact(2, SAMPLE_IMPACT2_RATE0, SAMPLE_IMPACT2_RATE1, SAMPLE_IMPACT2_LOSS);
    /* A bad call answers with a code and a message, and writes nothing. */
    if (rocking_impact_model(2, dummy_mass, bad_status, dummy_v, 0, NULL, NULL) != ROCKING_ERR_INVALID_CLOSING_INTERFACE) {
        fprintf(stderr, "expected ROCKING_ERR_INVALID_CLOSING_INTERFACE\n");
        failures++;
    } else {
        printf("bad call refused: %s\n", rocking_last_error_message());
    }
    printf("%s\n", failures ? "FAILED" : "all thesis values reproduced");
    return failures ? 1 : 0;
}
