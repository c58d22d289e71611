// The KD-tree search index stored in the database block (format version 3;
// since version 7 over feature rows stored in each tree's leaf order;
// since version 4 one tree pair per class, no whole-database pair),
// so a database loads with its index in milliseconds instead of rebuilding
// the trees at every load.
//
// Section layout (little-endian, 64-bit), at FileHeader::index_offset:
//   IndexSection (32 bytes): tag "LWKDTREE", u32 nanoflann version, u32 node
//     bytes, u32 tree dimensions, u32 leaf size, u32 tree count, u32 0
//   TreeEntry[tree count]: u64 offset (from the section start), u64 bytes,
//     u64 points
//   the trees, 8-aligned: each nanoflann's saveIndex() output (point count,
//     dimensions, bounding box, leaf size, the point permutation, the nodes
//     in pre-order).
// Nothing declared in the section is trusted: every size is checked against
// the section's bytes and the class ranges, every point index and node is
// checked before nanoflann reads the tree (so a damaged file is refused with
// a message even when the checksum is not verified).
#include "database_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <sstream>

namespace legwork::accent {
namespace {

static_assert(sizeof(std::size_t) == 8, "the stored index assumes a 64-bit size_t");

constexpr char kIndexTag[8] = {'L', 'W', 'K', 'D', 'T', 'R', 'E', 'E'};
constexpr int kMaxTreeDepth = 64;  // a balanced tree of 2^32 points is about 32 deep

struct IndexSection {
  char tag[8];
  std::uint32_t nanoflann_version, node_bytes, tree_dim, leaf_size, tree_count, reserved;
};
static_assert(sizeof(IndexSection) == 32);
struct TreeEntry {
  std::uint64_t offset, bytes, points;
};
static_assert(sizeof(TreeEntry) == 24);

using Node = KdTree::Node;
constexpr std::uint32_t kNodeBytes = sizeof(Node);

[[noreturn]] void bad(const std::string& source, const std::string& what) {
  throw Error("accent database '" + source + "': search index " + what + "; rebuild it with 'legwork accent build'");
}

// The point ranges of the stored trees, in section order: per class (left,
// right hand); a one-class database's pair covers every window.
std::vector<std::pair<std::size_t, std::size_t>> tree_ranges(std::size_t windows,
                                                             const std::vector<std::pair<int, int>>& ranges) {
  if (ranges.size() <= 1) return std::vector<std::pair<std::size_t, std::size_t>>(2, {0, windows});
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (auto [a, b] : ranges)
    for (int hand = 0; hand < 2; ++hand) out.emplace_back(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
  return out;
}

// A bounded reader over one tree's bytes.
class Cursor {
 public:
  Cursor(std::span<const std::byte> s, const std::string& source, std::size_t tree)
      : s_(s), source_(source), tree_(tree) {}
  template <class T>
  T read(const char* what) {
    if (sizeof(T) > s_.size() - pos_) fail(std::string(what) + " runs past its end");
    T v;
    std::memcpy(&v, s_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  std::size_t left() const { return s_.size() - pos_; }
  std::size_t pos() const { return pos_; }
  void skip(std::size_t n) { pos_ += n; }
  const std::byte* here() const { return s_.data() + pos_; }
  [[noreturn]] void fail(const std::string& what) const { bad(source_, "tree " + std::to_string(tree_) + ": " + what); }

 private:
  std::span<const std::byte> s_;
  std::size_t pos_ = 0;
  const std::string& source_;
  std::size_t tree_;
};

// Where a stored tree's parts lie in its serialization (nanoflann's saveIndex:
// point count, dimensions, bounding box, leaf size, permutation, nodes).
struct TreeLayout {
  std::size_t bbox_at = 0, leaf_at = 0, perm_at = 0, nodes_at = 0;
};

// One tree's serialization, checked field by field against `points`.
TreeLayout check_tree(std::span<const std::byte> blob, std::size_t points, const std::string& source, std::size_t tree) {
  Cursor c(blob, source, tree);
  TreeLayout t;
  if (c.read<std::uint64_t>("point count") != points) c.fail("point count differs from its class's windows");
  if (c.read<std::int32_t>("dimensions") != kTreeDim) c.fail("dimension count differs");
  t.bbox_at = c.pos();
  for (int i = 0; i < 2 * kTreeDim; ++i)
    if (!std::isfinite(c.read<float>("bounding box"))) c.fail("bounding box is not finite");
  t.leaf_at = c.pos();
  const auto leaf = c.read<std::uint64_t>("leaf size");
  if (leaf == 0 || leaf > points + 1) c.fail("leaf size " + std::to_string(leaf) + " is invalid");
  if (c.read<std::uint64_t>("permutation size") != points) c.fail("permutation size differs from its point count");
  if (c.left() / 4 < points) c.fail("permutation runs past its end");
  t.perm_at = c.pos();
  // Since version 7 the builder stores the identity (rows in leaf order): one
  // sequential pass proves it is a permutation.
  std::uint32_t differs = 0;
  for (std::size_t i = 0; i < points; ++i) {
    std::uint32_t v;
    std::memcpy(&v, c.here() + 4 * i, 4);
    differs |= v ^ static_cast<std::uint32_t>(i);
  }
  if (differs == 0) {
    c.skip(4 * points);
    t.nodes_at = c.pos();
    return t;
  }
  std::vector<std::uint8_t> seen(points, 0);
  std::uint32_t out_of_range = 0;
  for (std::size_t i = 0; i < points; ++i) {
    std::uint32_t v;
    std::memcpy(&v, c.here() + 4 * i, 4);
    const bool inside = v < points;
    out_of_range |= !inside;
    seen[inside ? v : 0] = 1;
  }
  std::size_t distinct = 0;
  for (std::uint8_t s : seen) distinct += s;
  if (out_of_range || distinct != points) {  // name the first offending entry
    std::fill(seen.begin(), seen.end(), 0);
    for (std::size_t i = 0; i < points; ++i) {
      std::uint32_t v;
      std::memcpy(&v, c.here() + 4 * i, 4);
      if (v >= points || seen[v]) c.fail("permutation entry " + std::to_string(i) + " is out of range or repeated");
      seen[v] = 1;
    }
  }
  c.skip(4 * points);
  t.nodes_at = c.pos();
  return t;
}

// Copies the nodes (pre-order) into one pool allocation and links them,
// checking each as it goes: children both present or both absent, leaves
// inside the point range, split dimensions inside the tree's, bounded depth,
// and the nodes end exactly at the tree's last byte.
Node* link_nodes(KdTree& tree, Cursor& c, std::size_t points) {
  const std::size_t count = c.left() / sizeof(Node);
  if (count == 0) c.fail("node list runs past its end");
  Node* nodes = tree.pool.template allocate<Node>(count);
  std::memcpy(static_cast<void*>(nodes), c.here(), count * sizeof(Node));
  Node* root = nullptr;
  std::vector<std::pair<Node**, int>> todo{{&root, 0}};  // slots still to fill, with their depth
  todo.reserve(2 * kMaxTreeDepth + 4);
  std::size_t i = 0;
  while (!todo.empty()) {
    const auto [slot, at] = todo.back();
    todo.pop_back();
    if (at > kMaxTreeDepth) c.fail("deeper than " + std::to_string(kMaxTreeDepth) + " levels");
    if (i >= count) c.fail("node list runs past its end");
    if (i + 1 > 2 * points + 1) c.fail("has more nodes than its points allow");
    Node& n = nodes[i++];
    *slot = &n;
    const bool c1 = n.child1 != nullptr, c2 = n.child2 != nullptr;
    if (c1 != c2) c.fail("node " + std::to_string(i - 1) + " has one child");
    if (!c1) {
      if (!(n.node_type.lr.left <= n.node_type.lr.right && n.node_type.lr.right <= points))
        c.fail("leaf " + std::to_string(i - 1) + " points outside the tree's " + std::to_string(points) + " points");
      continue;
    }
    if (n.node_type.sub.divfeat < 0 || n.node_type.sub.divfeat >= kTreeDim || !std::isfinite(n.node_type.sub.divlow) ||
        !std::isfinite(n.node_type.sub.divhigh))
      c.fail("node " + std::to_string(i - 1) + " has an invalid split");
    todo.push_back({&n.child2, at + 1});  // read after child1's subtree
    todo.push_back({&n.child1, at + 1});
  }
  if (const std::size_t extra = c.left() - i * sizeof(Node); extra != 0)
    c.fail(std::to_string(extra) + " bytes after its last node");
  return root;
}

// Fills `tree` from a checked serialization directly (what nanoflann's
// loadIndex does through an istream, one node allocation and stream read per
// node): the permutation in one copy, the nodes in one pool allocation.
void fill_tree(KdTree& tree, std::span<const std::byte> blob, const TreeLayout& t, std::size_t points,
               const std::string& source, std::size_t index) {
  tree.m_size = points;
  tree.m_size_at_index_build = points;
  tree.dim = kTreeDim;
  std::memcpy(tree.root_bbox.data(), blob.data() + t.bbox_at, sizeof(tree.root_bbox));
  std::memcpy(&tree.m_leaf_max_size, blob.data() + t.leaf_at, sizeof(std::uint64_t));
  tree.vAcc.resize(points);
  std::memcpy(tree.vAcc.data(), blob.data() + t.perm_at, 4 * points);
  Cursor c(blob, source, index);
  c.skip(t.nodes_at);
  tree.root_node = link_nodes(tree, c, points);
}

// nanoflann's saveIndex writes each node as it lies in memory: its child
// pointers (heap addresses) and, in split nodes, the union's unused bytes.
// Both are rewritten so that the same database saves to the same bytes: a
// zeroed node with only its fields, children as the marker 1 (the loader
// only asks whether a child is there, then links the real ones).
void canonical_nodes(std::string& blob, std::size_t points, std::size_t tree) {
  const auto bytes = std::as_bytes(std::span(blob.data(), blob.size()));
  const TreeLayout layout = check_tree(bytes, points, "(being saved)", tree);
  Node* const there = reinterpret_cast<Node*>(std::uintptr_t{1});
  for (std::size_t at = layout.nodes_at; at + sizeof(Node) <= blob.size(); at += sizeof(Node)) {
    Node n, z;
    std::memcpy(static_cast<void*>(&n), blob.data() + at, sizeof(Node));
    std::memset(static_cast<void*>(&z), 0, sizeof(Node));
    if (n.child1 == nullptr && n.child2 == nullptr) {
      z.node_type.lr.left = n.node_type.lr.left;
      z.node_type.lr.right = n.node_type.lr.right;
    } else {
      z.node_type.sub.divfeat = n.node_type.sub.divfeat;
      z.node_type.sub.divlow = n.node_type.sub.divlow;
      z.node_type.sub.divhigh = n.node_type.sub.divhigh;
      z.child1 = n.child1 ? there : nullptr;
      z.child2 = n.child2 ? there : nullptr;
    }
    std::memcpy(blob.data() + at, static_cast<const void*>(&z), sizeof(Node));
  }
}

}  // namespace

std::vector<std::byte> serialize_index(const std::array<Feature*, 2>& features, std::size_t windows,
                                       const std::vector<std::pair<int, int>>& ranges,
                                       std::array<std::vector<std::uint32_t>, 2>& window_of_row) {
  const auto trees = tree_ranges(windows, ranges);
  for (auto& order : window_of_row) {
    order.resize(windows);
    for (std::size_t w = 0; w < windows; ++w) order[w] = static_cast<std::uint32_t>(w);
  }
  std::vector<std::string> blobs;
  std::vector<Feature> rows;
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const auto [a, b] = trees[t];
    if (a == b) {
      blobs.emplace_back();
      continue;
    }
    Feature* at = features[t % 2] + a;
    FeatureCloud cloud{reinterpret_cast<const float*>(at), b - a};
    KdTree tree(kTreeDim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(kIndexLeafSize));
    // Rows into the tree's leaf order: row a + i takes the point the tree
    // visits i-th, and the permutation becomes the identity (the nodes' leaf
    // ranges index the permutation, so they stay valid).
    rows.assign(at, at + (b - a));
    auto& order = window_of_row[t % 2];
    for (std::size_t i = 0; i < b - a; ++i) {
      at[i] = rows[tree.vAcc[i]];
      order[a + i] = static_cast<std::uint32_t>(a + tree.vAcc[i]);
      tree.vAcc[i] = static_cast<std::uint32_t>(i);
    }
    std::ostringstream out(std::ios::binary);
    tree.saveIndex(out);
    blobs.push_back(std::move(out).str());
    canonical_nodes(blobs.back(), b - a, t);
  }
  IndexSection h{};
  std::memcpy(h.tag, kIndexTag, sizeof kIndexTag);
  h.nanoflann_version = NANOFLANN_VERSION;
  h.node_bytes = kNodeBytes;
  h.tree_dim = kTreeDim;
  h.leaf_size = kIndexLeafSize;
  h.tree_count = static_cast<std::uint32_t>(trees.size());
  std::vector<TreeEntry> entries(trees.size());
  std::size_t at = sizeof h + entries.size() * sizeof(TreeEntry);
  for (std::size_t t = 0; t < trees.size(); ++t) {
    at = (at + 7) & ~std::size_t{7};
    entries[t] = {at, blobs[t].size(), trees[t].second - trees[t].first};
    at += blobs[t].size();
  }
  std::vector<std::byte> out(at);
  std::memcpy(out.data(), &h, sizeof h);
  for (std::size_t t = 0; t < trees.size(); ++t)
    std::memcpy(out.data() + sizeof h + t * sizeof(TreeEntry), &entries[t], sizeof(TreeEntry));
  for (std::size_t t = 0; t < trees.size(); ++t)
    if (!blobs[t].empty()) std::memcpy(out.data() + entries[t].offset, blobs[t].data(), blobs[t].size());
  return out;
}

bool load_index(Database::Impl& d, std::span<const std::byte> section, const std::string& source) {
  IndexSection h;
  if (section.size() < sizeof h) bad(source, "section is " + std::to_string(section.size()) + " bytes (truncated)");
  std::memcpy(&h, section.data(), sizeof h);
  if (std::memcmp(h.tag, kIndexTag, sizeof kIndexTag) != 0) bad(source, "section has no index tag");
  if (h.nanoflann_version != NANOFLANN_VERSION || h.node_bytes != kNodeBytes || h.tree_dim != kTreeDim) return false;
  const auto trees = tree_ranges(d.header.window_count, d.meta.ranges);
  if (h.tree_count != trees.size())
    bad(source, "holds " + std::to_string(h.tree_count) + " trees, expected " + std::to_string(trees.size()));
  if ((section.size() - sizeof h) / sizeof(TreeEntry) < trees.size()) bad(source, "tree table runs past the section");
  std::vector<TreeEntry> entries(trees.size());
  std::vector<TreeLayout> layouts(trees.size());
  for (std::size_t t = 0; t < trees.size(); ++t)
    std::memcpy(&entries[t], section.data() + sizeof h + t * sizeof(TreeEntry), sizeof(TreeEntry));
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const TreeEntry& e = entries[t];
    const std::size_t points = trees[t].second - trees[t].first;
    if (e.points != points) bad(source, "tree " + std::to_string(t) + " declares " + std::to_string(e.points) + " points, its class has " + std::to_string(points));
    if (e.offset > section.size() || e.bytes > section.size() - e.offset)
      bad(source, "tree " + std::to_string(t) + " lies outside the section (truncated?)");
    if ((points == 0) != (e.bytes == 0)) bad(source, "tree " + std::to_string(t) + " is empty but its class is not, or the reverse");
    if (points) layouts[t] = check_tree(section.subspan(e.offset, e.bytes), points, source, t);
  }
  d.index.clear();
  d.index.resize(d.meta.classes.size());
  d.all = ClassIndex{};
  d.leaf_size = static_cast<int>(h.leaf_size);
  d.indexed = true;
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const std::size_t hand = t % 2;
    ClassIndex& ci = d.meta.classes.size() <= 1 ? d.all : d.index[t / 2];
    ci.cloud[hand] = {reinterpret_cast<const float*>(d.features[hand] + trees[t].first), trees[t].second - trees[t].first};
    if (entries[t].bytes == 0) continue;
    ci.tree[hand] = std::make_unique<KdTree>(kTreeDim, ci.cloud[hand],
                                             nanoflann::KDTreeSingleIndexAdaptorParams(h.leaf_size, nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex));
    fill_tree(*ci.tree[hand], section.subspan(entries[t].offset, entries[t].bytes), layouts[t], ci.cloud[hand].count,
              source, t);
  }
  return true;
}

}  // namespace legwork::accent
