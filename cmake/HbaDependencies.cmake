# Every dependency comes from a Debian package (see scripts/install_deps.sh).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres REQUIRED)
find_package(TBB REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(fmt REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(nanoflann REQUIRED)
find_package(Threads REQUIRED)

find_package(liblzf REQUIRED)   # PCD binary_compressed
# Recordings' chunks: lz4 and zstd (liblz4-dev, libzstd-dev, through pkg-config)
# and bzip2 (libbz2-dev); ROS 2 sqlite3 bags (libsqlite3-dev). Without
# HBA_WITH_RECORDINGS none is needed and a recording is refused by name.
if(HBA_WITH_RECORDINGS)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET liblz4)
  pkg_check_modules(ZSTD REQUIRED IMPORTED_TARGET libzstd)
  find_package(BZip2 REQUIRED)
  find_package(SQLite3 REQUIRED)
  find_package(ZLIB REQUIRED)  # MCAP's CRC-32 (zlib1g-dev)
endif()

find_package(PNG REQUIRED)      # the pictures' encoding (libpng-dev)
# MPI for the tool only (the library links no transport): AUTO takes it
# when found (libopenmpi-dev), ON requires it, OFF leaves it out.
if(HBA_WITH_MPI STREQUAL "AUTO")
  find_package(MPI COMPONENTS CXX QUIET)
  set(HBA_MPI ${MPI_CXX_FOUND})
elseif(HBA_WITH_MPI)
  find_package(MPI REQUIRED COMPONENTS CXX)
  set(HBA_MPI ON)
else()
  set(HBA_MPI OFF)
endif()
message(STATUS "hba: MPI ${HBA_MPI} (HBA_WITH_MPI=${HBA_WITH_MPI})")

# stb (the pictures' text, stb_easy_font; the tests decode the pictures with
# stb_image, a decoder other than the encoder's): Debian ships the compiled
# implementations as libstb, so no *_IMPLEMENTATION define is needed.
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
find_library(STB_LIBRARY NAMES stb)
if(NOT STB_INCLUDE_DIR OR NOT STB_LIBRARY)
  message(FATAL_ERROR "stb not found: install the Debian package libstb-dev")
endif()
add_library(hba_stb INTERFACE)
target_include_directories(hba_stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(hba_stb INTERFACE ${STB_LIBRARY})

if(HBA_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(HBA_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
