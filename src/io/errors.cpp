#include <legwork/io/errors.hpp>

#include <legwork/core/types.hpp>

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <new>
#include <stdexcept>
#include <system_error>

namespace legwork::io {

std::string describe_exception(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const legwork::Error& e) {
    return e.what();
  } catch (const std::bad_alloc&) {
    return "out of memory: the input or an option asks for more than this machine can hold";
  } catch (const std::length_error&) {
    return "a size from the input or an option is larger than legwork can hold";
  } catch (const std::filesystem::filesystem_error& e) {
    std::string msg = e.path1().empty() ? std::string("file system") : e.path1().string();
    if (!e.path2().empty()) msg += " -> " + e.path2().string();
    return msg + ": " + e.code().message();
  } catch (const std::system_error& e) {
    return "system error: " + e.code().message();
  } catch (const nlohmann::json::exception& e) {
    // "[json.exception.type_error.316] invalid UTF-8 byte ..." -> the part after the tag.
    std::string what = e.what();
    if (const auto close = what.find("] "); what.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
      what.erase(0, close + 2);
    return "JSON data: " + what;
  } catch (const std::invalid_argument&) {
    return "a value that should be a number is not one (check the numeric options)";
  } catch (const std::out_of_range&) {
    return "a number or index is out of range (check the numeric options and frame ranges)";
  } catch (const std::exception& e) {
    const char* debug = std::getenv("LEGWORK_DEBUG");
    return std::string("internal error (please report it with the command line)") +
           (debug && *debug ? std::string(": ") + e.what() : std::string("; LEGWORK_DEBUG=1 shows details"));
  } catch (...) {
    return "internal error: unknown exception (please report it with the command line)";
  }
}

}  // namespace legwork::io
