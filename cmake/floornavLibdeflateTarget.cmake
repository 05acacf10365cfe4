# libdeflate::libdeflate, the CRC-32 of the MCAP records (io/mcap_writer.cpp: 3-4 times zlib's
# speed, and a bag's CRCs cover megabytes), in floornav's build and in its installed package
# config (the same file is installed beside floornavConfig.cmake). Debian 12's libdeflate-dev has
# no CMake config: an imported target. Sets libdeflate_FOUND.
set(libdeflate_FOUND TRUE)
if(NOT TARGET libdeflate::libdeflate)
  find_path(LIBDEFLATE_INCLUDE_DIR libdeflate.h)
  find_library(LIBDEFLATE_LIBRARY NAMES deflate)
  if(LIBDEFLATE_INCLUDE_DIR AND LIBDEFLATE_LIBRARY)
    add_library(libdeflate::libdeflate INTERFACE IMPORTED)
    set_target_properties(libdeflate::libdeflate PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${LIBDEFLATE_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${LIBDEFLATE_LIBRARY}")
  else()
    set(libdeflate_FOUND FALSE)
  endif()
endif()
