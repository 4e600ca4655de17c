// `medax view` and `medax snapshot` in a real browser (headless Chromium), on a small real run:
// quickstart's interior Voronoi axis of the bundled ellipsoid.
#include "viewer_fixture.hpp"

#include <medax/io.hpp>

#include <cmath>
#include <fstream>
#include <regex>

using namespace medax::test;

namespace {

/// The attribute `name` of the viewer's #status element in a dumped DOM, or "" without one.
std::string status_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  const std::regex element("<div id=\"status\"[^>]*>");
  if (!std::regex_search(dom, m, element)) return "";
  const std::string tag = m.str();
  if (!std::regex_search(tag, m, std::regex(name + "=\"([^\"]*)\""))) return "";
  return m[1];
}

}  // namespace

TEST_CASE("medax view writes one self-contained page: scripts and data inline, nothing fetched", "[viewer]") {
  const std::string html = file_text(small_run_page());
  CHECK(html.size() > 500000);  // three.js is embedded
  CHECK(html.find("<script src") == std::string::npos);
  CHECK(html.find("<link") == std::string::npos);
  CHECK(html.find("OrbitControls") != std::string::npos);
  CHECK(html.find("<script id=\"medax-data\" type=\"application/json\">{") != std::string::npos);
  CHECK(html.find("<!--medax:") == std::string::npos);  // every slot of the template is filled
}

TEST_CASE("medax run --view writes the run's page beside its folder when the run ends", "[viewer]") {
  const auto dir = scratch_dir("viewer_run_view") / "run";
  // No display: the page's path is printed instead of opening a browser.
  const auto r = run_medax("run '" + (source_dir() / "tests" / "viewer" / "small_run.yaml").string() + "' --out '" +
                           dir.string() + "' --quiet --view");
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const auto page = dir.parent_path() / "run.html";
  CHECK_THAT(r.out, Catch::Contains("viewer: " + page.string()));
  CHECK(std::filesystem::file_size(page) > 500000);
  CHECK(!std::filesystem::exists(dir / "run.html"));  // the run folder stays as run.json lists it
}

TEST_CASE("the viewer page loads in Chromium without console errors and holds every medial triangle", "[viewer]") {
  const auto page = small_run_page();
  const auto medial = medax::read_ma(small_run() / "medial.ma");
  REQUIRE(!medial.faces.empty());
  Browser browser;
  std::string log;
  const std::string dom = browser.dom(page, "", log);
  INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
  CHECK(status_attribute(dom, "data-state") == "ready");
  CHECK(status_attribute(dom, "data-errors") == "0");
  CHECK(status_attribute(dom, "data-field") == "vertex:radius");
  CHECK(status_attribute(dom, "data-triangles") == std::to_string(medial.faces.size()));
  CHECK(medax::cli::page_errors(log).empty());

  // The same check catches an error: a field the run does not have is reported.
  const std::string bad = browser.dom(page, "field=no_such_field", log);
  CHECK(status_attribute(bad, "data-errors") == "1");
  CHECK(medax::cli::page_errors(log).size() == 1);
}

TEST_CASE("the viewer draws the axis: pixels differ from the background where the shape is", "[viewer]") {
  const auto page = small_run_page();
  Browser browser;
  const Picture shape = browser.screenshot(page, "view=front&legend=0", 400, 300);
  REQUIRE(shape.width == 400);
  REQUIRE(shape.height == 300);
  // The ellipsoid (semi-axes 0.2 0.3 0.5, seen along z) sits in the middle of the picture.
  CHECK(count_not(shape, kWhite) > 400 * 300 / 20);
  const std::uint8_t* centre = shape.at(200, 150);
  CHECK((centre[0] < 230 || centre[1] < 230 || centre[2] < 230));
  // Control: with no layer shown the picture is all background, so the count above is the shape.
  const Picture empty = browser.screenshot(page, "view=front&legend=0&layers=", 400, 300);
  CHECK(count_not(empty, kWhite) == 0);
}

TEST_CASE("switching the field recolours the axis and keeps its outline", "[viewer]") {
  const auto page = small_run_page();
  Browser browser;
  const std::string view = "view=front&legend=0&layers=triangles";
  const Picture radius = browser.screenshot(page, view + "&field=radius", 400, 300);
  const Picture polygon = browser.screenshot(page, view + "&field=face:polygon", 400, 300);
  const Picture plain = browser.screenshot(page, view + "&field=none", 400, 300);
  const std::size_t drawn = count_not(radius, kWhite);
  REQUIRE(drawn > 1000);
  CHECK(count_different(radius, polygon) > drawn / 4);
  CHECK(count_different(radius, plain) > drawn / 4);
  // The same triangles are drawn whatever the colour: the outlines match.
  const double outline_change = std::abs(double(count_not(polygon, kWhite)) - double(drawn)) / double(drawn);
  CHECK(outline_change < 0.02);
}

TEST_CASE("medax snapshot writes a PNG of the requested size showing the axis", "[viewer][snapshot]") {
  const auto png = small_run().parent_path() / "shot.png";
  const auto r =
      run_medax("snapshot '" + small_run().string() + "' --size 320x240 --view top -o '" + png.string() + "'");
  INFO(r.out << r.err);
  REQUIRE(r.code == 0);
  const Picture shot = read_png(png);
  CHECK(shot.width == 320);
  CHECK(shot.height == 240);
  CHECK(count_not(shot, kWhite) > 320 * 240 / 20);

  // A picked vertex adds its sphere to the picture.
  const auto picked_png = small_run().parent_path() / "picked.png";
  const auto picked = run_medax("snapshot '" + small_run().string() + "' --size 320x240 --view top --pick 0 -o '" +
                                picked_png.string() + "'");
  REQUIRE(picked.code == 0);
  CHECK(count_different(shot, read_png(picked_png)) > 50);
}

TEST_CASE("a stage's point set is drawn coloured by its distance field, without page errors", "[viewer]") {
  // The small run plus envelope samples as the reconstruction stage writes them (a ring of points
  // around the ellipsoid's waist, coloured by distance).
  const auto dir = scratch_dir("viewer_points") / "run";
  std::filesystem::copy(small_run(), dir);
  std::ofstream ply(dir / "reconstruction_envelope.ply");
  ply << "ply\nformat ascii 1.0\nelement vertex 360\nproperty double x\nproperty double y\nproperty double z\n"
         "property double distance\nend_header\n";
  for (int i = 0; i < 360; ++i)
    ply << 0.2 * std::cos(i * M_PI / 180) << ' ' << 0.3 * std::sin(i * M_PI / 180) << " 0 " << i * 1e-4 << '\n';
  ply.close();
  const auto page = dir.parent_path() / "view.html";
  REQUIRE(run_medax("view '" + dir.string() + "' --no-open -o '" + page.string() + "'").code == 0);
  Browser browser;
  std::string log;
  const std::string dom = browser.dom(page, "", log);
  CHECK(status_attribute(dom, "data-errors") == "0");
  CHECK(medax::cli::page_errors(log).empty());
  const Picture points = browser.screenshot(page, "view=front&legend=0&layers=reconstruction_envelope.ply", 400, 300);
  const std::size_t drawn = count_not(points, kWhite);
  CHECK(drawn > 200);
  CHECK(drawn < 400 * 300 / 10);  // points on a ring, not a filled shape
}

TEST_CASE("medax snapshot refuses a field the run does not have and lists the fields (exit 2)", "[viewer][snapshot]") {
  const auto png = small_run().parent_path() / "never.png";
  const auto r = run_medax("snapshot '" + small_run().string() + "' --field et -o '" + png.string() + "'");
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Catch::Contains("no field 'et'"));
  CHECK_THAT(r.err, Catch::Contains("vertex:radius"));
  CHECK(!std::filesystem::exists(png));
}

TEST_CASE("medax view on an experiment writes results.html: a sortable row, a picture and a viewer per job",
          "[viewer][experiment]") {
  // A space, '#' and '%' in the folder's name stay part of the path in the pages' file:// URLs.
  const auto dir = scratch_dir("viewer_experiment") / "experiment #1 100%";
  const auto run = run_medax("run '" + (source_dir() / "tests" / "viewer" / "small_experiment.yaml").string() +
                             "' --out '" + dir.string() + "' --quiet");
  INFO(run.out << run.err);
  REQUIRE(run.code == 0);
  const auto view = run_medax("view '" + dir.string() + "' --no-open");
  INFO(view.out << view.err);
  REQUIRE(view.code == 0);
  CHECK_THAT(view.out, Catch::Contains("results.html"));
  for (const char* job : {"0001-ellipsoid", "0002-joint"})
    CHECK(std::filesystem::is_regular_file(dir / "viewers" / (std::string(job) + ".html")));

  Browser browser;
  std::string log;
  // Sorted by face count: the ellipsoid's axis has 944 triangles, the joint's 186.
  const std::string up = browser.dom(dir / "results.html", "sort=counts.faces", log);
  const std::string down = browser.dom(dir / "results.html", "sort=counts.faces&order=down", log);
  CHECK(status_attribute(up, "data-state") == "ready");
  CHECK(status_attribute(up, "data-rows") == "2");
  CHECK(up.find("0002-joint</a>") < up.find("0001-ellipsoid</a>"));
  CHECK(down.find("0001-ellipsoid</a>") < down.find("0002-joint</a>"));
  CHECK(up.find("href=\"viewers/0001-ellipsoid.html\"") != std::string::npos);
  // One picture per job, each a PNG inside the page.
  std::size_t pictures = 0;
  for (std::size_t at = up.find("class=\"thumbnail\" src=\"data:image/png;base64,"); at != std::string::npos;
       at = up.find("class=\"thumbnail\" src=\"data:image/png;base64,", at + 1))
    ++pictures;
  CHECK(pictures == 2);
}
