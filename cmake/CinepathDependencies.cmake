# Every third-party package cinepath uses, found once. Target names and packaging quirks:
# docs/dependencies.md.
find_package(PkgConfig REQUIRED)

# Find the config packages before CGAL: CGAL prepends Find modules that shadow them.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMesh CONFIG REQUIRED)
find_package(nlohmann_json 3.11 REQUIRED)
# The JSON parser under core/json.cc (nlohmann keeps the DOM, the writer and the located errors).
find_package(simdjson 3 REQUIRED)
find_package(fmt 9 REQUIRED)
find_package(CLI11 2.1 REQUIRED)
find_package(TBB REQUIRED)
find_package(Ceres 2.1 REQUIRED)
find_package(draco 1.5 REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)
find_package(embree 3 REQUIRED)
pkg_check_modules(GEOGRAPHICLIB REQUIRED IMPORTED_TARGET geographiclib)
# COLMAP's database.db (the features the photos-only path matches itself).
find_package(SQLite3 3.40 REQUIRED)
# render's image files and textures, without OpenImageIO's ~260 libraries (preview/CMakeLists.txt).
find_package(PNG REQUIRED)
find_package(JPEG REQUIRED)
find_package(ZLIB REQUIRED)
# render's PNG frames: libdeflate's level 1 deflates a frame in under half zlib's time (preview/image_files.cc).
pkg_check_modules(LIBDEFLATE REQUIRED IMPORTED_TARGET libdeflate)
find_package(OpenEXR 3.1 CONFIG REQUIRED)

find_package(OpenImageIO 2.4 REQUIRED)
# OIIO's exported target lists /usr/include/opencv4, which does not exist without libopencv-dev.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
if(_oiio_includes)
  list(FILTER _oiio_includes EXCLUDE REGEX "opencv4")
  set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_includes}")
endif()

set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL 5.5 REQUIRED)
include(CGAL_Eigen3_support)

if(CINEPATH_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(CINEPATH_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
