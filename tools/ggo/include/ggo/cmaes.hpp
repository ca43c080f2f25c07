#pragma once
// Cmaes: the covariance matrix adaptation evolution strategy (Hansen, "The CMA Evolution
// Strategy: A Tutorial", 2016; the (mu/mu_w, lambda) variant with rank-one and rank-mu
// updates and cumulative step-size adaptation), as GGO uses it to search guidance weights
// (Zhang et al., "Guidance Graph Optimization for Lifelong Multi-Agent Path Finding",
// IJCAI 2024). Minimises; ask() / tell() so the caller owns the (expensive) evaluations.
// Deterministic for a seed: one std::mt19937_64, samples drawn in a fixed order.
#include <Eigen/Dense>
#include <cstdint>
#include <random>
#include <vector>

namespace ggo {

struct CmaesOptions {
  int lambda = 0;       // offspring per generation; 0: 4 + floor(3 ln n) (the tutorial's default)
  uint64_t seed = 0;
};

class Cmaes {
 public:
  Cmaes(const Eigen::VectorXd& mean, double sigma, CmaesOptions opt = {});

  // lambda candidates of the next generation (x = m + sigma B D z).
  const std::vector<Eigen::VectorXd>& ask();
  // Their fitness, in ask()'s order (lower is better); updates mean, paths, C and sigma.
  void tell(const std::vector<double>& fitness);

  const Eigen::VectorXd& mean() const { return m_; }
  double sigma() const { return sigma_; }
  int lambda() const { return lambda_; }
  int generation() const { return gen_; }
  // The best candidate told so far and its fitness (+inf before the first tell).
  const Eigen::VectorXd& best() const { return best_x_; }
  double best_fitness() const { return best_f_; }

 private:
  void decompose();

  int n_, lambda_, mu_, gen_ = 0;
  Eigen::VectorXd w_;  // recombination weights, sum 1
  double mueff_, cc_, cs_, c1_, cmu_, damps_, chi_n_;
  Eigen::VectorXd m_, pc_, ps_;
  Eigen::MatrixXd C_, B_;
  Eigen::VectorXd D_;  // sqrt of C's eigenvalues
  double sigma_;
  std::mt19937_64 rng_;
  std::vector<Eigen::VectorXd> xs_, zs_;
  Eigen::VectorXd best_x_;
  double best_f_;
};

}  // namespace ggo
