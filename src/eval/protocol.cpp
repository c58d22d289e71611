#include <legwork/eval/protocol.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace legwork::eval {
namespace fs = std::filesystem;

const char* protocol_key(Protocol p) {
  switch (p) {
    case Protocol::CrossSubject: return "cross_subject";
    case Protocol::CrossTrial: return "cross_trial";
    case Protocol::CrossDataset: return "cross_dataset";
  }
  return "?";
}

FoldPlan plan_folds(const Catalogue& data, Protocol p) {
  if (p == Protocol::CrossDataset) throw Error("plan_folds: cross-dataset needs a test catalogue");
  FoldPlan plan;
  for (const auto& cls : data.classes()) {
    std::vector<int> members;
    std::map<int, std::vector<int>> by_subject;
    for (int i = 0; i < static_cast<int>(data.trials.size()); ++i)
      if (data.trials[static_cast<std::size_t>(i)].cls == cls) {
        members.push_back(i);
        by_subject[data.trials[static_cast<std::size_t>(i)].subject].push_back(i);
      }
    if (p == Protocol::CrossSubject) {
      if (by_subject.size() < 2) {
        plan.skipped.emplace_back(cls, "only " + std::to_string(by_subject.size()) +
                                           " subject (leave-one-subject-out needs at least 2)");
        continue;
      }
      for (const auto& [subject, tests] : by_subject) {
        Fold f;
        f.protocol = p;
        f.cls = cls;
        f.held_out = "subject " + std::to_string(subject);
        f.held_out_subject = subject;
        f.test = tests;
        for (int i : members)
          if (data.trials[static_cast<std::size_t>(i)].subject != subject) f.database.push_back(i);
        plan.folds.push_back(std::move(f));
      }
    } else {
      if (members.size() < 2) {
        plan.skipped.emplace_back(cls, "only 1 trial (leave-one-trial-out needs at least 2)");
        continue;
      }
      for (int held : members) {
        Fold f;
        f.protocol = p;
        f.cls = cls;
        f.held_out = "trial " + data.trials[static_cast<std::size_t>(held)].id();
        f.test = {held};
        for (int i : members)
          if (i != held) f.database.push_back(i);
        plan.folds.push_back(std::move(f));
      }
    }
  }
  return plan;
}

FoldPlan plan_cross_dataset(const Catalogue& data, const Catalogue& test) {
  FoldPlan plan;
  const auto data_classes = data.classes();
  std::set<std::string> missing;
  for (int t = 0; t < static_cast<int>(test.trials.size()); ++t) {
    const auto& e = test.trials[static_cast<std::size_t>(t)];
    if (std::find(data_classes.begin(), data_classes.end(), e.cls) == data_classes.end()) {
      missing.insert(e.cls);
      continue;
    }
    Fold f;
    f.protocol = Protocol::CrossDataset;
    f.cls = e.cls;
    f.held_out = e.id();
    f.test = {t};
    for (int i = 0; i < static_cast<int>(data.trials.size()); ++i)
      if (data.trials[static_cast<std::size_t>(i)].cls == e.cls) f.database.push_back(i);
    plan.folds.push_back(std::move(f));
  }
  for (const auto& m : missing) plan.skipped.emplace_back(m, "the database folder has no trial of this class");
  return plan;
}

std::string fold_leak(const Fold& f, const Catalogue& data, const Catalogue& test) {
  for (int d : f.database) {
    const auto& e = data.trials[static_cast<std::size_t>(d)];
    if (f.protocol == Protocol::CrossSubject && e.subject == f.held_out_subject)
      return "database holds " + e.file + " of held-out subject " + std::to_string(e.subject);
    for (int t : f.test) {
      const auto& h = test.trials[static_cast<std::size_t>(t)];
      if (fs::weakly_canonical(h.path) == fs::weakly_canonical(e.path)) return "database holds held-out trial " + e.file;
    }
  }
  return "";
}

Catalogue quick_subset(const Catalogue& c, int per_class) {
  Catalogue q;
  q.root = c.root;
  for (const auto& cls : c.classes()) {
    // Round-robin over subjects so both protocols have material.
    std::map<int, std::vector<const TrialEntry*>> by_subject;
    for (const auto& t : c.trials)
      if (t.cls == cls) by_subject[t.subject].push_back(&t);
    int taken = 0;
    for (std::size_t round = 0; taken < per_class; ++round) {
      bool any = false;
      for (auto& [s, list] : by_subject)
        if (round < list.size() && taken < per_class) {
          q.trials.push_back(*list[round]);
          ++taken;
          any = true;
        }
      if (!any) break;
    }
  }
  return q;
}

std::vector<Protocol> parse_protocols(const std::string& names, bool have_test) {
  if (names.empty()) {
    if (have_test) return {Protocol::CrossDataset};
    return {Protocol::CrossSubject, Protocol::CrossTrial};
  }
  std::vector<Protocol> out;
  std::size_t start = 0;
  while (start <= names.size()) {
    const std::size_t end = std::min(names.find(',', start), names.size());
    const std::string p = names.substr(start, end - start);
    start = end + 1;
    if (p.empty()) continue;
    if (p == "cross_subject" || p == "cross-subject") out.push_back(Protocol::CrossSubject);
    else if (p == "cross_trial" || p == "cross-trial") out.push_back(Protocol::CrossTrial);
    else if (p == "cross_dataset" || p == "cross-dataset") out.push_back(Protocol::CrossDataset);
    else throw Error("--protocols: unknown protocol '" + p + "' (cross_subject, cross_trial, cross_dataset)");
  }
  return out;
}

}  // namespace legwork::eval
