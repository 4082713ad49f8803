# Every third-party dependency is found here and nowhere else. All are Debian 12 packages;
# datasets_scripts/install_deps.sh installs them.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs videoio video calib3d)
find_package(nanoflann REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.2 REQUIRED)
find_package(Threads REQUIRED)

if(JGPM_WITH_V4L2)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(LIBV4L2 REQUIRED IMPORTED_TARGET libv4l2)
endif()

if(JGPM_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(JGPM_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
