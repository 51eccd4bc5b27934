# All dependencies come from Debian packages (see README).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# OpenImageIO's exported target names /usr/include/opencv4, which is absent without
# libopencv-dev and makes generation fail: drop that entry.
find_package(OpenImageIO CONFIG REQUIRED)
get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
list(FILTER _oiio_inc EXCLUDE REGEX "opencv")
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_inc}")

# OpenColorIO's CMake package is installed where find_package does not look: use pkg-config.
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)
find_package(OpenSSL REQUIRED)            # SHA-256 of outputs
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(Vulkan REQUIRED COMPONENTS glslc)
if(MATFORGE_TESTS)
  find_package(GTest REQUIRED)
endif()
if(MATFORGE_BENCHMARKS)
  find_package(benchmark QUIET)
endif()
