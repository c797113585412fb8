// placeholder: being written
#include "scenario.hpp"
namespace gyro::bench {
void run_c1(const Options&) {}
}
