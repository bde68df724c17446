# Warnings for project code only (third-party headers are included as SYSTEM).
add_library(ddafrac_warnings INTERFACE)
target_compile_options(ddafrac_warnings INTERFACE -Wall -Wextra -Wshadow -Wnon-virtual-dtor -Wpedantic)
