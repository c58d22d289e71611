#include <legwork/core/skeleton.hpp>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <unordered_map>

namespace legwork {

namespace {
constexpr std::string_view kRoleNames[kRoleCount] = {
    "pelvis",         "spine",         "chest",           "neck",       "head",
    "left_clavicle",  "left_shoulder", "left_elbow",      "left_hand",  "right_clavicle",
    "right_shoulder", "right_elbow",   "right_hand",      "left_hip",   "left_knee",
    "left_ankle",     "left_toe",      "right_hip",       "right_knee", "right_ankle",
    "right_toe"};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Name without a namespace prefix such as "mixamorig:" (or three.js's
// "mixamorig" with the colon removed from node names: "mixamorigHips").
std::string_view strip_namespace(std::string_view name) {
  auto colon = name.rfind(':');
  if (colon != std::string_view::npos) return name.substr(colon + 1);
  constexpr std::string_view kMixamo = "mixamorig";
  if (name.size() > kMixamo.size() && name.substr(0, kMixamo.size()) == kMixamo &&
      std::isupper(static_cast<unsigned char>(name[kMixamo.size()])))
    return name.substr(kMixamo.size());
  return name;
}

enum class Side { Centre, Left, Right };

struct SideSplit {
  Side side = Side::Centre;
  std::string base;         // lower-case name without the side token
  std::string counterpart;  // same name with the other side's token
};

bool upper_or_sep(char c) {
  return std::isupper(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == ' ' || c == '-';
}

// Recognises Left*/Right*, left_/right_, L*/R* (LHipJoint), l*/r* (lThigh),
// L_/R_, *_l/*_r, *.L/*.R, *_Left/*_Right.
SideSplit split_side(std::string_view full) {
  std::string_view ns = full.substr(0, full.size() - strip_namespace(full).size());
  std::string name(strip_namespace(full));
  SideSplit out;
  auto finish = [&](Side s, std::string base, std::string other) {
    out.side = s;
    out.base = lower(base);
    while (!out.base.empty() && (out.base.front() == '_' || out.base.front() == '.' ||
                                 out.base.front() == ' ' || out.base.front() == '-'))
      out.base.erase(out.base.begin());
    while (!out.base.empty() && (out.base.back() == '_' || out.base.back() == '.' ||
                                 out.base.back() == ' ' || out.base.back() == '-'))
      out.base.pop_back();
    out.counterpart = std::string(ns) + other;
    return out;
  };
  const std::string lname = lower(name);
  // Whole words first.
  for (auto [word, other_word, side] :
       {std::tuple{"left", "right", Side::Left}, std::tuple{"right", "left", Side::Right}}) {
    std::string w = word;
    if (lname.rfind(w, 0) == 0) {
      std::string other = name;
      std::string rep = other_word;
      if (std::isupper(static_cast<unsigned char>(name[0]))) rep[0] = static_cast<char>(std::toupper(rep[0]));
      if (name.size() > 1 && std::isupper(static_cast<unsigned char>(name[1])))
        for (char& c : rep) c = static_cast<char>(std::toupper(c));
      other.replace(0, w.size(), rep);
      return finish(side, name.substr(w.size()), other);
    }
    if (lname.size() > w.size() && lname.compare(lname.size() - w.size(), w.size(), w) == 0 &&
        upper_or_sep(name[name.size() - w.size() - 1])) {
      std::string other = name;
      std::string rep = other_word;
      if (std::isupper(static_cast<unsigned char>(name[name.size() - w.size()])))
        rep[0] = static_cast<char>(std::toupper(rep[0]));
      other.replace(name.size() - w.size(), w.size(), rep);
      return finish(side, name.substr(0, name.size() - w.size()), other);
    }
  }
  // Single-letter prefix followed by a capital or a separator: LHipJoint, lThigh, L_arm.
  if (name.size() > 1 && (name[0] == 'L' || name[0] == 'R' || name[0] == 'l' || name[0] == 'r') &&
      upper_or_sep(name[1])) {
    const bool left = name[0] == 'L' || name[0] == 'l';
    std::string other = name;
    other[0] = left ? (name[0] == 'L' ? 'R' : 'r') : (name[0] == 'R' ? 'L' : 'l');
    return finish(left ? Side::Left : Side::Right, name.substr(1), other);
  }
  // Single-letter suffix after a separator: arm_l, arm.R.
  if (name.size() > 2) {
    char sep = name[name.size() - 2], c = name.back();
    if ((sep == '_' || sep == '.' || sep == ' ') && (c == 'L' || c == 'R' || c == 'l' || c == 'r')) {
      const bool left = c == 'L' || c == 'l';
      std::string other = name;
      other.back() = left ? (c == 'L' ? 'R' : 'r') : (c == 'R' ? 'L' : 'l');
      return finish(left ? Side::Left : Side::Right, name.substr(0, name.size() - 2), other);
    }
  }
  out.base = lname;
  return out;
}

bool base_is(const std::string& base, std::initializer_list<std::string_view> words) {
  for (auto w : words)
    if (base == w) return true;
  return false;
}

bool base_has(const std::string& base, std::initializer_list<std::string_view> words) {
  for (auto w : words)
    if (base.find(w) != std::string::npos) return true;
  return false;
}

// Depth of every joint in one pass (parents come before their children);
// a parent index that breaks that order is walked up, with a step bound.
std::vector<int> joint_depths(const Skeleton& s) {
  const int n = s.joint_count();
  std::vector<int> depth(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j) {
    const int p = s.parents[static_cast<std::size_t>(j)];
    if (p < 0) continue;
    if (p < j) {
      depth[static_cast<std::size_t>(j)] = depth[static_cast<std::size_t>(p)] + 1;
      continue;
    }
    int d = 0;
    for (int k = j; k >= 0 && k < n && d <= n; k = s.parents[static_cast<std::size_t>(k)]) ++d;
    depth[static_cast<std::size_t>(j)] = d - 1;
  }
  return depth;
}

// Shallowest joint on `side` whose base name is one of `exact` (or, failing
// that, contains one of `fuzzy` and none of the excluded words).
int find_sided(const Skeleton& s, const std::vector<SideSplit>& split, const std::vector<int>& depth, Side side,
               std::initializer_list<std::string_view> exact,
               std::initializer_list<std::string_view> fuzzy) {
  int best = -1, best_depth = 1 << 30;
  for (int pass = 0; pass < 2 && best < 0; ++pass) {
    for (int j = 0; j < s.joint_count(); ++j) {
      const auto& sp = split[static_cast<std::size_t>(j)];
      if (sp.side != side) continue;
      bool ok = pass == 0 ? base_is(sp.base, exact)
                          : base_has(sp.base, fuzzy) &&
                                !base_has(sp.base, {"end", "index", "thumb", "finger", "pinky",
                                                    "middle", "ring", "toe", "site"});
      const int d = depth[static_cast<std::size_t>(j)];
      if (ok && d < best_depth) best = j, best_depth = d;
    }
  }
  return best;
}

int parent_of(const Skeleton& s, int j) { return j < 0 ? -1 : s.parents[static_cast<std::size_t>(j)]; }

}  // namespace

std::string_view role_name(Role r) { return kRoleNames[static_cast<int>(r)]; }

bool role_is_required(Role r) {
  return r != Role::LeftClavicle && r != Role::RightClavicle && r != Role::LeftToe &&
         r != Role::RightToe && r != Role::Chest && r != Role::Spine;
}

int Skeleton::find(std::string_view name) const {
  for (int j = 0; j < joint_count(); ++j)
    if (names[static_cast<std::size_t>(j)] == name) return j;
  return -1;
}

int Skeleton::require(std::string_view name) const {
  int j = find(name);
  if (j < 0) {
    std::ostringstream os;
    os << "unknown joint '" << name << "'; the skeleton has:";
    for (const auto& n : names) os << ' ' << n;
    throw Error(os.str());
  }
  return j;
}

std::vector<int> Skeleton::children(int j) const {
  std::vector<int> out;
  for (int i = 0; i < joint_count(); ++i)
    if (parents[static_cast<std::size_t>(i)] == j) out.push_back(i);
  return out;
}

bool Skeleton::is_ancestor(int ancestor, int j) const {
  for (; j >= 0; j = parents[static_cast<std::size_t>(j)])
    if (j == ancestor) return true;
  return false;
}

int Skeleton::add_joint(std::string name, int parent, const Vec3& offset) {
  if (parent >= joint_count()) throw Error("add_joint: parent index out of range for " + name);
  names.push_back(std::move(name));
  parents.push_back(parent);
  rest_offsets.push_back(offset);
  end_sites.push_back(Vec3::Zero());
  has_end_site.push_back(0);
  mirror.push_back(joint_count() - 1);
  return joint_count() - 1;
}

void Skeleton::validate() const {
  const auto n = names.size();
  if (n == 0) throw Error("skeleton has no joints");
  if (parents.size() != n || rest_offsets.size() != n || end_sites.size() != n ||
      has_end_site.size() != n)
    throw Error("skeleton arrays have inconsistent sizes");
  if (parents[0] != -1) throw Error("skeleton joint 0 ('" + names[0] + "') must be the root");
  for (std::size_t j = 1; j < n; ++j) {
    if (parents[j] < 0 || static_cast<std::size_t>(parents[j]) >= j)
      throw Error("skeleton joint '" + names[j] + "' is not in depth-first order (parent index " +
                  std::to_string(parents[j]) + ")");
  }
  for (std::size_t j = 0; j < n; ++j)
    if (!rest_offsets[j].allFinite()) throw Error("skeleton joint '" + names[j] + "' has a non-finite offset");
}

void Skeleton::scale(double s) {
  for (auto& o : rest_offsets) o *= s;
  for (auto& e : end_sites) e *= s;
}

namespace {

// Mirror pairs: a sided joint whose counterpart name exists. Unpaired sided
// joints become central in `split`. A name index keeps this linear in the
// joint count (first joint of each name, as Skeleton::find).
void resolve_mirrors(Skeleton& skel, std::vector<SideSplit>& split) {
  const int n = skel.joint_count();
  std::unordered_map<std::string_view, int> index;
  index.reserve(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) index.emplace(skel.names[static_cast<std::size_t>(j)], j);
  skel.mirror.assign(static_cast<std::size_t>(n), 0);
  for (int j = 0; j < n; ++j) {
    const auto& sp = split[static_cast<std::size_t>(j)];
    const auto found = sp.side == Side::Centre ? index.end() : index.find(sp.counterpart);
    const int other = found == index.end() ? -1 : found->second;
    skel.mirror[static_cast<std::size_t>(j)] = other >= 0 ? other : j;
    if (other < 0) split[static_cast<std::size_t>(j)].side = Side::Centre;  // unpaired: treat as central
  }
}

// Limbs: end joints by name, the rest of each chain by hierarchy.
void resolve_limbs(const Skeleton& skel, const std::vector<SideSplit>& split, const std::vector<int>& depth,
                   JointRoles& r) {
  for (auto [side, hand, elbow, shoulder, clav, ankle, knee, hip, toe] :
       {std::tuple{Side::Left, Role::LeftHand, Role::LeftElbow, Role::LeftShoulder, Role::LeftClavicle,
                   Role::LeftAnkle, Role::LeftKnee, Role::LeftHip, Role::LeftToe},
        std::tuple{Side::Right, Role::RightHand, Role::RightElbow, Role::RightShoulder,
                   Role::RightClavicle, Role::RightAnkle, Role::RightKnee, Role::RightHip, Role::RightToe}}) {
    int h = find_sided(skel, split, depth, side, {"hand", "wrist"}, {"hand", "wrist"});
    if (h >= 0) {
      r[hand] = h;
      r[elbow] = parent_of(skel, h);
      r[shoulder] = parent_of(skel, r[elbow]);
      int c = parent_of(skel, r[shoulder]);
      if (c >= 0 && split[static_cast<std::size_t>(c)].side == side) r[clav] = c;
    }
    int a = find_sided(skel, split, depth, side, {"foot", "ankle"}, {"foot", "ankle"});
    if (a >= 0) {
      r[ankle] = a;
      r[knee] = parent_of(skel, a);
      r[hip] = parent_of(skel, r[knee]);
      const auto ch = skel.children(a);
      for (int c : ch) {
        const auto& b = split[static_cast<std::size_t>(c)].base;
        if (base_has(b, {"toe", "ball"})) { r[toe] = c; break; }
      }
      if (r[toe] < 0 && !ch.empty()) r[toe] = ch.front();
    }
  }
}

// Pelvis: the deepest common ancestor of both hips (usually the root; side
// joints such as CMU's LHipJoint are skipped, being ancestors of one hip only).
int common_ancestor(const Skeleton& skel, int a, int b) {
  std::vector<unsigned char> above_b(skel.parents.size(), 0);
  for (int p = b, steps = 0; p >= 0 && steps <= skel.joint_count(); p = parent_of(skel, p), ++steps)
    above_b[static_cast<std::size_t>(p)] = 1;
  int p = a;
  for (int steps = 0; p >= 0 && !above_b[static_cast<std::size_t>(p)] && steps <= skel.joint_count(); ++steps)
    p = parent_of(skel, p);
  return p >= 0 && above_b[static_cast<std::size_t>(p)] ? p : -1;
}

// Head, pelvis, neck and the spine chain between them.
void resolve_trunk(const Skeleton& skel, const std::vector<SideSplit>& split, const std::vector<int>& depth,
                   JointRoles& r) {
  const int n = skel.joint_count();
  // Head: exact "head", else a central joint containing "head" (not HeadTop_End).
  int head = -1, best_depth = 1 << 30;
  for (int pass = 0; pass < 2 && head < 0; ++pass)
    for (int j = 0; j < n; ++j) {
      const auto& sp = split[static_cast<std::size_t>(j)];
      if (sp.side != Side::Centre) continue;
      bool ok = pass == 0 ? sp.base == "head" : base_has(sp.base, {"head"}) && !base_has(sp.base, {"end", "top", "site"});
      if (ok && depth[static_cast<std::size_t>(j)] < best_depth) head = j, best_depth = depth[static_cast<std::size_t>(j)];
    }
  r[Role::Head] = head;
  const int lh = r[Role::LeftHip], rh = r[Role::RightHip];
  r[Role::Pelvis] = lh >= 0 && rh >= 0 ? common_ancestor(skel, lh, rh) : 0;
  if (head < 0) return;
  // Neck: lowest joint named *neck* between pelvis and head.
  std::vector<int> path;  // head's ancestors below pelvis, top-down order reversed later
  for (int j = parent_of(skel, head); j >= 0 && j != r[Role::Pelvis] && static_cast<int>(path.size()) < n;
       j = parent_of(skel, j))
    path.push_back(j);
  std::reverse(path.begin(), path.end());  // bottom-up from just above the pelvis
  int neck = -1;
  for (int j : path)
    if (base_has(split[static_cast<std::size_t>(j)].base, {"neck"})) { neck = j; break; }
  if (neck < 0 && !path.empty()) neck = path.back();
  r[Role::Neck] = neck;
  for (int j : path) {
    if (j == neck) break;
    r.spine_chain.push_back(j);
  }
  if (!r.spine_chain.empty()) {
    r[Role::Spine] = r.spine_chain.front();
    r[Role::Chest] = r.spine_chain.back();
  }
}

}  // namespace

// Linear in the joint count (names are indexed, depths computed once), so a
// 100,000-joint skeleton resolves as fast as it is read.
std::vector<Role> resolve_roles(Skeleton& skel) {
  const int n = skel.joint_count();
  std::vector<SideSplit> split(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) split[static_cast<std::size_t>(j)] = split_side(skel.names[static_cast<std::size_t>(j)]);
  const std::vector<int> depth = joint_depths(skel);
  resolve_mirrors(skel, split);
  JointRoles r;
  resolve_limbs(skel, split, depth, r);
  resolve_trunk(skel, split, depth, r);
  skel.roles = r;
  std::vector<Role> missing;
  for (int i = 0; i < kRoleCount; ++i)
    if (r.joint[static_cast<std::size_t>(i)] < 0) missing.push_back(static_cast<Role>(i));
  return missing;
}

void require_roles(Skeleton& skel, std::string_view what) {
  auto missing = resolve_roles(skel);
  std::ostringstream os;
  bool any = false;
  for (Role m : missing)
    if (role_is_required(m)) {
      os << (any ? ", " : "") << role_name(m);
      any = true;
    }
  if (!any) return;
  std::ostringstream msg;
  msg << what << ": cannot resolve joint roles: " << os.str()
      << ". Joints are:";
  for (const auto& nm : skel.names) msg << ' ' << nm;
  msg << ". Known naming schemes: CMU (LeftUpLeg/LeftLeg/LeftFoot), Mixamo (mixamorig:), DAZ "
         "(lThigh/lShin/lFoot), Left*/Right*, L_/R_, l*/r*, *_l/*_r.";
  throw Error(msg.str());
}

}  // namespace legwork
