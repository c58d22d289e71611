// legwork eval combined: one avatar with an accentuated (or IK) upper body and
// walking-in-place legs, measured on walking trials (eval/combined.hpp).
#include "command.hpp"

#include <legwork/eval/combined.hpp>
#include <legwork/io/data_files.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace legwork::cli {
namespace {

struct CombinedArgs {
  std::string data, db, out, video, wip_table;
  int limit = 0;
};

void register_eval_combined(CLI::App& app) {
  auto* group = app.get_subcommand("eval");
  auto* cmd = group->add_subcommand(
      "combined",
      "One avatar, two sources: the upper body from head + hands (IK avatar, or accentuation with --db) and the legs\n"
      "from walking-in-place on the ankles, scored on walking trials against the capture beside the upper-body method\n"
      "alone (full body, lower body, hands, foot skating). Writes report.md and report.json with --out.\n"
      "Example: legwork eval combined --data ../shared/data/cmu/bvh/walking --db all.lwdb --out combined-eval");
  auto a = std::make_shared<CombinedArgs>();
  cmd->add_option("--data", a->data, "folder of walking BVH trials (default ../shared/data/cmu/bvh/walking, else data/cmu/bvh/walking)");
  cmd->add_option("--db", a->db, "database (.lwdb) for the accentuated upper body (the trials may be in it: say so when you report)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--wip-table", a->wip_table,
                  "learned walking-in-place table for the learned-legs rows of every trial (`legwork wip learn`, e.g. with "
                  "--exclude-subjects naming the evaluated ones; default: each trial's table learned from the other subjects in --data)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--limit", a->limit, "evaluate only the first N trials")->check(positive_number());
  output_file(cmd->add_option("--video", a->video, "MP4 of the first trial: the capture beside each method"));
  cmd->add_option("--out", a->out, "write report.md and report.json into this folder");
  cmd->callback([a] {
    std::string note;
    const std::filesystem::path data = a->data.empty() ? io::walking_data(&note) : std::filesystem::path(a->data);
    if (!std::filesystem::is_directory(data)) throw Error("--data '" + data.string() + "' is not a directory");
    if (!a->video.empty()) require_extension("--video", a->video, {".mp4"});
    if (!a->out.empty()) std::filesystem::create_directory(io::prepare_output(a->out, "--out"));  // the folder itself, as asked
    if (!note.empty()) std::cerr << "legwork eval combined: note: " << note << "\n";
    eval::CombinedEvalRun run;
    for (const auto& e : std::filesystem::directory_iterator(data))
      if (io::extension_of(e.path().string()) == ".bvh") run.files.push_back(e.path().string());
    std::sort(run.files.begin(), run.files.end());
    if (a->limit > 0 && static_cast<int>(run.files.size()) > a->limit) run.files.resize(static_cast<std::size_t>(a->limit));
    if (run.files.empty()) throw Error("--data '" + data.string() + "' holds no .bvh files");
    run.database = a->db;
    run.video = a->video;
    run.wip_table = a->wip_table;
    run.progress = progress_bar("legwork eval combined: trial");
    const auto report = eval::evaluate_combined(run);
    const std::string table = eval::combined_table(report);
    std::printf("%zu trials at %.0f Hz (%zu skipped)\n%s", report["trials"].size(), report["rate_hz"].get<double>(),
                report["skipped"].size(), table.c_str());
    if (!a->video.empty()) announce("video", a->video);
    if (a->out.empty()) return;
    io::write_text_file(a->out + "/report.json", report.dump(2) + "\n");
    io::write_text_file(a->out + "/report.md", "# One avatar, two sources\n\n" + std::to_string(report["trials"].size()) +
                                                   " walking trials; the upper body from head + hands, the legs from "
                                                   "walking-in-place on the ankles (`legwork eval combined`).\n\n" + table);
    announce("report", a->out + "/report.md");
    announce("report", a->out + "/report.json");
  });
}

LEGWORK_COMMAND(register_eval_combined, 91);

}  // namespace
}  // namespace legwork::cli
