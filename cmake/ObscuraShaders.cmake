# Embeds shaders/ into the library at build time.
#
# The embed tool resolves #include (with #line directives so that compile errors point at the
# original file and line), and writes one C++ source with every stage as a byte array plus a
# manifest for the glslangValidator test. Any change to a file under shaders/ re-runs it.
add_executable(obscura_embed_shaders
  "${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cpp"
  "${PROJECT_SOURCE_DIR}/src/core/shader_source.cpp")
target_include_directories(obscura_embed_shaders PRIVATE "${PROJECT_SOURCE_DIR}/src")
obscura_set_warnings(obscura_embed_shaders)

# obscura_embed_shaders(<out_cpp> <shader_root> <resolved_dir>)
function(obscura_embed_shaders out_cpp root resolved_dir)
  file(GLOB_RECURSE _all CONFIGURE_DEPENDS RELATIVE "${root}" "${root}/*.glsl" "${root}/*.h")
  list(SORT _all)
  set(_deps)
  foreach(f IN LISTS _all)
    list(APPEND _deps "${root}/${f}")
  endforeach()
  add_custom_command(
    OUTPUT "${out_cpp}" "${resolved_dir}/manifest.txt"
    COMMAND obscura_embed_shaders --root "${root}" --out "${out_cpp}" --resolved "${resolved_dir}" ${_all}
    DEPENDS obscura_embed_shaders ${_deps}
    COMMENT "Embedding shaders"
    VERBATIM)
endfunction()
