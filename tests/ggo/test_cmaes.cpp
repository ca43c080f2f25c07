// CMA-ES (tools/ggo): minimises smooth functions from a given start, deterministically.
#include <gtest/gtest.h>

#include <cmath>

#include "ggo/cmaes.hpp"

namespace {

double sphere(const Eigen::VectorXd& x) { return x.squaredNorm(); }

// A rotated ellipsoid, condition 1e4: needs the covariance (not only the step size) to adapt.
double ellipsoid(const Eigen::VectorXd& x)
{
  const int n = static_cast<int>(x.size());
  double f = 0;
  for (int i = 0; i < n; ++i) {
    const double y = x[i] + 0.5 * x[(i + 1) % n];  // a fixed, invertible mix of the coordinates
    f += std::pow(1e4, static_cast<double>(i) / (n - 1)) * y * y;
  }
  return f;
}

template <class F>
ggo::Cmaes run(F f, int n, double start, double sigma, int gens, uint64_t seed)
{
  ggo::CmaesOptions o;
  o.seed = seed;
  ggo::Cmaes es(Eigen::VectorXd::Constant(n, start), sigma, o);
  for (int g = 0; g < gens; ++g) {
    const auto& xs = es.ask();
    std::vector<double> v;
    for (const auto& x : xs) v.push_back(f(x));
    es.tell(v);
  }
  return es;
}

TEST(Cmaes, MinimisesSphereFromGivenStart)
{
  const ggo::Cmaes es = run(sphere, 10, 3.0, 1.0, 250, 0);
  EXPECT_EQ(es.lambda(), 4 + static_cast<int>(std::floor(3 * std::log(10.0))));
  EXPECT_LT(sphere(es.mean()), 1e-10);  // start: 90
  EXPECT_LT(es.best_fitness(), 1e-10);
  EXPECT_LT(es.sigma(), 1e-4);  // the step size shrank with the distance
}

TEST(Cmaes, AdaptsCovarianceOnIllConditionedQuadratic)
{
  const ggo::Cmaes es = run(ellipsoid, 8, 1.0, 0.5, 600, 3);
  EXPECT_LT(ellipsoid(es.best()), 1e-8);  // start: ~2.5e4
}

TEST(Cmaes, DeterministicForASeed)
{
  const ggo::Cmaes a = run(sphere, 6, 2.0, 0.5, 20, 7), b = run(sphere, 6, 2.0, 0.5, 20, 7);
  const ggo::Cmaes c = run(sphere, 6, 2.0, 0.5, 20, 8);
  EXPECT_EQ(a.best(), b.best());
  EXPECT_EQ(a.best_fitness(), b.best_fitness());
  EXPECT_EQ(a.sigma(), b.sigma());
  EXPECT_NE(a.best(), c.best());
}

TEST(Cmaes, BestIsTheBestToldAndImprovesOnTheStart)
{
  ggo::Cmaes es(Eigen::VectorXd::Constant(4, 1.0), 0.3);
  double best = 1e300;
  for (int g = 0; g < 5; ++g) {
    const auto& xs = es.ask();
    std::vector<double> v;
    for (const auto& x : xs) v.push_back(sphere(x)), best = std::min(best, v.back());
    es.tell(v);
  }
  EXPECT_EQ(es.best_fitness(), best);
  EXPECT_EQ(sphere(es.best()), best);
  EXPECT_LT(best, 4.0);
  EXPECT_EQ(es.generation(), 5);
}

TEST(Cmaes, RejectsBadArguments)
{
  EXPECT_THROW(ggo::Cmaes(Eigen::VectorXd(), 1.0), std::invalid_argument);
  EXPECT_THROW(ggo::Cmaes(Eigen::VectorXd::Zero(3), 0.0), std::invalid_argument);
  ggo::Cmaes es(Eigen::VectorXd::Zero(3), 1.0);
  EXPECT_THROW(es.tell({1.0}), std::invalid_argument);  // no ask() yet
  es.ask();
  EXPECT_THROW(es.tell({1.0, 2.0}), std::invalid_argument);
}

}  // namespace
