# The package: floornav::core, floornav::ompl (a build with OMPL), floornav::io,
# floornav::render, floornav::runner and the umbrella floornav::floornav, the same names in the
# build tree (ALIAS targets) and after `cmake --install` (find_package(floornav CONFIG REQUIRED)).
# Included by the top-level CMakeLists.txt after the targets are defined.
#
# Each library is a component of the package with its own export file, so that
# find_package(floornav COMPONENTS core) looks only for the core's dependencies (Eigen, fmt), not
# for yaml-cpp, libpng or OMPL (floornavConfig.cmake.in).
#
# The project's own flags (-Wall -Wextra -ffp-contract=off, -Werror) are directory options, so
# they stay out of the exported interface: a user's program compiles with the user's flags. The
# libraries themselves are always built with -ffp-contract=off (determinism).

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FLOORNAV_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/floornav)
set(FLOORNAV_INSTALL_SCENARIODIR ${CMAKE_INSTALL_DATADIR}/floornav/scenarios)
set(FLOORNAV_INSTALL_MODULEDIR ${CMAKE_INSTALL_LIBDIR}/floornav)

# The libraries in dependency order (each after those it links): the order the config loads them.
set(FLOORNAV_COMPONENTS core)
if(TARGET floornav_ompl)
  list(APPEND FLOORNAV_COMPONENTS ompl)
endif()
list(APPEND FLOORNAV_COMPONENTS io render runner)

foreach(lib IN LISTS FLOORNAV_COMPONENTS)
  # Public headers come only from include/ (src/ stays private, see STYLE.md point 1).
  target_include_directories(floornav_${lib} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(floornav_${lib} PUBLIC cxx_std_20)
  set_target_properties(floornav_${lib} PROPERTIES EXPORT_NAME ${lib})
  add_library(floornav::${lib} ALIAS floornav_${lib})
  install(TARGETS floornav_${lib} EXPORT floornav-${lib}-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT floornav-${lib}-targets NAMESPACE floornav::
    DESTINATION ${FLOORNAV_INSTALL_CMAKEDIR})
endforeach()

# The umbrella: every library (floornav/floornav.hpp), one name to link; with floornav::ompl in a
# build with OMPL, so that its programs have the rrt_connect planner.
# (Named outright: $<TARGET_NAME_IF_EXISTS:floornav_ompl> would be exported as it is, and a
# program built against the install, where the target is floornav::ompl, would not link it.)
add_library(floornav_floornav INTERFACE)
target_link_libraries(floornav_floornav INTERFACE
  floornav_core floornav_io floornav_render floornav_runner)
if(TARGET floornav_ompl)
  target_link_libraries(floornav_floornav INTERFACE floornav_ompl)
endif()
set_target_properties(floornav_floornav PROPERTIES EXPORT_NAME floornav)
add_library(floornav::floornav ALIAS floornav_floornav)
install(TARGETS floornav_floornav EXPORT floornav-floornav-targets)
install(EXPORT floornav-floornav-targets NAMESPACE floornav::
  DESTINATION ${FLOORNAV_INSTALL_CMAKEDIR})

# Headers: floornav/ompl* only with the library that defines what they declare.
set(_floornav_no_ompl_headers)
if(NOT TARGET floornav_ompl)
  set(_floornav_no_ompl_headers PATTERN ompl EXCLUDE PATTERN ompl.hpp EXCLUDE)
endif()
install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} ${_floornav_no_ompl_headers})

# FLOORNAV_COMPONENTS (the installed libraries) is written into the config.
configure_package_config_file(cmake/floornavConfig.cmake.in
  ${PROJECT_BINARY_DIR}/floornavConfig.cmake
  INSTALL_DESTINATION ${FLOORNAV_INSTALL_CMAKEDIR}
  PATH_VARS FLOORNAV_INSTALL_SCENARIODIR FLOORNAV_INSTALL_MODULEDIR)
# 0.x: the minor version may still break the API; SameMajorVersion is the promise from 1.0 on.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/floornavConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/floornavConfig.cmake
  ${PROJECT_BINARY_DIR}/floornavConfigVersion.cmake cmake/floornavLibdeflateTarget.cmake
  DESTINATION ${FLOORNAV_INSTALL_CMAKEDIR})

# The rrt_connect module (loaded on the first search; see CMakeLists.txt) in its own directory,
# which the config puts on the run path of programs linking floornav::ompl, and the installed
# tool finds relative to itself: the install may be moved (cmake --install --prefix).
if(TARGET floornav_rrt_connect)
  install(TARGETS floornav_rrt_connect LIBRARY DESTINATION ${FLOORNAV_INSTALL_MODULEDIR})
endif()

# The command-line tool, so that an installed floornav runs scenarios too.
if(TARGET floornav)
  install(TARGETS floornav RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(TARGET floornav_rrt_connect)
    file(RELATIVE_PATH _floornav_tool_to_module ${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_BINDIR}
      ${CMAKE_INSTALL_PREFIX}/${FLOORNAV_INSTALL_MODULEDIR})
    set_target_properties(floornav PROPERTIES INSTALL_RPATH "$ORIGIN/${_floornav_tool_to_module}")
  endif()
endif()

# The chapter scenarios, self-contained (no map files): the examples, the README's program and
# `floornav run` use them. Scenarios that point at the repository's data/maps (ros/, the BARN and
# MovingAI templates) would not load from an install prefix, so they are not installed.
install(FILES
  scenarios/circle_obstacle.yaml scenarios/concave_obstacle.yaml scenarios/convex_obstacle.yaml
  scenarios/coppeliasim_pioneer.yaml scenarios/factory_delivery.yaml scenarios/fleet_aisles.yaml
  scenarios/fleet_crossing.yaml scenarios/point_obstacle.yaml scenarios/practice2_pillars.yaml
  scenarios/rectangle.yaml scenarios/week7_pocket.yaml
  DESTINATION ${FLOORNAV_INSTALL_SCENARIODIR})
