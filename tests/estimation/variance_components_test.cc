// Variance components, the measured-noise covariance and the cluster-robust covariance
// (estimation/variance_components.h, estimation/marginal_covariance.h) against dense linear
// algebra on small linear least-squares problems where every quantity has a closed form.
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/model_noise_cluster.h"
#include "splinecal/estimation/variance_components.h"

namespace splinecal {
namespace {

// r = (a_x . x + a_y . y - b) / sigma: one row over a 3-block x and a 2-block y.
class LinearRow : public ceres::SizedCostFunction<1, 3, 2> {
 public:
  LinearRow(const Eigen::Vector3d& a_x, const Eigen::Vector2d& a_y, double b, double sigma)
      : a_x_(a_x / sigma), a_y_(a_y / sigma), b_(b / sigma) {}
  bool Evaluate(double const* const* p, double* r, double** J) const override {
    r[0] = a_x_.dot(Eigen::Map<const Eigen::Vector3d>(p[0])) +
           a_y_.dot(Eigen::Map<const Eigen::Vector2d>(p[1])) - b_;
    if (J != nullptr && J[0] != nullptr) std::copy(a_x_.data(), a_x_.data() + 3, J[0]);
    if (J != nullptr && J[1] != nullptr) std::copy(a_y_.data(), a_y_.data() + 2, J[1]);
    return true;
  }
  Eigen::Matrix<double, 1, 5> row() const {
    Eigen::Matrix<double, 1, 5> j;
    j << a_x_.transpose(), a_y_.transpose();
    return j;
  }

 private:
  Eigen::Vector3d a_x_;
  Eigen::Vector2d a_y_;
  double b_;
};

// Two groups of rows (group 0 and 1) with true noise true_sigma[g], weighted by
// assumed_sigma[g]; solved, with the dense Jacobian J (weighted), residuals e, group and cluster
// of every row kept for the checks.
struct LinearProblem {
  std::unique_ptr<ceres::Problem> problem = std::make_unique<ceres::Problem>();
  double x[3] = {0, 0, 0};
  double y[2] = {0, 0};
  std::map<ceres::ResidualBlockId, int> group;
  std::map<ceres::ResidualBlockId, int> cluster;
  std::vector<const LinearRow*> rows;
  std::vector<int> row_group;
  std::vector<int> row_cluster;

  LinearProblem(int rows_per_group,
                const double true_sigma[2],
                const double assumed_sigma[2],
                int clusters,
                double cluster_offset_std,
                uint32_t seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> normal;
    const Eigen::Matrix<double, 5, 1> truth = (Eigen::Matrix<double, 5, 1>() << 1, -2, 0.5, 3, 1)
                                                  .finished();
    std::vector<double> offsets(clusters);
    for (double& o : offsets) o = cluster_offset_std * normal(random);
    for (int g = 0; g < 2; ++g) {
      for (int k = 0; k < rows_per_group; ++k) {
        const Eigen::Vector3d a_x(normal(random), normal(random), normal(random));
        // Group 1 sees y only weakly: the groups determine different shares of the parameters.
        const Eigen::Vector2d a_y = (g == 0 ? 1.0 : 0.2) * Eigen::Vector2d(normal(random), normal(random));
        const int c = k % clusters;
        const double b = a_x.dot(truth.head<3>()) + a_y.dot(truth.tail<2>()) +
                         true_sigma[g] * normal(random) + offsets[c];
        auto* cost = new LinearRow(a_x, a_y, b, assumed_sigma[g]);
        const ceres::ResidualBlockId id = problem->AddResidualBlock(cost, nullptr, x, y);
        group[id] = g;
        cluster[id] = c;
        rows.push_back(cost);
        row_group.push_back(g);
        row_cluster.push_back(c);
      }
    }
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.function_tolerance = 1e-15;
    options.gradient_tolerance = 1e-15;
    options.parameter_tolerance = 1e-15;
    ceres::Solver::Summary summary;
    ceres::Solve(options, problem.get(), &summary);
  }

  Eigen::MatrixXd J() const {
    Eigen::MatrixXd j(rows.size(), 5);
    for (size_t i = 0; i < rows.size(); ++i) j.row(i) = rows[i]->row();
    return j;
  }
  Eigen::VectorXd Residuals() const {
    Eigen::VectorXd e(rows.size());
    double const* params[2] = {x, y};
    for (size_t i = 0; i < rows.size(); ++i) rows[i]->Evaluate(params, &e[i], nullptr);
    return e;
  }
  // sum_k g_k g_k^T over clusters 0..clusters-1, g_k = sum over cluster k's rows of j^T e.
  Eigen::MatrixXd ClusterMeat(int clusters) const {
    const Eigen::MatrixXd j = J();
    const Eigen::VectorXd e = Residuals();
    Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(5, 5);
    for (int c = 0; c < clusters; ++c) {
      Eigen::VectorXd g = Eigen::VectorXd::Zero(5);
      for (int i = 0; i < e.size(); ++i) {
        if (row_cluster[i] == c) g += j.row(i).transpose() * e[i];
      }
      meat += g * g.transpose();
    }
    return meat;
  }
  // H_g = sum over group g's rows of j^T j.
  Eigen::MatrixXd GroupInformation(int g) const {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(5, 5);
    const Eigen::MatrixXd j = J();
    for (size_t i = 0; i < rows.size(); ++i) {
      if (row_group[i] == g) H += j.row(i).transpose() * j.row(i);
    }
    return H;
  }
};

TEST(VarianceComponents, RedundancyAndFactorMatchTheDenseFormulas) {
  const double true_sigma[2] = {0.5, 2.0};
  const double assumed_sigma[2] = {1.0, 1.0};
  LinearProblem p(400, true_sigma, assumed_sigma, 1, 0.0, 7);
  const VarianceComponents vc = EstimateVarianceComponents(
      p.problem.get(), [&p](ceres::ResidualBlockId id) { return p.group.at(id); });
  ASSERT_TRUE(vc.ok);
  const Eigen::MatrixXd H = p.GroupInformation(0) + p.GroupInformation(1);
  const Eigen::VectorXd e = p.Residuals();
  for (int g = 0; g < 2; ++g) {
    const double trace = (H.inverse() * p.GroupInformation(g)).trace();
    double squares = 0.0;
    for (int i = 0; i < e.size(); ++i) squares += p.row_group[i] == g ? e[i] * e[i] : 0.0;
    const VarianceComponent& c = vc.groups.at(g);
    EXPECT_EQ(c.num_residuals, 400);
    EXPECT_NEAR(c.squared_sum, squares, 1e-9 * squares);
    // The traces are exact (selected inversion): the redundancy to rounding.
    EXPECT_NEAR(c.redundancy, 400.0 - trace, 1e-9 * 400.0) << g;
    EXPECT_TRUE(c.identifiable);
    // The factor estimates (true / assumed)^2: 0.25 and 4, to 3 of its relative std sqrt(2/r).
    const double expected = std::pow(true_sigma[g] / assumed_sigma[g], 2);
    EXPECT_NEAR(c.factor, expected, 3.0 * std::sqrt(2.0 / c.redundancy) * expected) << g;
  }
  // The traces share out the 5 parameters.
  EXPECT_NEAR(vc.groups.at(0).redundancy + vc.groups.at(1).redundancy, 800.0 - 5.0, 1e-9 * 800.0);
}

TEST(VarianceComponents, AGroupBelowTheMinimumRedundancyIsNotIdentifiable) {
  const double sigma[2] = {1.0, 1.0};
  LinearProblem p(400, sigma, sigma, 1, 0.0, 3);
  // Group 1 counted as 6 independent rows (a given rank): redundancy below 30.
  const VarianceComponents vc = EstimateVarianceComponents(
      p.problem.get(), [&p](ceres::ResidualBlockId id) { return p.group.at(id); }, {}, {{1, 6.0}});
  ASSERT_TRUE(vc.ok);
  EXPECT_LT(vc.groups.at(1).redundancy, 6.0);
  EXPECT_FALSE(vc.groups.at(1).identifiable);
  EXPECT_EQ(vc.groups.at(1).factor, 1.0);
  EXPECT_TRUE(vc.groups.at(0).identifiable);
}

TEST(MarginalCovarianceExtras, NoiseRobustAndMappedCovariancesMatchTheDenseFormulas) {
  const double true_sigma[2] = {0.5, 2.0};
  const double assumed_sigma[2] = {1.0, 1.0};
  const int clusters = 20;
  LinearProblem p(200, true_sigma, assumed_sigma, clusters, 0.3, 11);
  const std::map<int, double> factors = {{0, 0.3}, {1, 5.0}};
  Eigen::MatrixXd A(2, 5);  // reported: x_0 + y_1 and 2 y_0
  A << 1, 0, 0, 0, 1, 0, 0, 0, 2, 0;
  MarginalCovarianceOptions options;
  options.cluster_of = [&p](ceres::ResidualBlockId id) { return p.cluster.at(id); };
  options.group_of = [&p](ceres::ResidualBlockId id) { return p.group.at(id); };
  options.noise_factors = factors;
  options.reported_map = A;
  const MarginalCovariance m = ComputeMarginalCovariance(p.problem.get(), {p.x, p.y}, options);
  ASSERT_TRUE(m.ok);
  // Dense references.
  const Eigen::MatrixXd H0 = p.GroupInformation(0);
  const Eigen::MatrixXd H1 = p.GroupInformation(1);
  const Eigen::MatrixXd H_inv = (H0 + H1).inverse();
  const Eigen::MatrixXd model = A * H_inv * A.transpose();
  const Eigen::MatrixXd noise = A * H_inv * (0.3 * H0 + 5.0 * H1) * H_inv * A.transpose();
  const Eigen::MatrixXd meat = p.ClusterMeat(clusters);
  const Eigen::MatrixXd robust =
      A * H_inv * (clusters / (clusters - 1.0) * meat) * H_inv * A.transpose();
  EXPECT_TRUE(m.covariance.isApprox(model, 1e-9)) << m.covariance << "\n" << model;
  EXPECT_TRUE(m.noise_covariance.isApprox(noise, 1e-9)) << m.noise_covariance << "\n" << noise;
  EXPECT_TRUE(m.robust_covariance.isApprox(robust, 1e-9)) << m.robust_covariance << "\n" << robust;
  EXPECT_EQ(m.num_clusters, clusters);
}

// r = L^-1 (x - x0): a prior on the 3-block x with covariance L L^T.
class PriorOnX : public ceres::SizedCostFunction<3, 3> {
 public:
  PriorOnX(const Eigen::Matrix3d& L, const Eigen::Vector3d& x0) : L_inv_(L.inverse()), x0_(x0) {}
  bool Evaluate(double const* const* p, double* r, double** J) const override {
    Eigen::Map<Eigen::Vector3d> residual(r);
    residual = L_inv_ * (Eigen::Map<const Eigen::Vector3d>(p[0]) - x0_);
    if (J != nullptr && J[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> jacobian(J[0]);
      jacobian = L_inv_;
    }
    return true;
  }

 private:
  Eigen::Matrix3d L_inv_;
  Eigen::Vector3d x0_;
};

// A prior is not a data cluster (estimation/model_noise_cluster.h): its variance in the robust covariance's
// M is its information L^-T L^-1, however far the data pull against it. Data that scatter as
// their weights say, and a prior 4 of its stds from them: the robust std of x stays below the
// prior's. Taken as a cluster, its realised pull (4 stds) would count 16x its variance.
TEST(MarginalCovarianceExtras, APriorEntersTheRobustCovarianceByItsStatedVariance) {
  const double sigma[2] = {1.0, 1.0};
  const int clusters = 10;  // 2 rows each
  LinearProblem p(10, sigma, sigma, clusters, 0.0, 5);  // 20 rows: x poorly determined
  Eigen::Matrix3d L;
  L << 0.3, 0, 0, 0.1, 0.2, 0, -0.05, 0.02, 0.25;
  const Eigen::Vector3d x_data(p.x[0], p.x[1], p.x[2]);  // the data's own solution
  const Eigen::Vector3d x0 = x_data + 4.0 * L * Eigen::Vector3d(1, -1, 1).normalized();
  const ceres::ResidualBlockId prior =
      p.problem->AddResidualBlock(new PriorOnX(L, x0), nullptr, p.x);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.function_tolerance = solver.gradient_tolerance = solver.parameter_tolerance = 1e-15;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, p.problem.get(), &summary);
  MarginalCovarianceOptions options;
  options.cluster_of = [&p, prior](ceres::ResidualBlockId id) {
    return id == prior ? kModelNoiseCluster : p.cluster.at(id);
  };
  const MarginalCovariance m = ComputeMarginalCovariance(p.problem.get(), {p.x, p.y}, options);
  ASSERT_TRUE(m.ok);
  // Dense reference: H = H_data + H_prior, M = G/(G-1) sum_k g_k g_k^T (data) + H_prior.
  Eigen::MatrixXd H_prior = Eigen::MatrixXd::Zero(5, 5);
  const Eigen::Matrix3d L_inv = L.inverse();
  H_prior.topLeftCorner<3, 3>() = L_inv.transpose() * L_inv;
  const Eigen::MatrixXd H_inv = (p.GroupInformation(0) + p.GroupInformation(1) + H_prior).inverse();
  const Eigen::MatrixXd meat = p.ClusterMeat(clusters);
  const Eigen::MatrixXd robust =
      H_inv * (clusters / (clusters - 1.0) * meat + H_prior) * H_inv;
  EXPECT_TRUE(m.covariance.isApprox(H_inv, 1e-9)) << m.covariance << "\n" << H_inv;
  EXPECT_TRUE(m.robust_covariance.isApprox(robust, 1e-9)) << m.robust_covariance << "\n"
                                                         << robust;
  EXPECT_EQ(m.num_clusters, clusters);  // the prior is none of them
  const Eigen::Matrix3d prior_covariance = L * L.transpose();
  for (int k = 0; k < 3; ++k) {
    EXPECT_LT(m.robust_covariance(k, k), prior_covariance(k, k)) << k;
  }
}

// A hub block and its leaves: every row couples the hub x with one leaf y_i, so the group of
// the rows (grouped by their first block, x) holds the pairs (x, x), (x, y_i), (y_i, y_i) and
// none between two leaves: a block-sparse information, as a target view's with every point
// free. Its covariances (the weights', the measured noise's, the robust one) and the variance
// components' traces against the dense formulas.
TEST(MarginalCovarianceExtras, ABlockSparseGroupMatchesTheDenseFormulas) {
  constexpr int kLeaves = 6;
  constexpr int kRowsPerLeaf = 5;
  constexpr int kClusters = 4;
  constexpr int kColumns = 3 + 2 * kLeaves;
  std::mt19937 random(23);
  std::normal_distribution<double> normal;
  ceres::Problem problem;
  double x[3] = {0, 0, 0};
  double y[kLeaves][2] = {};
  std::map<ceres::ResidualBlockId, int> label;
  std::map<ceres::ResidualBlockId, int> cluster;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(kLeaves * kRowsPerLeaf, kColumns);
  std::vector<const LinearRow*> rows;
  std::vector<int> row_label, row_cluster, row_leaf;
  for (int i = 0; i < kLeaves; ++i) {
    for (int k = 0; k < kRowsPerLeaf; ++k) {
      const Eigen::Vector3d a_x(normal(random), normal(random), normal(random));
      const Eigen::Vector2d a_y(normal(random), normal(random));
      const double sigma = i % 2 == 0 ? 1.0 : 2.0;
      auto* cost = new LinearRow(a_x, a_y, 3.0 * normal(random), sigma);
      const ceres::ResidualBlockId id = problem.AddResidualBlock(cost, nullptr, x, y[i]);
      const int row = static_cast<int>(rows.size());
      J.row(row).head<3>() = cost->row().head<3>();
      J.row(row).segment<2>(3 + 2 * i) = cost->row().tail<2>();
      label[id] = i % 2;
      cluster[id] = row % kClusters;
      rows.push_back(cost);
      row_label.push_back(i % 2);
      row_cluster.push_back(row % kClusters);
      row_leaf.push_back(i);
    }
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.function_tolerance = solver.gradient_tolerance = solver.parameter_tolerance = 1e-15;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  Eigen::VectorXd e(rows.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    double const* params[2] = {x, y[row_leaf[r]]};
    rows[r]->Evaluate(params, &e[r], nullptr);
  }
  // Dense references.
  Eigen::MatrixXd H_label[2] = {Eigen::MatrixXd::Zero(kColumns, kColumns),
                                Eigen::MatrixXd::Zero(kColumns, kColumns)};
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(kColumns, kClusters);
  for (int r = 0; r < J.rows(); ++r) {
    H_label[row_label[r]] += J.row(r).transpose() * J.row(r);
    g.col(row_cluster[r]) += J.row(r).transpose() * e[r];
  }
  const Eigen::MatrixXd H_inv = (H_label[0] + H_label[1]).inverse();
  const Eigen::MatrixXd meat = kClusters / (kClusters - 1.0) * g * g.transpose();
  // The reported blocks x and y_2: columns 0-2 and 7-8.
  const std::vector<int> wanted = {0, 1, 2, 7, 8};
  auto on_wanted = [&wanted](const Eigen::MatrixXd& m) {
    Eigen::MatrixXd out(wanted.size(), wanted.size());
    for (size_t i = 0; i < wanted.size(); ++i) {
      for (size_t j = 0; j < wanted.size(); ++j) out(i, j) = m(wanted[i], wanted[j]);
    }
    return out;
  };
  MarginalCovarianceOptions options;
  options.group_of = [&label](ceres::ResidualBlockId id) { return label.at(id); };
  options.noise_factors = {{0, 0.3}, {1, 5.0}};
  options.cluster_of = [&cluster](ceres::ResidualBlockId id) { return cluster.at(id); };
  const MarginalCovariance m = ComputeMarginalCovariance(&problem, {x, y[2]}, options);
  ASSERT_TRUE(m.ok);
  const Eigen::MatrixXd model = on_wanted(H_inv);
  const Eigen::MatrixXd noise = on_wanted(H_inv * (0.3 * H_label[0] + 5.0 * H_label[1]) * H_inv);
  const Eigen::MatrixXd robust = on_wanted(H_inv * meat * H_inv);
  EXPECT_TRUE(m.covariance.isApprox(model, 1e-9)) << m.covariance << "\n" << model;
  EXPECT_TRUE(m.noise_covariance.isApprox(noise, 1e-9)) << m.noise_covariance << "\n" << noise;
  EXPECT_TRUE(m.robust_covariance.isApprox(robust, 1e-9)) << m.robust_covariance << "\n"
                                                         << robust;
  // Variance components: the redundancy n_l - tr(H^-1 H_l) of each label's rows.
  const VarianceComponents vc = EstimateVarianceComponents(
      &problem, [&label](ceres::ResidualBlockId id) { return label.at(id); });
  ASSERT_TRUE(vc.ok);
  for (int l = 0; l < 2; ++l) {
    const double expected = kLeaves / 2 * kRowsPerLeaf - (H_inv * H_label[l]).trace();
    EXPECT_NEAR(vc.groups.at(l).redundancy, expected, 1e-9 * kColumns) << l;
  }
}

// A further clustering (MarginalCovarianceOptions::further_cluster_of) shares the first one's
// linearisation and factorisation: its robust covariance is what a run with it as the only
// clustering gives, a residual it puts in kModelNoiseCluster included, and the first one's
// result does not change.
TEST(MarginalCovarianceExtras, AFurtherClusteringGivesWhatItsOwnRunGives) {
  const double true_sigma[2] = {0.5, 2.0};
  const double assumed_sigma[2] = {1.0, 1.0};
  const int clusters = 20;
  LinearProblem p(200, true_sigma, assumed_sigma, clusters, 0.3, 17);
  const auto by_cluster = [&p](ceres::ResidualBlockId id) { return p.cluster.at(id); };
  const ceres::ResidualBlockId stated = p.cluster.begin()->first;
  const auto coarser = [&p, stated](ceres::ResidualBlockId id) {
    return id == stated ? kModelNoiseCluster : p.cluster.at(id) % 6;
  };
  MarginalCovarianceOptions options;
  options.group_of = [&p](ceres::ResidualBlockId id) { return p.group.at(id); };
  options.noise_factors = {{0, 0.3}, {1, 5.0}};
  options.cluster_of = by_cluster;
  const MarginalCovariance first = ComputeMarginalCovariance(p.problem.get(), {p.x, p.y}, options);
  options.further_cluster_of = {coarser};
  const MarginalCovariance both = ComputeMarginalCovariance(p.problem.get(), {p.x, p.y}, options);
  options.cluster_of = coarser;
  options.further_cluster_of.clear();
  const MarginalCovariance alone = ComputeMarginalCovariance(p.problem.get(), {p.x, p.y}, options);
  ASSERT_TRUE(first.ok && both.ok && alone.ok);
  ASSERT_EQ(both.further.size(), 1u);
  const MarginalCovariance& further = both.further.front();
  // The same sums in the same order: equal to the last bit.
  EXPECT_EQ(both.robust_covariance, first.robust_covariance);
  EXPECT_EQ(both.num_clusters, clusters);
  EXPECT_EQ(further.robust_covariance, alone.robust_covariance);
  EXPECT_EQ(further.num_clusters, 6);
  EXPECT_EQ(alone.num_clusters, 6);
  EXPECT_TRUE(further.ok);
  EXPECT_EQ(further.covariance, both.covariance);
  EXPECT_EQ(further.noise_covariance, both.noise_covariance);
  EXPECT_EQ(further.covariance, alone.covariance);
  // The coarser clustering scatters otherwise than the first: not a copy of it.
  EXPECT_GT((further.robust_covariance - both.robust_covariance).norm(),
            1e-3 * both.robust_covariance.norm());
}

TEST(ReportedCovariance, TakesTheLargestAndTheRobustOnlyWhenSignificant) {
  MarginalCovariance m;
  m.ok = true;
  m.covariance = Eigen::Matrix2d::Identity();
  m.covariance(0, 1) = m.covariance(1, 0) = 0.5;
  m.noise_covariance = m.covariance;
  m.noise_covariance(0, 0) = 4.0;  // measured noise: std x2 on the first coordinate
  m.robust_covariance = Eigen::Matrix2d::Identity();
  m.robust_covariance(0, 0) = 5.0;  // 1.25x the noise variance: within its scatter for G = 36
  m.robust_covariance(1, 1) = 9.0;  // 9x: significant
  m.num_clusters = 36;
  const ReportedCovariance r = ReportedCovarianceOf(m);
  // chi^2_35 95% quantile / 35 = 1.4208 (tables: 49.802 / 35 = 1.4229); threshold its sqrt.
  EXPECT_NEAR(r.robust_threshold * r.robust_threshold, 49.802 / 35.0, 0.005);
  EXPECT_NEAR(r.covariance(0, 0), 4.0, 1e-12);  // the measured noise, not the robust 5
  EXPECT_NEAR(r.covariance(1, 1), 9.0, 1e-12);  // the robust one
  EXPECT_NEAR(r.inflation[0], 2.0, 1e-12);
  EXPECT_NEAR(r.inflation[1], 3.0, 1e-12);
  // The correlation is kept: 0.5 / (1 * 1) -> 0.5 * 2 * 3 / (2 * 3).
  EXPECT_NEAR(r.covariance(0, 1), 0.5 * 2.0 * 3.0, 1e-12);
}

}  // namespace
}  // namespace splinecal
