// An empty shared library built as libvulkan.so.1 (tests/unit/CMakeLists.txt): a "Vulkan loader"
// without a single symbol, as a stub or a broken install on LD_LIBRARY_PATH would be. vkpath must
// refuse it with "no usable Vulkan loader" and exit code 2 (test_cli_errors), not crash.
