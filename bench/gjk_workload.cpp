// placeholder: being written
#include "scenario.hpp"
namespace gyro::bench {
void run_gjk(const Options&) {}
}
