#pragma once
// HTTP side of `legwork serve`: static files and the JSON API (private header).
#include <legwork/serve/methods.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace legwork::serve {

struct HttpReply {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
};

struct ApiContext {
  Resources resources;
  std::vector<std::string> classes;  // database classes
  std::string web_dir, trials_dir;
};

// GET/HEAD `target` (path + query). Never throws: errors are JSON replies
// {"type":"error","code":...,"message":...} with 400/404/405/500.
HttpReply handle_http(const ApiContext& ctx, std::string_view method, std::string_view target);

// Trial names (relative paths without .bvh) under dir, sorted.
std::vector<std::string> list_trials(const std::string& dir);

}  // namespace legwork::serve
