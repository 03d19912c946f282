#include "doe/nelder_mead.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace cdem::calib {

namespace {

struct Simplex {
  std::vector<Eigen::VectorXd> x;
  std::vector<double> f;
};

}  // namespace

NelderMeadResult nelder_mead_box(const std::function<double(const Eigen::VectorXd&)>& f,
                                 const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper, const NelderMeadOptions& options) {
  const Eigen::Index n = start.size();
  const Eigen::VectorXd range = upper - lower;
  NelderMeadResult best{start.cwiseMax(lower).cwiseMin(upper), 0.0, 0};
  auto evaluate = [&](const Eigen::VectorXd& x) {
    ++best.evaluations;
    return f(x);
  };
  auto project = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return x.cwiseMax(lower).cwiseMin(upper);
  };
  best.f = evaluate(best.x);

  // Standard coefficients: reflection 1, expansion 2, contraction 1/2, shrink 1/2.
  for (int round = 0; round < 2; ++round) {
    const double step = options.initial_step / (round == 0 ? 1.0 : 10.0);
    Simplex s;
    s.x.push_back(best.x);
    s.f.push_back(best.f);
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::VectorXd v = best.x;
      // Step away from the nearer bound so that the vertex does not collapse onto the face.
      const double delta = step * range(i);
      v(i) += (v(i) + delta <= upper(i)) ? delta : -delta;
      s.x.push_back(project(v));
      s.f.push_back(evaluate(s.x.back()));
    }
    std::vector<std::size_t> order(s.x.size());
    while (best.evaluations < options.max_evaluations) {
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.f[a] < s.f[b]; });
      const std::size_t lo = order.front(), hi = order.back(), second = order[order.size() - 2];
      double span = 0;
      for (const auto& v : s.x)
        span = std::max(span, ((v - s.x[lo]).cwiseQuotient(range)).cwiseAbs().maxCoeff());
      if (span < options.x_tolerance || s.f[hi] - s.f[lo] < options.f_tolerance) break;

      Eigen::VectorXd centroid = Eigen::VectorXd::Zero(n);
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (i != hi) centroid += s.x[i];
      centroid /= static_cast<double>(n);

      const Eigen::VectorXd reflected = project(centroid + (centroid - s.x[hi]));
      const double f_reflected = evaluate(reflected);
      if (f_reflected < s.f[lo]) {
        const Eigen::VectorXd expanded = project(centroid + 2.0 * (centroid - s.x[hi]));
        const double f_expanded = evaluate(expanded);
        if (f_expanded < f_reflected) {
          s.x[hi] = expanded;
          s.f[hi] = f_expanded;
        } else {
          s.x[hi] = reflected;
          s.f[hi] = f_reflected;
        }
        continue;
      }
      if (f_reflected < s.f[second]) {
        s.x[hi] = reflected;
        s.f[hi] = f_reflected;
        continue;
      }
      // Contract outside if the reflection improved on the worst vertex, inside otherwise.
      const bool outside = f_reflected < s.f[hi];
      const Eigen::VectorXd contracted =
          outside ? Eigen::VectorXd(centroid + 0.5 * (reflected - centroid))
                  : Eigen::VectorXd(centroid + 0.5 * (s.x[hi] - centroid));
      const double f_contracted = evaluate(contracted);
      if (f_contracted < (outside ? f_reflected : s.f[hi])) {
        s.x[hi] = contracted;
        s.f[hi] = f_contracted;
        continue;
      }
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (i == lo) continue;
        s.x[i] = s.x[lo] + 0.5 * (s.x[i] - s.x[lo]);
        s.f[i] = evaluate(s.x[i]);
      }
    }
    const auto best_vertex = std::min_element(s.f.begin(), s.f.end()) - s.f.begin();
    if (s.f[best_vertex] < best.f) {
      best.f = s.f[best_vertex];
      best.x = s.x[best_vertex];
    }
  }
  return best;
}

}  // namespace cdem::calib
