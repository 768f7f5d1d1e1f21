// A C++ client of the installed library (tests/install/run.sh builds it with CMake against a
// fresh prefix): thesis Eq. 11 through rocking.h, with the numbers of src/samples.rs.
#include <cmath>
#include <cstdio>
#include <rocking.h>
#include "rocking_samples.h"

int main() {
    if (rocking_abi_version() != ROCKING_ABI_VERSION || ROCKING_ABI_VERSION != CMAKE_ROCKING_ABI_VERSION) {
        std::fprintf(stderr, "ABI mismatch: library %u, header %d, CMake package %d\n", rocking_abi_version(),
                     ROCKING_ABI_VERSION, CMAKE_ROCKING_ABI_VERSION);
        return 1;
    }
    double width[] = SAMPLE_IMPACT_WIDTH, height[] = SAMPLE_IMPACT_HEIGHT, mass_kg[] = SAMPLE_IMPACT_BLOCK_MASS;
    double mass[16], velocity[] = SAMPLE_IMPACT_VELOCITY;
    int8_t status[] = SAMPLE_IMPACT_STATUS;
    RockingOptions options = {1, ROCKING_SOLVER_AUTO, 1e-12};
    RockingReport report;
    int32_t code = rocking_column_mass_matrix(2, width, height, mass_kg, NULL, NULL, NULL, 0.0, 9.81, mass, NULL);
    if (code == ROCKING_OK)
        code = rocking_impact_model(2, mass, status, velocity, SAMPLE_IMPACT_CLOSING, &options, &report);
    if (code != ROCKING_OK) {
        std::fprintf(stderr, "%s: %s\n", rocking_error_message(code), rocking_last_error_message());
        return 1;
    }
    bool ok = status[0] == -1 && status[1] == -1 && std::fabs(velocity[0] - SAMPLE_IMPACT1_RATE0) < 5e-5 &&
              std::fabs(velocity[1] - SAMPLE_IMPACT1_RATE1) < 5e-5;
    // A bad call: a code, a message, nothing written.
    double before = velocity[0];
    code = rocking_impact_model(2, mass, status, velocity, 7, &options, &report);
    ok = ok && code == ROCKING_ERR_INVALID_CLOSING_INTERFACE && velocity[0] == before &&
         rocking_last_error_message()[0] != '\0';
    std::printf("rocking %s (ABI %u) from C++: Eq. 11 rates %.4f %.4f: %s\n", rocking_version(),
                rocking_abi_version(), velocity[0], velocity[1], ok ? "ok" : "MISMATCH");
    return ok ? 0 : 1;
}
