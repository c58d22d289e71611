#pragma once
// Evaluation protocols of CoolMoves section 4.1 over a folder of BVH trials
// laid out like ../shared/data/cmu (MANIFEST.tsv with columns file, class,
// subject, trial; or DIR/bvh*/<class>/SS_TT.bvh without a manifest).
//   cross-subject: per class, leave one subject out: database = the class's
//                  trials of the other subjects, test = the held-out subject's;
//   cross-trial:   per class, leave one trial out: database = every other
//                  trial of the class (same subject included);
//   cross-dataset: database = a class's trials of one folder, test = every
//                  trial of that class in another folder.
// Offline code: allocates, throws legwork::Error naming the file/line at fault.
#include <legwork/io/catalogue.hpp>

#include <string>
#include <utility>
#include <vector>

namespace legwork::eval {

// The trial catalogue (manifest or folder layout) is shared with the database
// builder: see legwork/io/catalogue.hpp.
using io::Catalogue;
using io::read_catalogue;
using io::TrialEntry;

enum class Protocol { CrossSubject, CrossTrial, CrossDataset };
const char* protocol_key(Protocol p);  // "cross_subject", "cross_trial", "cross_dataset"
// Comma-separated protocol keys (or with '-' for '_'); empty = cross_dataset
// when there is a test set, else cross_subject and cross_trial. Throws
// legwork::Error naming --protocols for an unknown name.
std::vector<Protocol> parse_protocols(const std::string& names, bool have_test);

struct Fold {
  Protocol protocol = Protocol::CrossSubject;
  std::string cls;
  std::string held_out;       // "subject 16", "trial 16_21", or the test trial id
  int held_out_subject = -1;  // cross-subject: the subject left out
  std::vector<int> test;      // indices into the test catalogue (= the data catalogue except cross-dataset)
  std::vector<int> database;  // indices into the data catalogue
};

struct FoldPlan {
  std::vector<Fold> folds;
  std::vector<std::pair<std::string, std::string>> skipped;  // class, why it cannot be evaluated
};

FoldPlan plan_folds(const Catalogue& data, Protocol p);
// Cross-dataset: one fold per test trial whose class the data folder has.
FoldPlan plan_cross_dataset(const Catalogue& data, const Catalogue& test);

// A fold's database leaks if it holds the held-out subject (cross-subject) or
// a held-out trial (any protocol). Returns a description of the leak, or "".
std::string fold_leak(const Fold& f, const Catalogue& data, const Catalogue& test);

// --quick: at most `per_class` trials per class, spread over as many subjects
// as possible (for a CI smoke run).
Catalogue quick_subset(const Catalogue& c, int per_class);

}  // namespace legwork::eval
