#pragma once
// k-nearest-neighbour search over one hand's database features.
// Runtime code: no allocation, no exceptions; thread-safe on a const Database.
#include <legwork/accent/database.hpp>

#include <span>

namespace legwork::accent {

enum class SearchMode {
  BruteForce,  // linear scan: the reference
  Exact,       // KD-tree, exact (same neighbours as BruteForce, ties aside)
  Fast,        // KD-tree, eps-approximate: a neighbour may be up to (1+eps)x farther
};

struct Match {
  int window = -1;
  float distance = 0;  // L2 in projected feature units (not squared)
};

// Up to k nearest windows to `query` for hand 0 (left) / 1 (right), sorted by
// distance, among the classes whose mask byte is non-zero (empty mask = all
// classes). k is capped at out.size(). Falls back to BruteForce when the
// database has no index. Returns the number of matches written.
// `seeds` (optional): windows likely to be close, e.g. the previous frame's
// matches; they tighten the KD-tree bound from the start (results unchanged
// in Exact mode, usually better in Fast mode).
// `max_checks` (Fast mode only, 0 = unlimited): stop a class's tree after this
// many full-distance evaluations, bounding the worst-case latency when the
// query is far from everything in the database.
// `class_scale` (optional, one factor >= 1 per database class, or empty = all
// 1): each class's distances are multiplied by its factor before ranking (and
// reported so), so a class can be preferred without excluding the others
// (Settings::other_class_cost). A larger factor prunes that class's tree
// harder, so it costs less than an unscaled search over the same classes.
int search_knn(const Database& db, int hand, const Feature& query, int k, SearchMode mode, float eps,
               std::span<const unsigned char> class_mask, std::span<Match> out, std::span<const int> seeds = {},
               int max_checks = 0, std::span<const float> class_scale = {});

// Up to k of the given windows nearest to `query`, ranked as search_knn ranks
// (class_mask and class_scale likewise), without the index: duplicates and
// windows out of range or of a masked class are skipped. The continuation
// between two searches (Settings::search_interval). Returns the number written.
int rank_windows(const Database& db, int hand, const Feature& query, int k, std::span<const unsigned char> class_mask,
                 std::span<const int> windows, std::span<Match> out, std::span<const float> class_scale = {});

}  // namespace legwork::accent
