# vkpath_draco_island(<name> SOURCES <files...> [LOCALIZE_EXCEPT <symbol prefix>])
#   -> STATIC library <name>: the sources and the members of Debian's libdraco.a they need, joined
#      into one relocatable object (ld -r) at build time.
# Why: libdraco (static and shared alike) carries its own copy of tinygltf and stb_image in one
# member (tiny_gltf_utils.cc.o). Linked the usual way, that member is pulled in whenever the
# link line reaches libdraco.a while a tinygltf or stb symbol is still undefined, and its copies
# then replace Debian's libtinygltf and libstb for the whole program (a crash: the structs
# differ). Joined here, libdraco.a is searched only for the island's own references, the build
# fails if tinygltf or stb code came along, and the final link never sees libdraco.a.
# LOCALIZE_EXCEPT: make every strong global symbol local except those starting with the prefix,
# so a second island (the tests' encoder) can sit next to the renderer's decoder island.
function(vkpath_draco_island name)
  cmake_parse_arguments(ARG "" "LOCALIZE_EXCEPT" "SOURCES" ${ARGN})
  add_library(${name}_objects OBJECT ${ARG_SOURCES})
  target_link_libraries(${name}_objects PRIVATE draco::draco_static vkpath_warnings)
  set_target_properties(${name}_objects PROPERTIES POSITION_INDEPENDENT_CODE ON)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/${name}.island.o")
  add_custom_command(
    OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} "-DLINKER=${CMAKE_LINKER}" "-DNM=${CMAKE_NM}" "-DOBJCOPY=${CMAKE_OBJCOPY}"
            "-DOBJECTS=$<JOIN:$<TARGET_OBJECTS:${name}_objects>,|>" "-DARCHIVE=$<TARGET_FILE:draco::draco_static>"
            "-DKEEP=${ARG_LOCALIZE_EXCEPT}" "-DOUT=${out}" -P "${PROJECT_SOURCE_DIR}/cmake/draco_island.cmake"
    DEPENDS ${name}_objects $<TARGET_OBJECTS:${name}_objects> "$<TARGET_FILE:draco::draco_static>"
            "${PROJECT_SOURCE_DIR}/cmake/draco_island.cmake"
    VERBATIM)
  set_source_files_properties("${out}" PROPERTIES EXTERNAL_OBJECT TRUE GENERATED TRUE)
  add_library(${name} STATIC "${out}")
  set_target_properties(${name} PROPERTIES LINKER_LANGUAGE CXX)
  target_include_directories(${name} INTERFACE $<TARGET_PROPERTY:draco::draco_static,INTERFACE_INCLUDE_DIRECTORIES>)
endfunction()
