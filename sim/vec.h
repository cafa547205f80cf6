#pragma once
// Fixed-size vectors for per-particle arithmetic. Particle data are flat arrays of these.
#include <Eigen/Core>
#include <vector>

namespace gs {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

template <int D>
using IVec = Eigen::Matrix<int, D, 1>;

// std::vector of fixed-size Eigen types: with D = 2 or 4 doubles Eigen wants aligned storage.
template <int D>
using VecArray = std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>>;

}  // namespace gs
