#include "ggo/cmaes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace ggo {

Cmaes::Cmaes(const Eigen::VectorXd& mean, double sigma, CmaesOptions opt)
    : n_(static_cast<int>(mean.size())), m_(mean), sigma_(sigma), rng_(opt.seed), best_x_(mean),
      best_f_(std::numeric_limits<double>::infinity())
{
  if (n_ < 1) throw std::invalid_argument("cmaes: empty mean");
  if (!(sigma > 0)) throw std::invalid_argument("cmaes: sigma must be positive");
  const double n = n_;
  lambda_ = opt.lambda > 0 ? opt.lambda : 4 + static_cast<int>(std::floor(3 * std::log(n)));
  if (lambda_ < 2) throw std::invalid_argument("cmaes: lambda must be at least 2");
  mu_ = lambda_ / 2;
  w_.resize(mu_);
  for (int i = 0; i < mu_; ++i) w_[i] = std::log((lambda_ + 1) / 2.0) - std::log(i + 1.0);
  w_ /= w_.sum();
  mueff_ = 1 / w_.squaredNorm();
  cc_ = (4 + mueff_ / n) / (n + 4 + 2 * mueff_ / n);
  cs_ = (mueff_ + 2) / (n + mueff_ + 5);
  c1_ = 2 / ((n + 1.3) * (n + 1.3) + mueff_);
  cmu_ = std::min(1 - c1_, 2 * (mueff_ - 2 + 1 / mueff_) / ((n + 2) * (n + 2) + mueff_));
  damps_ = 1 + 2 * std::max(0.0, std::sqrt((mueff_ - 1) / (n + 1)) - 1) + cs_;
  chi_n_ = std::sqrt(n) * (1 - 1 / (4 * n) + 1 / (21 * n * n));
  pc_ = ps_ = Eigen::VectorXd::Zero(n_);
  C_ = B_ = Eigen::MatrixXd::Identity(n_, n_);
  D_ = Eigen::VectorXd::Ones(n_);
}

const std::vector<Eigen::VectorXd>& Cmaes::ask()
{
  std::normal_distribution<double> normal;
  xs_.assign(static_cast<size_t>(lambda_), Eigen::VectorXd());
  zs_.assign(static_cast<size_t>(lambda_), Eigen::VectorXd());
  for (int k = 0; k < lambda_; ++k) {
    Eigen::VectorXd z(n_);
    for (int i = 0; i < n_; ++i) z[i] = normal(rng_);
    xs_[k] = m_ + sigma_ * (B_ * D_.cwiseProduct(z));
    zs_[k] = std::move(z);
  }
  return xs_;
}

void Cmaes::tell(const std::vector<double>& fitness)
{
  if (static_cast<int>(fitness.size()) != lambda_ || static_cast<int>(xs_.size()) != lambda_)
    throw std::invalid_argument("cmaes: tell() needs one fitness per candidate of the last ask()");
  std::vector<int> idx(static_cast<size_t>(lambda_));
  std::iota(idx.begin(), idx.end(), 0);
  // Stable: equal fitness keeps ask()'s order, so plateaus (rounded weights) stay deterministic.
  std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) { return fitness[a] < fitness[b]; });
  if (fitness[idx[0]] < best_f_) best_f_ = fitness[idx[0]], best_x_ = xs_[idx[0]];

  const Eigen::VectorXd old = m_;
  Eigen::VectorXd zmean = Eigen::VectorXd::Zero(n_);
  m_.setZero();
  for (int i = 0; i < mu_; ++i) m_ += w_[i] * xs_[idx[i]], zmean += w_[i] * zs_[idx[i]];
  const double n = n_;
  ps_ = (1 - cs_) * ps_ + std::sqrt(cs_ * (2 - cs_) * mueff_) * (B_ * zmean);
  ++gen_;
  const bool hsig =
      ps_.norm() / std::sqrt(1 - std::pow(1 - cs_, 2.0 * gen_)) / chi_n_ < 1.4 + 2 / (n + 1);
  const Eigen::VectorXd y = (m_ - old) / sigma_;
  pc_ = (1 - cc_) * pc_ + (hsig ? std::sqrt(cc_ * (2 - cc_) * mueff_) : 0.0) * y;
  Eigen::MatrixXd rank_mu = Eigen::MatrixXd::Zero(n_, n_);
  for (int i = 0; i < mu_; ++i) {
    const Eigen::VectorXd yi = (xs_[idx[i]] - old) / sigma_;
    rank_mu += w_[i] * yi * yi.transpose();
  }
  C_ = (1 - c1_ - cmu_) * C_ + c1_ * (pc_ * pc_.transpose() + (hsig ? 0.0 : cc_ * (2 - cc_)) * C_) + cmu_ * rank_mu;
  sigma_ *= std::exp((cs_ / damps_) * (ps_.norm() / chi_n_ - 1));
  decompose();
}

void Cmaes::decompose()
{
  C_ = C_.triangularView<Eigen::Upper>();
  C_ = C_.selfadjointView<Eigen::Upper>();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(C_);
  B_ = es.eigenvectors();
  D_ = es.eigenvalues().cwiseMax(1e-20).cwiseSqrt();
}

}  // namespace ggo
