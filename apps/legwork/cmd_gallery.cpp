// legwork gallery: an index.html over a folder of results (the demo's outputs).
#include "command.hpp"

#include <legwork/io/text.hpp>
#include <legwork/render/gallery.hpp>

#include <filesystem>
#include <memory>

namespace legwork::cli {
namespace {

void register_gallery(CLI::App& app) {
  auto* cmd = app.add_subcommand("gallery",
                                 "Write DIR/index.html showing every picture, video and result file under DIR\n"
                                 "(one section per sub-folder; captions from each folder's README.txt 'file: caption' lines).\n"
                                 "Example: legwork gallery demo-out");
  auto dir = std::make_shared<std::string>();
  auto title = std::make_shared<std::string>("legwork results");
  cmd->add_option("dir", *dir, "folder of results")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--title", *title, "page title");
  cmd->callback([dir, title] {
    const auto out = (std::filesystem::path(*dir) / "index.html").string();
    io::write_text_file(out, render::gallery_html(*dir, *title));
    announce("gallery", out);
  });
}

LEGWORK_COMMAND(register_gallery, 900);

}  // namespace
}  // namespace legwork::cli
