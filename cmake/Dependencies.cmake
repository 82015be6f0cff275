# Every library comes from a Debian package (docs/design.md "Dependencies"); nothing is vendored.
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
find_package(glm REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(tinyexr REQUIRED)
find_package(TinyGLTF REQUIRED)                      # libtinygltf-dev: a shared library (no TINYGLTF_IMPLEMENTATION)
find_package(draco REQUIRED)                         # libdraco-dev: KHR_draco_mesh_compression
find_package(meshoptimizer REQUIRED)                 # libmeshoptimizer-dev: EXT_meshopt_compression
find_package(SPIRV-Tools-opt REQUIRED)               # spirv-tools: specialization on the host (host/vk/spirv_specialize.h)
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET stb)   # libstb-dev: headers under <stb/...> + libstb
find_package(Threads REQUIRED)
if(VKPATH_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
