#include <legwork/accent/search.hpp>

#include "database_impl.hpp"

#include <Eigen/Core>

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

// push_top, unless the window is already in out[0..n). Only for distances all
// computed alike (squared_distance, one class factor each): the same window then
// has the same distance, so only the entries equal to d2 need a look.
inline void push_unique(std::span<Match> out, int k, int& n, int window, float d2) {
  if (n == k && d2 >= out[static_cast<std::size_t>(n - 1)].distance) return;
  int i = n;  // the insertion point: found first, as the check needs it, then the entries moved
  while (i > 0 && out[static_cast<std::size_t>(i - 1)].distance > d2) --i;
  for (int j = i - 1; j >= 0 && out[static_cast<std::size_t>(j)].distance == d2; --j)
    if (out[static_cast<std::size_t>(j)].window == window) return;
  if (n < k) ++n;
  for (int m = n - 1; m > i; --m) out[static_cast<std::size_t>(m)] = out[static_cast<std::size_t>(m - 1)];
  out[static_cast<std::size_t>(i)] = {window, d2};
}

// Squared distance between two feature rows, in SIMD packets (Eigen sums
// them in independent lanes: a scalar loop is one serial chain of kDim adds).
inline float squared_distance(const float* a, const float* b) {
  using Row = Eigen::Map<const Eigen::Array<float, kDim, 1>>;
  return (Row(a) - Row(b)).square().sum();
}

// nanoflann result set over the prefix trees: the tree reports points whose
// prefix distance beats worstDist(); we rank them by their full distance and
// report the k-th best full distance as the bound (prefix <= full, so no true
// neighbour is ever pruned).
struct FullDistanceResult {
  const float* features;  // rows in storage order
  const std::uint32_t* window_of_row;
  const std::uint32_t* row_of_window;
  const float* query;
  int base;
  Match* out;  // holds squared distances
  int k, n;
  int budget = -1;  // remaining full-distance evaluations; < 0 = unlimited
  // Class scales (squared): the tree being searched holds one class whose
  // squared distances are multiplied by tree_scale2 (its pruning bound divided
  // by it); with per_window set (one tree over several classes, or seeds) each
  // window's own class factor applies and the bound is not tightened.
  float tree_scale2 = 1.0f;
  const float* class_scale = nullptr;  // factor per class, or nullptr = all 1
  const Database* db = nullptr;
  bool per_window = false;
  float worstDist() const { return n == k ? out[n - 1].distance / tree_scale2 : std::numeric_limits<float>::max(); }
  bool full() const { return n == k; }
  // `prefix` is the tree's distance over the first kTreeDim dimensions.
  bool addPoint(float prefix, std::uint32_t index) {
    if (budget == 0) return false;  // spent in an earlier tree
    const int row = base + static_cast<int>(index);
    add(static_cast<int>(window_of_row[row]), row, prefix);
    return budget < 0 || --budget > 0;  // false stops the tree search
  }
  void add_window(int w) { add(w, static_cast<int>(row_of_window[w]), -1.0f); }
  // prefix >= 0: the squared distance over the first kTreeDim dimensions is
  // known, and the next kTailCheck dimensions (the projection's largest after
  // the tree's) reject most rows before the full distance (a lower bound:
  // every term is >= 0). The distances kept are the full ones, as before.
  static constexpr int kTailCheck = 8;
  static_assert(kTreeDim + kTailCheck <= kDim, "the partial check reads kTailCheck dimensions after the tree's");
  void add(int w, int row, float prefix) {
    const float f = class_scale && per_window ? class_scale[db->source(w).cls] : 1.0f;
    const float s2 = !class_scale ? 1.0f : per_window ? f * f : tree_scale2;
    const float* r = features + static_cast<std::ptrdiff_t>(row) * kDim;
    if (prefix >= 0.0f && n == k) {
      using Part = Eigen::Map<const Eigen::Array<float, kTailCheck, 1>>;
      const float part = prefix + (Part(r + kTreeDim) - Part(query + kTreeDim)).square().sum();
      if (s2 * part >= out[n - 1].distance) return;
    }
    const float d2 = s2 * squared_distance(r, query);
    if (n == k && d2 >= out[n - 1].distance) return;
    for (int i = 0; i < n; ++i)
      if (out[i].window == w) return;  // a seed found again by the tree
    push_top({out, static_cast<std::size_t>(k)}, k, n, w, d2);
  }
};

// The most full-distance evaluations (Fast mode with a check budget) a class
// at a cost (class_scale > 1) gets of the budget: its windows only count if
// nearer than the preferred class's by the factor, and walking every other
// class's tree, cold in the cache, took the no-class search from about 18,500
// to 9,100 frames/s (p99 77 -> 216 us) for 0.01 cm (docs/accent.md, "Other
// classes at a cost"; 64 is also the class probes' budget).
constexpr int kScaledTreeChecks = 64;

bool allowed(std::span<const unsigned char> mask, std::size_t c) { return mask.empty() || (c < mask.size() && mask[c]); }

// The allowed class whose tree's root box is nearest the query (squared
// distance over the tree's dimensions, times the class's squared scale; on a
// tie the smaller scale: a preferred class gets the check budget first);
// ranges.size() when none is allowed.
template <class Scale2>
std::size_t nearest_class_tree(const Database::Impl& d, int hand, const Feature& query,
                               std::span<const unsigned char> class_mask, Scale2 scale2) {
  std::size_t best = d.meta.ranges.size();
  float best_d2 = std::numeric_limits<float>::max(), best_s2 = std::numeric_limits<float>::max();
  for (std::size_t c = 0; c < d.meta.ranges.size(); ++c) {
    const KdTree* tree = d.index[c].tree[static_cast<std::size_t>(hand)].get();
    if (!allowed(class_mask, c) || !tree) continue;
    float d2 = 0;
    for (int i = 0; i < kTreeDim; ++i) {
      const auto& box = tree->root_bbox[static_cast<std::size_t>(i)];
      const float q = query[static_cast<std::size_t>(i)];
      const float out = q < box.low ? box.low - q : q > box.high ? q - box.high : 0.0f;
      d2 += out * out;
    }
    const float s2 = scale2(c);
    d2 *= s2;
    if (d2 < best_d2 || (d2 == best_d2 && s2 < best_s2)) {
      best_d2 = d2;
      best_s2 = s2;
      best = c;
    }
  }
  return best;
}

// Squared class factors (class_scale), when given for every class.
struct ClassScale2 {
  std::span<const float> scale;
  float operator()(std::size_t c) const { return scale.empty() ? 1.0f : scale[c] * scale[c]; }
};
ClassScale2 class_scale2_of(const Database& db, std::span<const float> class_scale) {
  return {class_scale.size() >= db.impl().meta.ranges.size() ? class_scale : std::span<const float>{}};
}

// The given windows into the sorted top-k list out[0..n) (squared distances).
int rank_squared(const Database& db, int hand, const Feature& query, int k, std::span<const unsigned char> class_mask,
                 std::span<const int> windows, std::span<Match> out, const ClassScale2& scale2) {
  const auto& d = db.impl();
  const float* feats = reinterpret_cast<const float*>(d.features[hand]);
  int n = 0;
  for (int w : windows)
    if (w >= 0 && w < db.window_count() && allowed(class_mask, db.source(w).cls))
      push_unique(out, k, n, w,
                  scale2(db.source(w).cls) *
                      squared_distance(feats + static_cast<std::ptrdiff_t>(d.row_of_window[hand][w]) * kDim, query.data()));
  return n;
}

}  // namespace

int rank_windows(const Database& db, int hand, const Feature& query, int k, std::span<const unsigned char> class_mask,
                 std::span<const int> windows, std::span<Match> out, std::span<const float> class_scale) {
  k = std::min<int>(k, static_cast<int>(out.size()));
  if (k <= 0) return 0;
  const int n = rank_squared(db, hand, query, k, class_mask, windows, out, class_scale2_of(db, class_scale));
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)].distance = std::sqrt(out[static_cast<std::size_t>(i)].distance);
  return n;
}

int search_knn(const Database& db, int hand, const Feature& query, int k, SearchMode mode, float eps,
               std::span<const unsigned char> class_mask, std::span<Match> out, std::span<const int> seeds,
               int max_checks, std::span<const float> class_scale) {
  k = std::min<int>(k, static_cast<int>(out.size()));
  if (k <= 0) return 0;
  const auto& d = db.impl();
  const ClassScale2 class_scale2 = class_scale2_of(db, class_scale);
  const bool scaled = !class_scale2.scale.empty();
  int n = 0;  // out[] holds squared distances until the end
  if (mode == SearchMode::BruteForce || !d.indexed) {
    const float* feats = reinterpret_cast<const float*>(d.features[hand]);
    const std::uint32_t* window_of_row = d.window_of_row[hand];
    // Seeds first: a tight bound from the start rejects most rows on the prefix.
    n = rank_squared(db, hand, query, k, class_mask, seeds, out, class_scale2);
    const int seeded = n;
    for (std::size_t c = 0; c < d.meta.ranges.size(); ++c) {
      if (!allowed(class_mask, c)) continue;
      const float s2 = class_scale2(c);
      // Rows stay inside their class's range (database.cpp, open_row_order).
      for (int r = d.meta.ranges[c].first; r < d.meta.ranges[c].second; ++r) {
        const float* row = feats + static_cast<std::ptrdiff_t>(r) * kDim;
        // The principal dimensions come first: most windows are rejected on them.
        float s = 0;
        for (int i = 0; i < 8; ++i) {
          const float x = row[i] - query[static_cast<std::size_t>(i)];
          s += x * x;
        }
        if (n == k && s2 * s >= out[static_cast<std::size_t>(n - 1)].distance) continue;
        for (int i = 8; i < kDim; ++i) {
          const float x = row[i] - query[static_cast<std::size_t>(i)];
          s += x * x;
        }
        s *= s2;
        if (n == k && s >= out[static_cast<std::size_t>(n - 1)].distance) continue;
        const int w = static_cast<int>(window_of_row[r]);
        bool dup = false;
        for (int i = 0; i < n && seeded; ++i) dup = dup || out[static_cast<std::size_t>(i)].window == w;
        if (!dup) push_top(out, k, n, w, s);
      }
    }
  } else {
    // One result set across the class trees: the k-th best full distance found
    // so far prunes every later tree too.
    FullDistanceResult rs{reinterpret_cast<const float*>(d.features[hand]), d.window_of_row[hand],
                          d.row_of_window[hand], query.data(), 0, out.data(), k, 0};
    if (scaled) {
      rs.class_scale = class_scale.data();
      rs.db = &db;
    }
    rs.per_window = true;  // seeds: each its own class's factor
    for (int w : seeds)
      if (w >= 0 && w < db.window_count() && allowed(class_mask, db.source(w).cls)) rs.add_window(w);
    const nanoflann::SearchParams params(32, mode == SearchMode::Fast ? eps : 0.0f);
    const int budget = mode == SearchMode::Fast && max_checks > 0 ? max_checks : -1;
    if (d.index.size() != d.meta.ranges.size() || d.meta.ranges.size() <= 1) {  // one class: one tree pair
      rs.base = 0;
      rs.budget = budget;  // one tree over every class: per-window factors (rs.per_window)
      if (d.all.tree[static_cast<std::size_t>(hand)]) d.all.tree[static_cast<std::size_t>(hand)]->findNeighbors(rs, query.data(), params);
    } else {
      // Each allowed class's tree, nearest root box first, sharing one check
      // budget (as one tree over every allowed window would spend it): the
      // nearest class's tree gets most of it, and the k-th best distance
      // found so far prunes the others.
      const std::size_t first = nearest_class_tree(d, hand, query, class_mask, class_scale2);
      rs.budget = budget;
      rs.per_window = false;
      for (std::size_t i = 0; i <= d.meta.ranges.size() && rs.budget != 0; ++i) {
        const std::size_t c = i == 0 ? first : i - 1;
        if (c >= d.meta.ranges.size() || (i > 0 && c == first) || !allowed(class_mask, c) ||
            d.meta.ranges[c].first == d.meta.ranges[c].second)
          continue;
        rs.base = d.meta.ranges[c].first;
        rs.tree_scale2 = class_scale2(c);
        // A class at a cost gets at most kScaledTreeChecks of the budget.
        int held = 0;
        if (rs.tree_scale2 > 1.0f && rs.budget > kScaledTreeChecks) {
          held = rs.budget - kScaledTreeChecks;
          rs.budget = kScaledTreeChecks;
        }
        d.index[c].tree[static_cast<std::size_t>(hand)]->findNeighbors(rs, query.data(), params);
        rs.budget += held;
      }
    }
    n = rs.n;
  }
  for (int i = 0; i < n; ++i) out[static_cast<std::size_t>(i)].distance = std::sqrt(out[static_cast<std::size_t>(i)].distance);
  return n;
}

}  // namespace legwork::accent
