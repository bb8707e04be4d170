# install.cmake: what `make install` (cmake --install) puts where, and the
# two ways another project finds it -- pkg-config (brdffit.pc) and CMake
# (find_package(brdffit): brdffit::brdffit, brdffit::brdffit_static).
# Both are relocatable: they locate the prefix from their own place in it,
# so `cmake --install build --prefix DIR` works for any DIR, and the tree
# still works after it is moved.
include(CMakePackageConfigHelpers)

set(BF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/brdffit)
set(BF_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(TARGETS brdffit_static brdffit_shared EXPORT brdffitTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
set_target_properties(brdffit_shared PROPERTIES EXPORT_NAME brdffit)
set_target_properties(brdffit_static PROPERTIES EXPORT_NAME brdffit_static)
install(FILES ${CMAKE_SOURCE_DIR}/include/brdffit.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# --- pkg-config ---------------------------------------------------------------
# prefix is found from the .pc file's own folder (${pcfiledir}, which
# pkg-config and pkgconf both define) when libdir and includedir lie under
# the prefix; an absolute CMAKE_INSTALL_LIBDIR or _INCLUDEDIR is written as
# given.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(BF_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(BF_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  file(RELATIVE_PATH bf_up "/p/${BF_PC_DIR}" "/p")
  string(REGEX REPLACE "/$" "" bf_up "${bf_up}")
  set(BF_PC_PREFIX "\${pcfiledir}/${bf_up}")
  set(BF_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(BF_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(BF_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
# The flag that links the OpenMP runtime with this compiler (-fopenmp).
string(REPLACE ";" " " BF_PC_OPENMP "${OpenMP_C_FLAGS}")
configure_file(${CMAKE_SOURCE_DIR}/brdffit.pc.in
               ${CMAKE_BINARY_DIR}/brdffit.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/brdffit.pc DESTINATION ${BF_PC_DIR})

# --- CMake package ------------------------------------------------------------
install(EXPORT brdffitTargets NAMESPACE brdffit::
  FILE brdffitTargets.cmake DESTINATION ${BF_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/brdffitConfig.cmake.in
  ${CMAKE_BINARY_DIR}/brdffitConfig.cmake INSTALL_DESTINATION ${BF_CMAKE_DIR})
# 0.x: a new minor version may change the API (semantic versioning).
write_basic_package_version_file(${CMAKE_BINARY_DIR}/brdffitConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/brdffitConfig.cmake
              ${CMAKE_BINARY_DIR}/brdffitConfigVersion.cmake
        DESTINATION ${BF_CMAKE_DIR})
