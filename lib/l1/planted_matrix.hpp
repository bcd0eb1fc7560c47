// Synthetic test matrices for the sparse residual factorization, after the paper's experiments:
// R = W F + E with random W, F and a sparse E with a controlled fraction of non-zeros, and the
// support comparison (precision / recall) that measures how well a factorization recovers E.
// Used by the tests and by `relume bench-factor`.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace relume {

struct PlantedMatrix {
  Eigen::MatrixXd W, F, E, R;  // R = W F + E
};

// W (rows x rank) and F (rank x cols) standard normal; each entry of E is non-zero with
// probability `density`, with magnitude uniform in [1, 2] and a random sign.
PlantedMatrix make_planted_matrix(int rows, int cols, int rank, double density, std::uint64_t seed);

struct SupportMatch {
  double precision = 1;  // found entries that are planted (1 when nothing was found)
  double recall = 1;     // planted entries that were found (1 when nothing was planted)
};

// Found: |estimate| > threshold; planted: truth != 0.
SupportMatch compare_support(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& truth,
                             double threshold);

}  // namespace relume
