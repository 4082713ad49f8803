# Every third-party dependency is found here and nowhere else. All are Debian 12 packages;
# datasets_scripts/install_deps.sh installs them.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres REQUIRED)
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs videoio video calib3d highgui)
find_package(nanoflann REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3.2 REQUIRED)
find_package(Threads REQUIRED)
find_package(ZLIB REQUIRED)  # CRCs of mask PNGs (tracker/clip/mask_png.h)

find_package(PkgConfig REQUIRED)
# Dense Cholesky factorisation and inversion of the N x N kernel matrices (N = 1800 for
# ML-JGPM) go to LAPACK: OpenBLAS's dpotrf + dpotri take 85 ms on 2 cores where Eigen's
# LLT + triangular solves take 520 ms (measured side by side, prior/numerics/cholesky.h).
pkg_check_modules(LAPACKE REQUIRED IMPORTED_TARGET lapacke)
pkg_check_modules(OPENBLAS REQUIRED IMPORTED_TARGET openblas)
# Live cameras (io/video/v4l2_api.h): the V4L2 calls through libv4l2.
pkg_check_modules(LIBV4L2 REQUIRED IMPORTED_TARGET libv4l2)


if(JGPM_BUILD_TESTS OR JGPM_BENCHMARKS)  # the benchmarks share the tests' support code
  find_package(GTest REQUIRED)
endif()
if(JGPM_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
