#pragma once
// The message of the legwork::Error a call throws, or "(no error)": failure
// tests compare it with the exact text.
#include <legwork/core/types.hpp>

#include <string>
#include <utility>

namespace legwork::testdata {

template <class F>
std::string message_of(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace legwork::testdata
