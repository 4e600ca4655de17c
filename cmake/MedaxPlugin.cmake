# medax_add_plugin(NAME SOURCES... [LIBRARIES ...] [OUTPUT_DIRECTORY dir] [NO_INSTALL])
# Builds one plugin package as a shared library libmedax_<NAME>.so that the kernel loads with
# Boost.DLL. In the medax tree it lands in <build>/lib/medax/plugins and installs beside the
# kernel; out of tree it lands in the build folder (put it on MEDAX_PLUGIN_PATH).
function(medax_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES;LIBRARIES" ${ARGN})
  set(target medax_${name})
  add_library(${target} MODULE ${ARG_SOURCES} ${ARG_UNPARSED_ARGUMENTS})
  if(TARGET medax::medax)
    target_link_libraries(${target} PRIVATE medax::medax ${ARG_LIBRARIES})
  else()
    target_link_libraries(${target} PRIVATE medax ${ARG_LIBRARIES})
  endif()
  set_target_properties(${target} PROPERTIES PREFIX "lib" CXX_VISIBILITY_PRESET hidden
                                             VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIRECTORY})
  elseif(DEFINED MEDAX_PLUGIN_SUBDIR)
    set_target_properties(${target} PROPERTIES
                          LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${MEDAX_PLUGIN_SUBDIR})
  endif()
  if(TARGET medax_plugins)
    add_dependencies(medax_plugins ${target})
  endif()
  if(DEFINED MEDAX_PLUGIN_SUBDIR AND NOT ARG_NO_INSTALL)
    # Installed plugins sit in <libdir>/medax/plugins and find the kernel libraries two
    # folders up (the build tree links them by absolute run path).
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN/../..")
    install(TARGETS ${target} LIBRARY DESTINATION ${MEDAX_PLUGIN_SUBDIR})
  endif()
endfunction()
