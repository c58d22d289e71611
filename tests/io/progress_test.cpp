// Progress for people: a live bar on a terminal, whole lines in logs.
#include <legwork/io/progress.hpp>

#include <gtest/gtest.h>

#include <algorithm>

using namespace legwork;

TEST(Progress, LogsGetWholeLinesAtTenthsNotCarriageReturns) {
  testing::internal::CaptureStderr();
  const auto p = io::progress_printer("reading", 0);
  for (int i = 0; i <= 100; ++i) p(i, 100, "trial_" + std::to_string(i));
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out.find('\r'), std::string::npos);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 11) << out;  // 0, 10 %, ..., 100 %
  EXPECT_NE(out.find("reading: 50/100 trial_50\n"), std::string::npos) << out;
  EXPECT_NE(out.find("reading: 100/100 trial_100\n"), std::string::npos) << out;
}

TEST(Progress, TerminalsGetOneBarRedrawnInPlace) {
  testing::internal::CaptureStderr();
  const auto p = io::progress_printer("building", 1);
  for (int i = 0; i <= 4; ++i) p(i, 4, "");
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(std::count(out.begin(), out.end(), '\r'), 5);
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1);  // only when done
  EXPECT_NE(out.find("building [###############...............] 2/4"), std::string::npos) << out;
}

TEST(Progress, StatusLinesInLogsKeepFoldsAndPhaseEnds) {
  testing::internal::CaptureStderr();
  const auto p = io::status_printer("[eval] ", 0);
  p("loading 1/3 trials");
  p("loading 3/3 trials");
  p("12/163 folds cross_subject boxing");
  const std::string out = testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "[eval] loading 3/3 trials\n[eval] 12/163 folds cross_subject boxing\n");
}
