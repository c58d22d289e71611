// legwork gallery: an index.html over a folder of results (the demo's outputs).
#include "command.hpp"

#include <legwork/io/text.hpp>
#include <legwork/render/gallery.hpp>

#include <cstdio>
#include <filesystem>
#include <memory>

namespace legwork::cli {
namespace {

void register_gallery(CLI::App& app) {
  auto* cmd = app.add_subcommand("gallery",
                                 "Write DIR/index.html showing every picture, video and result file under DIR:\n"
                                 "one section per sub-folder (in the order of DIR/README.txt's 'folder/: Heading - intro'\n"
                                 "lines), captions from each folder's README.txt 'file: caption' lines, the command that\n"
                                 "made each file from DIR/commands.txt, video posters (ffmpeg), and a page of its own\n"
                                 "for every folder inside a section.\n"
                                 "Example: legwork gallery demo-out");
  auto dir = std::make_shared<std::string>();
  auto title = std::make_shared<std::string>("legwork results");
  cmd->add_option("dir", *dir, "folder of results")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--title", *title, "page title")->capture_default_str();
  cmd->callback([dir, title] {
    std::vector<std::string> problems;
    render::write_video_posters(*dir, &problems);
    for (const auto& p : problems) std::fprintf(stderr, "gallery: no poster frame: %s\n", p.c_str());
    const auto pages = render::gallery_pages(*dir, *title);
    for (const auto& page : pages) io::write_text_file((std::filesystem::path(*dir) / page.path).string(), page.html);
    announce("gallery", (std::filesystem::path(*dir) / "index.html").string() +
                            (pages.size() > 1 ? " (+" + std::to_string(pages.size() - 1) + " sub-pages)" : ""));
  });
}

LEGWORK_COMMAND(register_gallery, 900);

}  // namespace
}  // namespace legwork::cli
