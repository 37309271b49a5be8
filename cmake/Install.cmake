# cmake --install build --prefix P:
#   P/bin/tessera                       the command line; finds the rest through relative paths
#   P/lib/tessera/tessera-tools         check, contact-sheet, bench (tessera execs it)
#   P/lib/tessera/tessera-oiio-module.so  texture formats other than PNG and JPEG
#   P/lib/tessera/libtessera_draco.so   Draco's decoder (src/scene/CMakeLists.txt says why a library)
#   P/lib/tessera/libtessera_*.a        the library, one archive per stage
#   P/include/tessera/                  its interface
#   P/lib/cmake/Tessera/                find_package(Tessera) -> tessera::tessera
# Every path between them is relative ($ORIGIN), so the tree may be moved after installing.

# tessera::tessera: the whole library behind include/tessera/ (scene loading, rendering, image output).
add_library(tessera_library INTERFACE)
target_link_libraries(tessera_library INTERFACE tessera_render)
target_compile_features(tessera_library INTERFACE cxx_std_20)  # the headers are C++20
set_target_properties(tessera_library PROPERTIES EXPORT_NAME tessera)
add_library(tessera::tessera ALIAS tessera_library)

set(TESSERA_INSTALL_LIBDIR "${CMAKE_INSTALL_LIBDIR}/tessera")
set(TESSERA_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/Tessera")

set_target_properties(tessera PROPERTIES INSTALL_RPATH "$ORIGIN/${TESSERA_HELPERS_FROM_BIN}")
set_target_properties(tessera_tools PROPERTIES INSTALL_RPATH "$ORIGIN")
install(TARGETS tessera RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS tessera_tools RUNTIME DESTINATION ${TESSERA_INSTALL_LIBDIR})
install(TARGETS tessera_oiio_module LIBRARY DESTINATION ${TESSERA_INSTALL_LIBDIR})

# The libraries tessera::tessera links, in stage order (a library a stage gains must be added here:
# install(EXPORT) refuses a target whose dependency is in no export set).
set(TESSERA_EXPORTED_LIBRARIES tessera_io tessera_simd tessera_texture tessera_environment tessera_scene tessera_draco tessera_geometry
  tessera_raster tessera_shade tessera_image tessera_render)
install(TARGETS tessera_library ${TESSERA_EXPORTED_LIBRARIES} EXPORT TesseraTargets
  ARCHIVE DESTINATION ${TESSERA_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${TESSERA_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/tessera DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT TesseraTargets NAMESPACE tessera:: DESTINATION ${TESSERA_INSTALL_CMAKEDIR})

include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TesseraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/TesseraConfig.cmake INSTALL_DESTINATION ${TESSERA_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)  # 0.x: a new minor version may change the interface
install(FILES ${PROJECT_BINARY_DIR}/TesseraConfig.cmake ${PROJECT_BINARY_DIR}/TesseraConfigVersion.cmake
  DESTINATION ${TESSERA_INSTALL_CMAKEDIR})

# The environment a glTF file on its own is lit by (src/cli/frame_options.cpp looks for it at
# bin/../share/tessera/environments/ before the source tree), with its licence.
install(FILES ${PROJECT_SOURCE_DIR}/scenes/environments/studio_256.exr ${PROJECT_SOURCE_DIR}/scenes/environments/LICENSE.md
  DESTINATION ${CMAKE_INSTALL_DATADIR}/tessera/environments)
