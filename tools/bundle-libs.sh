#!/usr/bin/env bash
# Copies the shared libraries that the given binaries load, beyond the C and C++ runtimes and the
# Vulkan loader, into DEST: Debian's tinygltf, tinyexr, stb, meshoptimizer and zlib, which a machine
# with a GPU but without Debian's packages lacks (tools/gpu-check.sh puts DEST on LD_LIBRARY_PATH).
# The C and C++ runtimes stay the machine's own: its Vulkan driver may need a newer libstdc++ than
# this build's (which needs GLIBCXX_3.4.29, GCC 11, and glibc 2.34). The build runs it for vkpath
# (target bundle_libs, DEST build/release/lib).
#   tools/bundle-libs.sh DEST BINARY...
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: tools/bundle-libs.sh DEST BINARY..." >&2; exit 2; }
dest=$1
shift
mkdir -p "$dest"
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
