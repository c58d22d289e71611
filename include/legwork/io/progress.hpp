#pragma once
// Progress of long work for people: on a terminal a live bar redrawn in
// place ("what [#####.....] 3/10 item"); in a log (stderr not a terminal)
// whole lines, one at the start, at each tenth and at the end, so logs stay
// readable line by line.
#include <functional>
#include <string>

namespace legwork::io {

using ProgressPrinter = std::function<void(int done, int total, const std::string& item)>;

// `live`: -1 = decide from stderr (a terminal or not), 0 = lines, 1 = bar.
ProgressPrinter progress_printer(const std::string& what, int live = -1);

// Status lines of long work ("12/163 folds ..."): on a terminal the line is
// rewritten in place (with a bar when it holds "N/M folds"); in a log only
// fold lines and the last line of each phase ("N/N") are printed, whole.
using StatusPrinter = std::function<void(const std::string& line)>;
StatusPrinter status_printer(const std::string& prefix, int live = -1);

}  // namespace legwork::io
