# All third-party packages come from Debian 12, each found here with the workaround its package needs (comments below).
# The list of Debian packages that provides them is in scripts/packages.txt; keep both in step.
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(spdlog REQUIRED)
find_package(OpenCV 4 REQUIRED COMPONENTS core imgproc imgcodecs video features2d calib3d)
find_package(fastcdr REQUIRED)
find_package(fastrtps REQUIRED)   # Fast DDS 2.9 (find_package(fastdds) is 3.x and not in Debian 12)
find_program(FASTDDSGEN fastddsgen REQUIRED)
if(TWINSLAM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(TWINSLAM_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
find_package(Ceres REQUIRED)
find_package(embree 3 REQUIRED)   # Embree 3.13 ray casting for the simulator renderer (target embree)
# Digital twin (common/twin): Draco (tile compression, KHR_draco_mesh_compression), PROJ 9 (projected CRSs),
# GeographicLib (ECEF <-> ENU; Debian ships only a Find module), libosmium (OSM XML, header only, needs expat),
# tinygltf (header only, /usr/include/tiny_gltf.h).
find_package(draco REQUIRED)
find_package(PROJ REQUIRED CONFIG)
list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
find_package(GeographicLib REQUIRED)
find_package(EXPAT REQUIRED)
find_package(ZLIB REQUIRED)
find_path(OSMIUM_INCLUDE_DIR osmium/osm.hpp REQUIRED)
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h REQUIRED)
# nanoflann 1.4 (header-only) for the registration library's KD-trees (services/registration/lib/src/kdtree.hpp).
find_package(nanoflann 1.4 REQUIRED)
# OpenMP (GCC's libgomp) for the registration library's parallel nearest-neighbour searches
# (RegistrationConfig::threads).
find_package(OpenMP REQUIRED COMPONENTS CXX)
# PCL 1.13 as the registration library's reference in its tests and benchmark (StatisticalOutlierRemoval,
# IterativeClosestPointWithNormals, the paper code's recipe). PCL's config drags VTK, whose MPI targets fail in a
# C++-only project: disable VTK first. PCL headers cost ~24 s and ~2 GB per translation unit: only
# tests/registration/test_pcl_reference.cpp and bench/registration/pcl_baseline.cpp include them.
set(CMAKE_DISABLE_FIND_PACKAGE_VTK ON)
find_package(PCL 1.13 REQUIRED COMPONENTS common kdtree search registration features filters io)
