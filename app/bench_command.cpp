// Placeholder: the DDA engine issue replaces this with the real `ddafrac bench`.
#include "commands.hpp"

namespace ddafrac::app {
void register_bench_command(CLI::App&) {}
}  // namespace ddafrac::app
