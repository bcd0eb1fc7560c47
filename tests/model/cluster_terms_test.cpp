// Tests of the terms-per-cluster choice: a cluster whose functions span fewer directions than
// `terms` keeps only those, the error the choice reports is the Eq. 16 error the field then has
// (the additions of dropped orthonormal rows are exact), the budget holds, a zero budget changes
// nothing, alignment keeps unused rows unused, and the container stores no weight for them.
#include "model/cluster_terms.hpp"

#include <relume/container.hpp>

#include "container/weight_prediction.hpp"
#include "model/basis_alignment.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::noisy_original;
using testing::TempDir;

// A random field of 4 clusters x 4 terms whose cluster k's weights span only `ranks[k]`
// directions (the other weight columns are mixes of those), so W F^k has that rank while every
// basis row is used.
CompressedField field_of_ranks(const std::vector<int>& ranks, std::uint64_t seed = 3) {
  RandomFieldShape shape;
  shape.width = 16;
  shape.height = 12;
  shape.lights = 32;
  shape.clusters = int(ranks.size());
  shape.terms = 4;
  shape.residual_per_function = 3;
  shape.seed = seed;
  CompressedField field = random_compressed_field(shape);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const int rank = ranks[field.cluster[r]];
    for (int j = rank; j < field.terms; ++j)
      field.weights(Eigen::Index(r), j) = 0.5f * field.weights(Eigen::Index(r), j % rank) -
                                          0.25f * field.weights(Eigen::Index(r), (j + 1) % rank);
  }
  return field;
}

double largest_difference(const ReflectanceField& a, const ReflectanceField& b) {
  return (a.values - b.values).cwiseAbs().maxCoeff();
}

TEST(ClusterTerms, ClustersKeepOnlyTheDirectionsTheirFunctionsSpan) {
  const std::vector<int> ranks{1, 2, 4, 3};
  CompressedField field = field_of_ranks(ranks);
  ASSERT_EQ(terms_per_cluster(field), std::vector<int>(4, 4));
  // Noise far below the weights: 1% of its error pays for the dependent directions only.
  const ReflectanceField exact = reconstruct_field(field);
  const ReflectanceField original = noisy_original(field, 1e-3);
  const TermChoice choice = drop_unneeded_terms(original, field, 0.01, 2);
  EXPECT_EQ(choice.cluster_terms, ranks);
  EXPECT_EQ(terms_per_cluster(field), ranks);
  EXPECT_EQ(choice.dropped, 6u);
  EXPECT_LT(largest_difference(reconstruct_field(field), exact), 1e-5);
  EXPECT_LE(choice.error_chosen, choice.error_all_terms * 1.01);
  // The unused rows and their weights are exactly zero.
  const std::vector<std::uint8_t> used = used_basis_rows(field);
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    for (int j = 0; j < field.terms; ++j)
      if (!used[std::size_t(field.cluster[r]) * field.terms + j]) {
        ASSERT_EQ(field.weights(Eigen::Index(r), j), 0.0f) << r << " " << j;
      }
}

TEST(ClusterTerms, ReportsTheErrorTheFieldHasAndKeepsTheBudget) {
  for (double budget : {0.02, 0.2, 1.0}) {
    CompressedField field = field_of_ranks({2, 3, 4, 4});
    const ReflectanceField original = noisy_original(field, 0.05);
    const double before = relative_error(original, field, false).mean;
    const TermChoice choice = drop_unneeded_terms(original, field, budget, 2);
    const double after = relative_error(original, field, false).mean;
    EXPECT_NEAR(choice.error_all_terms, before, 1e-6 * before) << budget;
    EXPECT_NEAR(choice.error_chosen, after, 1e-5 * after) << budget;
    EXPECT_LE(after, before * (1 + budget) * (1 + 1e-5)) << budget;
    EXPECT_GT(choice.dropped, 0u) << budget;  // at least the dependent directions go
  }
  // A larger budget drops more.
  CompressedField small = field_of_ranks({2, 3, 4, 4}), large = small;
  const ReflectanceField original = noisy_original(small, 0.05);
  EXPECT_LT(drop_unneeded_terms(original, small, 0.02, 2).dropped,
            drop_unneeded_terms(original, large, 1000.0, 2).dropped);
}

TEST(ClusterTerms, AZeroBudgetLeavesTheFieldAsItIs) {
  CompressedField field = field_of_ranks({1, 2, 3, 4});
  const CompressedField before = field;
  const TermChoice choice = drop_unneeded_terms(reconstruct_field(field), field, 0.0, 2);
  EXPECT_EQ(choice.dropped, 0u);
  EXPECT_EQ(field.bases, before.bases);
  EXPECT_TRUE(field.weights == before.weights);
}

TEST(ClusterTerms, AlignmentKeepsUnusedRowsUnused) {
  CompressedField field = field_of_ranks({1, 2, 4, 3});
  const ReflectanceField exact = reconstruct_field(field);
  drop_unneeded_terms(noisy_original(field, 1e-3), field, 0.01, 2);
  align_cluster_bases(field);
  EXPECT_EQ(terms_per_cluster(field), (std::vector<int>{1, 2, 4, 3}));
  EXPECT_LT(largest_difference(reconstruct_field(field), exact), 1e-5);
}

TEST(ClusterTerms, TheContainerStoresNoWeightForAnUnusedRow) {
  TempDir dir;
  CompressedField field = field_of_ranks({1, 2, 4, 3});
  const ReflectanceField original = noisy_original(field, 1e-3);
  QuantizationBudget budget;
  budget.term_increase = 0.01;
  budget.threads = 2;
  quantize_with_budget(original, field, budget);
  ASSERT_EQ(terms_per_cluster(field), (std::vector<int>{1, 2, 4, 3}));
  ContainerOptions raw;
  raw.entropy_coding = false;
  write_container(dir / "f.relume", field, raw);
  const std::uint64_t weights = stored_weight_count(field, used_basis_rows(field));
  EXPECT_LT(weights, field.stored_rows() * std::size_t(field.terms));
  EXPECT_EQ(describe_container(dir / "f.relume").section("weights").raw_bytes, 2 * weights);
  const CompressedField read = read_container(dir / "f.relume");
  EXPECT_EQ(read.bases, field.bases);
  EXPECT_TRUE(read.weights == field.weights);
}

}  // namespace
}  // namespace relume
