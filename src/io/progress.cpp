#include <legwork/io/progress.hpp>

#include <cstdio>
#include <algorithm>
#include <memory>
#include <regex>
#include <string>
#include <unistd.h>

namespace legwork::io {

ProgressPrinter progress_printer(const std::string& what, int live) {
  const bool bar = live < 0 ? ::isatty(STDERR_FILENO) != 0 : live > 0;
  if (bar) {
    return [what](int done, int total, const std::string& item) {
      const int width = 30;
      const int filled = total > 0 ? std::min(done, total) * width / total : width;
      std::fprintf(stderr, "\r%s [%s%s] %d/%d %-40.40s", what.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done, total, item.c_str());
      if (done >= total) std::fprintf(stderr, "\n");
      std::fflush(stderr);
    };
  }
  auto last_tenth = std::make_shared<int>(-1);
  return [what, last_tenth](int done, int total, const std::string& item) {
    const int tenth = total > 0 ? std::min(done, total) * 10 / total : 10;
    if (tenth == *last_tenth && done < total) return;
    *last_tenth = tenth;
    std::fprintf(stderr, "%s: %d/%d%s%s\n", what.c_str(), done, total, item.empty() ? "" : " ", item.c_str());
    std::fflush(stderr);
  };
}

StatusPrinter status_printer(const std::string& prefix, int live) {
  const bool tty = live < 0 ? ::isatty(STDERR_FILENO) != 0 : live > 0;
  return [tty, prefix](const std::string& line) {
    if (tty) {
      // A bar for the fold phase: "[#####.....] 12/163 folds ...".
      static const std::regex folds(R"((\d+)/(\d+) folds)");
      std::smatch m;
      std::string bar;
      if (std::regex_search(line, m, folds)) {
        const double f = std::stod(m[1].str()) / std::max(1.0, std::stod(m[2].str()));
        const int n = static_cast<int>(f * 20.0 + 0.5);
        bar = "[" + std::string(static_cast<std::size_t>(n), '#') + std::string(static_cast<std::size_t>(20 - n), '.') + "] ";
      }
      std::fprintf(stderr, "\r%s%s%s\x1b[K", prefix.c_str(), bar.c_str(), line.c_str());
    } else {
      // Only fold lines and the last line of each loading/preparing phase ("N/N").
      static const std::regex done_phase(R"((\d+)/\1\b)");
      const bool fold = line.find(" folds ") != std::string::npos;
      const bool phase_end = std::regex_search(line, done_phase);
      if (fold || phase_end) std::fprintf(stderr, "%s%s\n", prefix.c_str(), line.c_str());
    }
    std::fflush(stderr);
  };
}

}  // namespace legwork::io
