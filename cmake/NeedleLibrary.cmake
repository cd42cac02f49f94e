# needle_library(NAME SOURCES ... [PUBLIC deps...] [PRIVATE deps...])
# One folder's library, declared the one way every floor is: the target needle_NAME, its alias
# needle::NAME (and export name NAME), the repository's root as its include directory (installed
# headers under include/needle/), and its dependencies — PUBLIC when they appear in its headers,
# PRIVATE when wrapped.
function(needle_library name)
  cmake_parse_arguments(L "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(needle_${name} ${L_SOURCES})
  add_library(needle::${name} ALIAS needle_${name})
  set_target_properties(needle_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(needle_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/needle>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(needle_${name} PUBLIC ${L_PUBLIC} PRIVATE ${L_PRIVATE})
endfunction()
