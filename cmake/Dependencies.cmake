# Every dependency comes from a Debian 12 package (see tools/install_dependencies.sh).
find_package(glm CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(xsimd CONFIG REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
# doctest is found in tests/, only when the tests are built.

# Debian's xsimd target links a library "xtl" that the package does not ship
# (xsimd itself is header-only): drop it unless an xtl target really exists.
if(NOT TARGET xtl)
  set_target_properties(xsimd PROPERTIES INTERFACE_LINK_LIBRARIES "")
endif()

# Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist
# without OpenCV's headers; CMake refuses non-existent include paths.
foreach(oiio_target OpenImageIO::OpenImageIO OpenImageIO::OpenImageIO_Util)
  if(TARGET ${oiio_target})
    get_target_property(oiio_includes ${oiio_target} INTERFACE_INCLUDE_DIRECTORIES)
    if(oiio_includes)
      list(FILTER oiio_includes EXCLUDE REGEX "opencv4")
      set_target_properties(${oiio_target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${oiio_includes}")
    endif()
  endif()
endforeach()
