// Matrices of many megabytes, allocated so that their first touch is cheap.
//
// A fresh 4 KB page costs a fault when it is first written, and on a virtual machine like
// ours a fault is slow: 26 MB (an 1800 x 1800 kernel matrix) took 62 ms to fill the first
// time and 1 ms the second, so loading the torus prior spent 0.3 s of its 0.4 s faulting in
// its two kernel matrices and their copies. The same memory on 2 MB pages filled in 2-12
// ms. So a large matrix asks for transparent huge pages (madvise) before anything writes
// it; where the kernel gives none (THP "never", no memory to compact) it is an ordinary
// matrix. Below 4 MB (two huge pages) the call is not worth making.
#pragma once

#include <Eigen/Core>

namespace jgpm {

// An uninitialised rows x cols matrix, on huge pages where the system allows.
Eigen::MatrixXd LargeMatrix(Eigen::Index rows, Eigen::Index cols);

}  // namespace jgpm
