# ompl::ompl for a found OMPL, which the rrt_connect module links. Debian's OMPL config sets
# variables only; an imported target keeps them in one place.
if(NOT TARGET ompl::ompl)
  add_library(ompl::ompl INTERFACE IMPORTED)
  # libompl.so alone: a shared library brings its own dependencies. (The config also lists
  # Boost's and ODE's .so files, which are in -dev packages libompl-dev does not install.)
  list(GET OMPL_LIBRARIES 0 _floornav_ompl_library)
  set_target_properties(ompl::ompl PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${OMPL_INCLUDE_DIR}"
                                              INTERFACE_LINK_LIBRARIES "${_floornav_ompl_library}")
  unset(_floornav_ompl_library)
endif()
