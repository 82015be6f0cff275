# vkpath_embed_shaders(TARGET <name> SOURCES <a.comp> ...)  -> INTERFACE library <name>
# Compiles each GLSL compute shader to SPIR-V with glslangValidator at build time and embeds it:
# <name>.comp becomes the header <name>.spv.h (array k<Name>Spv, uint32_t words) in the target's
# include path. --depfile records every #include, so editing a header rebuilds the shader.
function(vkpath_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/spv")
  file(MAKE_DIRECTORY "${out_dir}")
  set(headers)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(abs "${src}" ABSOLUTE)
    get_filename_component(name "${src}" NAME_WE)
    # snake_case file name -> CamelCase symbol: pathtrace -> kPathtraceSpv, bvh_test -> kBvhTestSpv
    string(REPLACE "_" ";" parts "${name}")
    set(sym "k")
    foreach(p IN LISTS parts)
      string(SUBSTRING "${p}" 0 1 first)
      string(TOUPPER "${first}" first)
      string(SUBSTRING "${p}" 1 -1 rest)
      string(APPEND sym "${first}${rest}")
    endforeach()
    string(APPEND sym "Spv")
    set(hdr "${out_dir}/${name}.spv.h")
    add_custom_command(
      OUTPUT "${hdr}"
      COMMAND Vulkan::glslangValidator -V --target-env vulkan1.2 -g0
              -I${CMAKE_SOURCE_DIR}/shaders
              --depfile "${hdr}.d" --vn ${sym} -o "${hdr}" "${abs}"
      DEPENDS "${abs}"
      DEPFILE "${hdr}.d"
      COMMENT "glslang ${name}.comp -> ${name}.spv.h"
      VERBATIM)
    list(APPEND headers "${hdr}")
  endforeach()
  add_custom_target(${ARG_TARGET}_spirv DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_spirv)
  target_include_directories(${ARG_TARGET} INTERFACE "${out_dir}")
endfunction()

# vkpath_embed_shader_variant(TARGET <name> SOURCE <a.comp> NAME <variant_name> DEFINES <X=1> ...)
# One more SPIR-V from the same GLSL file, compiled with -D<define> for each DEFINES entry and
# embedded as <variant_name>.spv.h (array k<VariantName>Spv) in an INTERFACE library <name>. For
# bench and test kernels that compare variants of one source (e.g. tests/bench/bench_bvh_layout).
function(vkpath_embed_shader_variant)
  cmake_parse_arguments(ARG "" "TARGET;SOURCE;NAME" "DEFINES" ${ARGN})
  set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/spv_variants")
  file(MAKE_DIRECTORY "${out_dir}")
  get_filename_component(abs "${ARG_SOURCE}" ABSOLUTE)
  string(REPLACE "_" ";" parts "${ARG_NAME}")
  set(sym "k")
  foreach(p IN LISTS parts)
    string(SUBSTRING "${p}" 0 1 first)
    string(TOUPPER "${first}" first)
    string(SUBSTRING "${p}" 1 -1 rest)
    string(APPEND sym "${first}${rest}")
  endforeach()
  string(APPEND sym "Spv")
  set(defs)
  foreach(d IN LISTS ARG_DEFINES)
    list(APPEND defs "-D${d}")
  endforeach()
  set(hdr "${out_dir}/${ARG_NAME}.spv.h")
  add_custom_command(
    OUTPUT "${hdr}"
    COMMAND Vulkan::glslangValidator -V --target-env vulkan1.2 -g0
            -I${CMAKE_SOURCE_DIR}/shaders ${defs}
            --depfile "${hdr}.d" --vn ${sym} -o "${hdr}" "${abs}"
    DEPENDS "${abs}"
    DEPFILE "${hdr}.d"
    COMMENT "glslang ${ARG_NAME} (${ARG_DEFINES}) -> ${ARG_NAME}.spv.h"
    VERBATIM)
  if(NOT TARGET ${ARG_TARGET})
    add_custom_target(${ARG_TARGET}_spirv)
    add_library(${ARG_TARGET} INTERFACE)
    add_dependencies(${ARG_TARGET} ${ARG_TARGET}_spirv)
    target_include_directories(${ARG_TARGET} INTERFACE "${out_dir}")
  endif()
  add_custom_target(${ARG_TARGET}_${ARG_NAME} DEPENDS "${hdr}")
  add_dependencies(${ARG_TARGET}_spirv ${ARG_TARGET}_${ARG_NAME})
endfunction()
