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

if(JGPM_PYTHON)
  # The module's build needs Python's headers and pybind11 (python3-dev, pybind11-dev); its
  # tests NumPy (python3-numpy). Without pybind11 the module is left out, with a note.
  # Debian's python3 (its python3-numpy and python3-opencv), unless told otherwise.
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module)
  find_package(pybind11 CONFIG QUIET)
  if(NOT Python3_FOUND OR NOT pybind11_FOUND)
    message(STATUS "jgpm: pybind11 or Python's headers not found: the Python module is not built "
                   "(datasets_scripts/install_deps.sh installs them)")
    set(JGPM_PYTHON OFF)
  else()
    # Where `cmake --install` puts the module, under the install prefix: where Debian's
    # python3 looks for packages under /usr/local (the default prefix).
    set(JGPM_PYTHON_INSTALL_DIR "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages"
        CACHE STRING "Folder under the install prefix for the Python module")
  endif()
endif()
