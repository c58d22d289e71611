#include <legwork/accent/search.hpp>

#include "database_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace legwork::accent {
namespace {

// Inserts (window, d2) into the sorted top-k list held in out[0..n).
inline void push_top(std::span<Match> out, int k, int& n, int window, float d2) {
  if (n == k && d2 >= out[static_cast<std::size_t>(n - 1)].distance) return;
  int i = n < k ? n++ : n - 1;
  while (i > 0 && out[static_cast<std::size_t>(i - 1)].distance > d2) {
    out[static_cast<std::size_t>(i)] = out[static_cast<std::size_t>(i - 1)];
    --i;
  }
  out[static_cast<std::size_t>(i)] = {window, d2};
}

inline float squared_distance(const float* a, const float* b) {
  float s = 0;
  for (int d = 0; d < kDim; ++d) {
    const float x = a[d] - b[d];
    s += x * x;
  }
  return s;
}

bool allowed(std::span<const unsigned char> mask, std::size_t c) { return mask.empty() || (c < mask.size() && mask[c]); }

}  // namespace

int search_knn(const Database& db, int hand, const Feature& query, int k, SearchMode mode, float eps,
               std::span<const unsigned char> class_mask, std::span<Match> out) {
  k = std::min<int>(k, static_cast<int>(out.size()));
  if (k <= 0) return 0;
  const auto& d = db.impl();
  int n = 0;  // out[] holds squared distances until the end
  if (mode == SearchMode::BruteForce || d.index.empty()) {
    const float* feats = reinterpret_cast<const float*>(d.features[hand]);
    for (std::size_t c = 0; c < d.ranges.size(); ++c) {
      if (!allowed(class_mask, c)) continue;
      for (int w = d.ranges[c].first; w < d.ranges[c].second; ++w)
        push_top(out, k, n, w, squared_distance(feats + static_cast<std::ptrdiff_t>(w) * kDim, query.data()));
    }
  } else {
    constexpr int kMaxK = 64;
    std::uint32_t idx[kMaxK];
    float d2[kMaxK];
    const int kk = std::min(k, kMaxK);
    const nanoflann::SearchParams params(32, mode == SearchMode::Fast ? eps : 0.0f);
    for (std::size_t c = 0; c < d.ranges.size(); ++c) {
      if (!allowed(class_mask, c) || d.ranges[c].first == d.ranges[c].second) continue;
      nanoflann::KNNResultSet<float, std::uint32_t> rs(static_cast<std::size_t>(kk));
      rs.init(idx, d2);
      d.index[c].tree[static_cast<std::size_t>(hand)]->findNeighbors(rs, query.data(), params);
      const int got = static_cast<int>(rs.size());
      for (int i = 0; i < got; ++i) push_top(out, k, n, d.ranges[c].first + static_cast<int>(idx[i]), d2[i]);
    }
  }
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)].distance = std::sqrt(out[static_cast<std::size_t>(i)].distance);
  return n;
}

}  // namespace legwork::accent
