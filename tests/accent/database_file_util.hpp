#pragma once
// Helpers for the database file tests (database_file_test.cpp,
// database_index_test.cpp): temp files, raw blocks, re-checksummed writes.
#include <legwork/accent/database.hpp>
#include <legwork/io/text.hpp>

#include "../../src/accent/database_impl.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace legwork::accent {
namespace fs = std::filesystem;

inline fs::path temp_dir() {
  const auto d = fs::temp_directory_path() / "legwork_database_file_test";
  fs::create_directories(d);
  return d;
}

inline std::vector<std::byte> read_all(const fs::path& p) {
  const std::string bytes = io::read_binary_file(p.string());
  const auto* b = reinterpret_cast<const std::byte*>(bytes.data());
  return {b, b + bytes.size()};
}

// Writes `block` with its checksum recomputed, as a valid-looking file would be.
inline void write_with_checksum(const fs::path& p, std::vector<std::byte> block) {
  FileHeader h;
  std::memcpy(&h, block.data(), sizeof h);
  h.checksum = 0;
  std::memcpy(block.data(), &h, sizeof h);
  h.checksum = block_checksum(block);
  std::memcpy(block.data(), &h, sizeof h);
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(block.size()));
}

inline std::string load_error(const fs::path& p) {
  try {
    (void)load_database(p.string());
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace legwork::accent
