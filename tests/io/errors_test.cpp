// What a person reads for an exception: never a library's raw text.
#include <legwork/io/errors.hpp>

#include <legwork/core/types.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <new>
#include <string>
#include <vector>

using namespace legwork;

namespace {
template <class Fn>
std::string described(Fn&& fn) {
  try {
    fn();
  } catch (...) {
    return io::describe_exception(std::current_exception());
  }
  return "";
}
}  // namespace

TEST(Errors, LibraryTextIsReplacedBySentences) {
  EXPECT_EQ(described([] { throw Error("walk.json:3: expected a number"); }), "walk.json:3: expected a number");
  EXPECT_EQ(described([] { throw std::bad_alloc(); }),
            "out of memory: the input or an option asks for more than this machine can hold");
  EXPECT_EQ(described([] { (void)std::stod("abc"); }), "a value that should be a number is not one (check the numeric options)");
  EXPECT_EQ(described([] { std::vector<int> v; v.reserve(v.max_size() + 1); }),
            "a size from the input or an option is larger than legwork can hold");
  const std::string fs = described([] { (void)std::filesystem::file_size("/nonexistent-legwork/x.bvh"); });
  EXPECT_EQ(fs, "/nonexistent-legwork/x.bvh: No such file or directory");
  const std::string js = described([] { const auto j = nlohmann::json::parse("{oops"); (void)j; });
  EXPECT_EQ(js.rfind("JSON data: parse error", 0), 0u) << js;
  EXPECT_EQ(js.find("[json.exception"), std::string::npos) << js;
}

TEST(Errors, UnexpectedExceptionsAskForAReportWithoutTheirText) {
  unsetenv("LEGWORK_DEBUG");
  EXPECT_EQ(described([] { throw std::runtime_error("vector::_M_fill_insert"); }),
            "internal error (please report it with the command line); LEGWORK_DEBUG=1 shows details");
  setenv("LEGWORK_DEBUG", "1", 1);
  EXPECT_EQ(described([] { throw std::runtime_error("vector::_M_fill_insert"); }),
            "internal error (please report it with the command line): vector::_M_fill_insert");
  unsetenv("LEGWORK_DEBUG");
}
