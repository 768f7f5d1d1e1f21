// Proves that include/rocking.h compiles as C++ (extern "C", no C-only constructs) and links.
#include <cstdio>
#include "rocking.h"

int main() {
    RockingOptions options = {2, 2, 1e-12};
    RockingReport report;
    double mass[4] = {2.0, 0.5, 0.5, 2.0};
    int8_t status[1] = {1};
    double velocity[2] = {0.0, -1.0};
    int32_t code = rocking_impact_model(1, mass, status, velocity, 0, &options, &report);
    if (code != ROCKING_OK) {
        std::printf("error %d: %s\n", code, rocking_last_error_message());
        return 1;
    }
    std::printf("ok: status %d, rate %.4f\n", status[0], velocity[0]);
    return 0;
}
