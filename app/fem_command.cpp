// Placeholder: the FEM reference issue replaces this with the real `ddafrac fem`.
#include "commands.hpp"

namespace ddafrac::app {
void register_fem_command(CLI::App&) {}
}  // namespace ddafrac::app
