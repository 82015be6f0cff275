#!/usr/bin/env bash
# Copies the shared libraries that the given binaries load, beyond the C and C++ runtimes and the
# Vulkan loader, into DEST: Debian's tinygltf, tinyexr, stb, meshoptimizer and zlib, which a machine
# with a GPU but without Debian's packages lacks (tools/gpu-check.sh puts DEST on LD_LIBRARY_PATH).
# The C and C++ runtimes stay the machine's own: its Vulkan driver may need a newer libstdc++ than
# this build's (which needs GLIBCXX_3.4.29, GCC 11, and glibc 2.34). The build runs it for vkpath
# (target bundle_libs, DEST build/release/lib).
# With --validation-layer it also copies Khronos' validation layer (Debian's vulkan-validationlayers:
# its library and its manifest, which names the library beside it) into DEST/layers: the GPU tests
# run with that layer and fail without it, and a machine with a GPU driver may not have it
# (tools/gpu-check.sh points VK_LAYER_PATH there). Where the layer is not installed it says so and
# copies the rest: a build for rendering alone does not need it.
#   tools/bundle-libs.sh [--validation-layer] DEST BINARY...
set -euo pipefail
layer=0
[ "${1:-}" = --validation-layer ] && { layer=1; shift; }
[ $# -ge 2 ] || { echo "usage: tools/bundle-libs.sh [--validation-layer] DEST BINARY..." >&2; exit 2; }
dest=$1
shift
mkdir -p "$dest"
copy_validation_layer() {  # into $dest/layers, or says why not
  local manifest="" d name lib=""
  for d in /usr/share/vulkan/explicit_layer.d /etc/vulkan/explicit_layer.d /usr/local/share/vulkan/explicit_layer.d; do
    [ -f "$d/VkLayer_khronos_validation.json" ] && { manifest=$d/VkLayer_khronos_validation.json; break; }
  done
  if [ -z "$manifest" ]; then
    echo "bundle-libs: no validation layer to copy (apt-get install vulkan-validationlayers); the GPU tests need it" >&2
    return 0
  fi
  name=$(sed -n 's/^ *"library_path": *"\([^"]*\)".*/\1/p' "$manifest" | head -1)
  case $name in
    /*) lib=$name ;;
    */*) lib=$(dirname "$manifest")/$name ;;
    *) for d in "/usr/lib/$(uname -m)-linux-gnu" /usr/lib64 /usr/lib /usr/local/lib; do
         [ -f "$d/$name" ] && { lib=$d/$name; break; }
       done ;;
  esac
  [ -n "$lib" ] && [ -f "$lib" ] || { echo "bundle-libs: the validation layer's library $name is not found" >&2; exit 1; }
  mkdir -p "$dest/layers"
  cp -L "$lib" "$dest/layers/libVkLayer_khronos_validation.so.tmp"
  mv "$dest/layers/libVkLayer_khronos_validation.so.tmp" "$dest/layers/libVkLayer_khronos_validation.so"
  # A relative library_path is taken relative to the manifest (the Vulkan loader's layer interface).
  sed 's|^\( *"library_path": *"\)[^"]*"|\1./libVkLayer_khronos_validation.so"|' "$manifest" >"$dest/layers/VkLayer_khronos_validation.json"
}
[ "$layer" = 1 ] && copy_validation_layer
for bin in "$@"; do
  ldd "$bin" | while read -r name arrow path _; do
    [ "$arrow" = "=>" ] || continue
    case $name in
      linux-vdso* | ld-linux* | libc.so* | libm.so* | libdl.so* | libpthread.so* | librt.so* | libgcc_s.so* | \
        libstdc++.so* | libvulkan.so*) continue ;;
    esac
    [ "$path" != "not" ] || { echo "bundle-libs: $bin needs $name, which is not found" >&2; exit 1; }
    cp -L "$path" "$dest/$name.tmp" && mv "$dest/$name.tmp" "$dest/$name"
  done
done
