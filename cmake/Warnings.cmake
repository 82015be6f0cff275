# vkpath_warnings: an interface target carrying the project's warning flags.
add_library(vkpath_warnings INTERFACE)
target_compile_options(vkpath_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wno-missing-field-initializers>)
