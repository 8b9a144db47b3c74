// T = (I - diag(rho) F)^-1, one dense LU per channel.
#include "patch/precomputed_transfer.h"

#include <radiosity/error.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>

namespace rad {

PrecomputedTransfer::PrecomputedTransfer(const FormFactorTable& table, const PatchSystem& system,
                                         const ProgressCallback& progress)
    : n_(system.size()), columns_(3 * n_ * n_) {
  const Eigen::Index n = Eigen::Index(n_);
  for (int c = 0; c < 3; ++c) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto cols = table.columns(size_t(i));
      const auto vals = table.values(size_t(i));
      for (size_t k = 0; k < cols.size(); ++k)
        a(i, cols[k]) -= double(system.rho[size_t(i)][c]) * double(vals[k]);
    }
    const Eigen::MatrixXd t = a.partialPivLu().inverse();
    float* out = columns_.data() + size_t(c) * n_ * n_;
    for (Eigen::Index k = 0; k < n; ++k)
      for (Eigen::Index i = 0; i < n; ++i) out[size_t(k) * n_ + size_t(i)] = float(t(i, k));
    if (progress && !progress(double(c + 1) / 3.0)) throw Cancelled();
  }
}

void PrecomputedTransfer::propagate(std::span<const Color> u, const FormFactorTable& table,
                                    std::vector<Color>& radiosity,
                                    std::vector<Color>& irradiance) const {
  std::vector<uint32_t> sources;
  for (uint32_t k = 0; k < n_; ++k)
    if (u[k] != Color(0.0f)) sources.push_back(k);
  if (sources.empty()) return;
  // x = T u over the patches, in row blocks (each thread its own rows, every source column).
  std::vector<Color> x(n_, Color(0.0f));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n_, 512), [&](const auto& rows) {
    for (int c = 0; c < 3; ++c) {
      const float* t = columns_.data() + size_t(c) * n_ * n_;
      for (uint32_t k : sources) {
        const float weight = u[k][c];
        const float* column = t + size_t(k) * n_;
        for (size_t i = rows.begin(); i != rows.end(); ++i) x[i][c] += column[i] * weight;
      }
    }
  });
  tbb::parallel_for(size_t(0), n_, [&](size_t i) {
    radiosity[i] += x[i] - u[i];
    const auto cols = table.columns(i);
    const auto vals = table.values(i);
    Color h(0.0f);
    for (size_t k = 0; k < cols.size(); ++k) h += vals[k] * x[cols[k]];
    irradiance[i] += h;
  });
}

}  // namespace rad
