#pragma once
// A file written piece by piece, so that a long output is streamed instead of
// held whole (the BVH writer: a 10,000-step walk is ~100 MB of text).
#include <cstdio>
#include <string>
#include <string_view>

namespace legwork::io {

// The same messages as write_text_file: "<path>: is a directory, not a
// file", "<path>: cannot write file (<reason>)", "<path>: write failed (<reason>)".
class TextFileWriter {
 public:
  explicit TextFileWriter(const std::string& path);  // creates or truncates the file
  ~TextFileWriter();
  TextFileWriter(const TextFileWriter&) = delete;
  TextFileWriter& operator=(const TextFileWriter&) = delete;
  void write(std::string_view piece);  // throws naming the path if the write fails
  void close();                        // flushes; throws naming the path if that fails

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
};

}  // namespace legwork::io
