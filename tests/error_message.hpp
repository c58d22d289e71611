#pragma once
// The message of the legwork::Error a call throws, for tests that check the
// exact text of an error.
#include <legwork/core/types.hpp>

#include <string>

namespace legwork::testdata {

// What fn() throws as legwork::Error, or "(no error)" when it returns.
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace legwork::testdata
