# rtlacam_library(NAME): a layer's library is usable from the build tree and from an
# install under one name, rtlacam::NAME. Headers live in NAME/include/NAME/ and install
# to <prefix>/include/NAME/; the archive is librtlacam_NAME.a (plain "planner" would clash).
include(GNUInstallDirs)

function(rtlacam_library name)
  cmake_parse_arguments(ARG "NO_HEADERS" "" "" ${ARGN})
  add_library(rtlacam::${name} ALIAS ${name})
  set_target_properties(${name} PROPERTIES
    EXPORT_NAME ${name}
    OUTPUT_NAME rtlacam_${name}
    # The Python module (and any shared library of a user) links these static archives
    # into a shared object.
    POSITION_INDEPENDENT_CODE ${RTLACAM_PIC})
  # PIC alone would stop GCC inlining calls to our own non-static functions (they could be
  # interposed in a shared object); nobody interposes them, so keep the -O3 planner fast.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" OR CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    target_compile_options(${name} PRIVATE -fno-semantic-interposition)
  endif()
  target_include_directories(${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  install(TARGETS ${name} EXPORT rtlacam-targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  if(NOT ARG_NO_HEADERS)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endfunction()
