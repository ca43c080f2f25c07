#include "policy/model.hpp"

#include <utility>

namespace policy {

size_t Model::num_parameters() const
{
  size_t p = 0;
  for (const Dense& l : layers) p += static_cast<size_t>(l.w.size() + l.b.size());
  return p;
}

void Model::forward(const Eigen::Ref<const Eigen::MatrixXf>& x, Eigen::MatrixXf& logits) const
{
  Eigen::MatrixXf h, next;
  for (size_t k = 0; k < layers.size(); ++k) {
    const Dense& l = layers[k];
    Eigen::MatrixXf& y = k + 1 == layers.size() ? logits : next;
    if (k == 0) y.noalias() = l.w * x;
    else y.noalias() = l.w * h;
    y.colwise() += l.b;
    if (k + 1 < layers.size()) {
      y = y.cwiseMax(0.0f);
      std::swap(h, y);
    }
  }
}

}  // namespace policy
