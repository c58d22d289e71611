#include <legwork/core/series.hpp>

#include <legwork/core/types.hpp>

#include <deque>
#include <string>

namespace legwork {

std::vector<double> rolling_min(const std::vector<double>& x, int w) {
  if (w < 0) throw Error("rolling_min: window must be >= 0 samples, got " + std::to_string(w));
  // Monotone deque of indices whose values increase from front to back.
  const int n = static_cast<int>(x.size());
  std::vector<double> out(x.size());
  std::deque<int> dq;
  int next = 0;
  for (int i = 0; i < n; ++i) {
    for (; next < n && next <= i + w; ++next) {
      while (!dq.empty() && x[static_cast<std::size_t>(dq.back())] >= x[static_cast<std::size_t>(next)]) dq.pop_back();
      dq.push_back(next);
    }
    while (dq.front() < i - w) dq.pop_front();
    out[static_cast<std::size_t>(i)] = x[static_cast<std::size_t>(dq.front())];
  }
  return out;
}

}  // namespace legwork
