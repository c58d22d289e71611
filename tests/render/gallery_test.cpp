// The gallery page's structure: story order, one format per chart, plain
// files in a list, the command that made each file, sub-pages, posters.
#include <legwork/io/text.hpp>
#include <legwork/render/gallery.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

using namespace legwork;
namespace fs = std::filesystem;

namespace {

// A results folder laid out like the demo's (file contents do not matter to the page).
fs::path make_results() {
  // One folder per test process: ctest runs the tests of this file in parallel.
  const fs::path root = fs::temp_directory_path() / ("legwork_gallery_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  for (const char* d : {"accent", "data", "wip/eval", "zoo"}) fs::create_directories(root / d);
  for (const char* f : {"data/sheet.png", "data/sheet.svg", "data/arc.svg", "data/walk.mp4", "data/walk.poster.png", "data/walk.glb",
                        "data/info.json", "data/arc.csv", "accent/body.bvh", "wip/eval/t1.png", "wip/eval/t2.png", "wip/report.md", "zoo/x.csv"})
    io::write_text_file((root / f).string(), "x");
  io::write_text_file((root / "README.txt").string(),
                      "Intro line: a sentence.\ndata/: Data - the clips\nwip/: Walking in place - legs\naccent/: Accentuation - bodies\n");
  io::write_text_file((root / "data/README.txt").string(),
                      "walk.mp4: the walk as video\nsheet.png: a contact sheet\nsheet.svg: the same as SVG\nwalk.glb: glTF\n");
  io::write_text_file((root / "wip/README.txt").string(), "eval/: one plot per trial\neval/t2.png: the second trial\n");
  io::write_text_file((root / "commands.txt").string(),
                      "legwork render data/cmu/a.bvh --out demo-out/data/sheet.png\n"
                      "legwork render data/cmu/a.bvh --out /abs/demo-out/data/walk.mp4\n"
                      "legwork wip eval --out demo-out/wip/eval\n"
                      "legwork walkcycle --arc-out demo-out/data/arc\n"
                      "legwork eval accent --quick --out demo-out/accent\n");
  return root;
}

std::size_t at(const std::string& html, const std::string& what) {
  const auto p = html.find(what);
  EXPECT_NE(p, std::string::npos) << "missing: " << what;
  return p;
}

}  // namespace

TEST(Gallery, SectionsFollowTheStoryThenTheRest) {
  const std::string html = render::gallery_html(make_results().string(), "t");
  EXPECT_LT(at(html, "<h2 id=\"data\">Data</h2>"), at(html, "<h2 id=\"wip\">Walking in place</h2>"));
  EXPECT_LT(at(html, "<h2 id=\"wip\">"), at(html, "<h2 id=\"accent\">Accentuation</h2>"));
  EXPECT_LT(at(html, "<h2 id=\"accent\">"), at(html, "<h2 id=\"zoo\">zoo</h2>"));  // not in the README: last
  at(html, "<p class=\"intro\">Intro line: a sentence. </p>");
  at(html, "<p class=\"intro\">the clips</p>");
}

TEST(Gallery, OneFormatPerChartAndFilesInAList) {
  const std::string html = render::gallery_html(make_results().string(), "t");
  EXPECT_EQ(html.find("<img src=\"data/sheet.svg\""), std::string::npos) << "the SVG twin is shown as a picture too";
  at(html, "<img src=\"data/sheet.png\"");
  at(html, "<a class=\"fmt\" href=\"data/sheet.svg\">SVG</a>");
  at(html, "<img src=\"data/arc.svg\"");  // an SVG without a PNG is the picture
  EXPECT_EQ(html.find(">walk.poster.png</a>"), std::string::npos) << "a poster listed as a result";
  // README order inside the section: the video first, then the sheet.
  EXPECT_LT(at(html, "src=\"data/walk.mp4\""), at(html, "src=\"data/sheet.png\""));
  at(html, "poster=\"data/walk.poster.png\"");
  const auto list = at(html, "<ul class=\"files\">");
  EXPECT_GT(at(html, ">walk.glb</a>"), list);
  EXPECT_LT(at(html, "src=\"data/sheet.png\""), list);
}

TEST(Gallery, EachFileShowsTheCommandThatMadeIt) {
  const std::string html = render::gallery_html(make_results().string(), "t");
  // Exact path (with the output folder in front, relative or absolute) and output stems.
  EXPECT_LT(at(html, "src=\"data/sheet.png\""), at(html, "$ legwork render data/cmu/a.bvh --out demo-out/data/sheet.png"));
  at(html, "$ legwork render data/cmu/a.bvh --out /abs/demo-out/data/walk.mp4");
  const auto arc = at(html, "src=\"data/arc.svg\"");
  EXPECT_EQ(html.find("$ legwork walkcycle --arc-out demo-out/data/arc"), html.find("$ legwork", arc)) << "stem match";
  // A section folder given as the output; "eval" (a subcommand, not a path) names no folder.
  EXPECT_GT(at(html, "$ legwork eval accent --quick --out demo-out/accent"), at(html, ">body.bvh</a>"));
  // A command shown once in a folder is named by its first file after that.
  at(html, "$ the command of <a href=\"data/arc.svg\">arc.svg</a>");
  // A file no command names gets none.
  const auto glb = at(html, ">walk.glb</a>");
  EXPECT_EQ(html.substr(glb, html.find("</li>", glb) - glb).find("$ legwork"), std::string::npos);
}

TEST(Gallery, NestedFoldersGetTheirOwnPage) {
  const auto root = make_results();
  const auto pages = render::gallery_pages(root.string(), "t");
  ASSERT_EQ(pages.size(), 2u);
  EXPECT_EQ(pages[1].path, "wip/eval/index.html");
  at(pages[0].html, "<a href=\"wip/eval/index.html\">eval/</a> <span class=\"size\">2 pictures &mdash; own page</span> &mdash; one plot per trial");
  EXPECT_EQ(pages[0].html.find("t1.png"), std::string::npos) << "per-trial plots on the main page";
  at(pages[1].html, "<img src=\"t1.png\"");
  // Captioned from the parent's README ("eval/t2.png: ..."), and first (README order).
  EXPECT_LT(at(pages[1].html, "the second trial"), at(pages[1].html, "<img src=\"t1.png\""));
  at(pages[1].html, "<a href=\"../../index.html\">");
  at(pages[1].html, "$ legwork wip eval --out demo-out/wip/eval");  // a folder output
}

TEST(Gallery, TheResultsFolderLineMakesMatchesExact) {
  // "# results: demo-out" (written by scripts/demo-log.sh): a later command
  // writing demo-out/wip/accent must not claim accent/body.bvh, as the
  // any-leading-folders fallback would.
  const auto root = make_results();
  const std::string log = "legwork accent run --out demo-out/accent\nlegwork wip run --out demo-out/wip/accent\n";
  io::write_text_file((root / "commands.txt").string(), log);
  const std::string loose = render::gallery_html(root.string(), "t");
  const auto row = at(loose, ">body.bvh</a>");
  EXPECT_EQ(loose.find("$ legwork", row), loose.find("$ legwork wip run", row)) << "fallback: the later command wins";
  io::write_text_file((root / "commands.txt").string(), "# results: demo-out\n" + log);
  const std::string exact = render::gallery_html(root.string(), "t");
  const auto row2 = at(exact, ">body.bvh</a>");
  EXPECT_EQ(exact.find("$ legwork", row2), exact.find("$ legwork accent run --out demo-out/accent", row2));
}
