// Placeholder: the DDA engine issue replaces this with the real `ddafrac run`.
#include "commands.hpp"

namespace ddafrac::app {
void register_run_command(CLI::App&) {}
}  // namespace ddafrac::app
