# Every dependency comes from a Debian 12 package (see tools/install_dependencies.sh).
find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(xsimd CONFIG REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
# Compressed glTF geometry: KHR_draco_mesh_compression and EXT_meshopt_compression.
find_package(draco CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)
# doctest is found in tests/, only when the tests are built.

# Debian's xsimd target links a library "xtl" that the package does not ship
# (xsimd itself is header-only): drop it unless an xtl target really exists.
if(NOT TARGET xtl)
  set_target_properties(xsimd PROPERTIES INTERFACE_LINK_LIBRARIES "")
endif()

# OpenImageIO comes from its pkg-config file, not its CMake package: Debian's
# OpenImageIOTargets.cmake also imports the command-line tools (/usr/bin/iconvert…,
# package openimageio-tools) and loads Imath's package, which imports a Python module
# (python3-imath). On a fresh machine without those two packages, find_package(OpenImageIO)
# stops at configure and Imath warns; installing them would pull in Qt and numpy for
# nothing we use. The .pc file names exactly the libraries we link.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OpenImageIO REQUIRED IMPORTED_TARGET GLOBAL OpenImageIO)
add_library(OpenImageIO::OpenImageIO ALIAS PkgConfig::OpenImageIO)
