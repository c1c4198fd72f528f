// The error-against-time study (renderer/analysis/convergence.h), its SVG plot (renderer/analysis/plot_svg.h) and `kiln converge`
// (renderer/cli/converge.h), run in-process on small scenes.
#include <gtest/gtest.h>

#include <fstream>
#include <pugixml.hpp>
#include <sstream>

#include "core/error.h"
#include "renderer/render_util.h"
#include "renderer/cli/converge.h"
#include "renderer/analysis/convergence.h"
#include "renderer/analysis/convergence_budget.h"
#include "renderer/image_io/image_io.h"
#include "renderer/analysis/plot_svg.h"

namespace kiln::test {
namespace {

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

SceneDesc small_default_scene(int res) {
  SceneDesc s = load_scene(std::string(KILN_SOURCE_DIR) + "/scenes/default.xml");
  s.cameras[0].width = s.cameras[0].height = res;
  return s;
}

TEST(Convergence, StrategyNamesShareTheTransportRules) {
  SceneDesc scene;
  scene.max_recursion_depth = 3;
  const PathSettings base = convergence_base_settings(scene);
  EXPECT_EQ(base.max_depth, 3);
  EXPECT_FALSE(base.russian_roulette);
  EXPECT_EQ(base.rr_min_depth, kKilnRouletteMinDepth);
  EXPECT_EQ(convergence_base_settings(SceneDesc{}).max_depth, 8);

  struct Want {
    const char* name;
    DirectionSampling dirs;
    bool nee, mis, rr;
  };
  const Want wants[] = {{"uniform", DirectionSampling::Uniform, false, false, false},
                        {"cosine", DirectionSampling::Cosine, false, false, false},
                        {"brdf", DirectionSampling::Brdf, false, false, false},
                        {"nee", DirectionSampling::Brdf, true, false, false},
                        {"nee+rr", DirectionSampling::Brdf, true, false, true},
                        {"mis", DirectionSampling::Brdf, true, true, false},
                        {"mis+rr", DirectionSampling::Brdf, true, true, true},
                        {"uniform+rr", DirectionSampling::Uniform, false, false, true}};
  for (const Want& w : wants) {
    const NamedStrategy s = make_strategy(w.name, base, kFeatureAll);
    EXPECT_EQ(s.name, w.name);
    // Every strategy is Kiln's own path tracer, never one of the course's integrators.
    const PathSettings* p = std::get_if<PathSettings>(&s.settings.method);
    ASSERT_NE(p, nullptr) << w.name;
    EXPECT_EQ(p->directions, w.dirs) << w.name;
    EXPECT_EQ(p->nee, w.nee) << w.name;
    EXPECT_EQ(p->mis, w.mis) << w.name;
    EXPECT_EQ(p->russian_roulette, w.rr) << w.name;
    EXPECT_EQ(p->max_depth, 3) << w.name;
  }
  for (const char* bad : {"direct", "mis+", "+rr", "MIS", "nee+rr+rr", ""}) {
    try {
      make_strategy(bad, base, kFeatureAll);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("--strategies"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(Convergence, SplitsLists) {
  EXPECT_EQ(split_list("uniform, cosine,,nee+rr "), (std::vector<std::string>{"uniform", "cosine", "nee+rr"}));
  EXPECT_TRUE(split_list(" , ").empty());
  EXPECT_EQ(split_list("mis"), (std::vector<std::string>{"mis"}));
}

TEST(Convergence, LogLogSlope) {
  EXPECT_NEAR(loglog_slope({1, 10, 100}, {5, 0.5, 0.05}), -1.0, 1e-12);
  EXPECT_NEAR(loglog_slope({2, 4, 8, -1}, {4, 16, 64, 1}), 2.0, 1e-12);  // the non-positive point is skipped
  EXPECT_TRUE(std::isnan(loglog_slope({1}, {1})));
  EXPECT_TRUE(std::isnan(loglog_slope({3, 3}, {1, 2})));
}

// On the Cornell box, MIS needs far less time than uniform hemisphere sampling for the same relMSE (the light is
// small); every run reaches the same spp, errors fall with spp, and the efficiency column is 1/(relMSE * time).
TEST(Convergence, MisBeatsUniformOnTheCornellBox) {
  const SceneDesc scene = small_default_scene(24);
  const auto world = build_world(scene, {});
  const Camera cam(scene.cameras[0]);
  const PathSettings base = convergence_base_settings(scene);
  RenderOptions ro;
  ro.seed = 12345;
  ro.spp_total = 512;
  Film ref_film(cam.width(), cam.height());
  render_samples(*world, cam, make_strategy("mis", base, world->features).settings, ro, 0, 512, ref_film);
  const Image reference = ref_film.mean();

  ConvergenceOptions co;
  co.runs = 3;
  co.budget_seconds = 0.6;
  std::vector<StrategySummary> summaries;
  for (const char* name : {"uniform", "mis"}) {
    const std::vector<ConvergencePoint> pts = measure_strategy(*world, cam, make_strategy(name, base, world->features), reference, co);
    ASSERT_GE(pts.size(), 3u) << name;
    for (size_t i = 0; i < pts.size(); ++i) {
      EXPECT_EQ(pts[i].strategy, name);
      EXPECT_EQ(pts[i].spp, 1u << i);
      EXPECT_EQ(pts[i].runs, 3) << name << " spp " << pts[i].spp;
      EXPECT_LE(pts[i].rel_mse_min, pts[i].rel_mse);
      EXPECT_GE(pts[i].rel_mse_max, pts[i].rel_mse);
      EXPECT_GT(pts[i].rel_mse_sd, 0.0);  // independent seeds
      EXPECT_NEAR(pts[i].efficiency, 1.0 / (pts[i].rel_mse * pts[i].seconds), 1e-9 * pts[i].efficiency);
    }
    EXPECT_LT(pts.back().rel_mse, 0.5 * pts.front().rel_mse) << name;
    summaries.push_back(summarize(pts));
  }
  EXPECT_GT(summaries[1].efficiency, 2.0 * summaries[0].efficiency)
      << "mis " << summaries[1].efficiency << " vs uniform " << summaries[0].efficiency;
  const std::string table = ranking_table(summaries);
  const auto rows = lines_of(table);
  ASSERT_EQ(rows.size(), 3u) << table;
  EXPECT_NE(rows[1].find("mis"), std::string::npos) << table;  // ranked first
  EXPECT_NE(rows[2].find("uniform"), std::string::npos) << table;
}

TEST(Convergence, CsvHasOneRowPerPoint) {
  ConvergencePoint p;
  p.strategy = "nee+rr";
  p.spp = 8;
  p.runs = 3;
  p.seconds = 0.5;
  p.rel_mse = 0.02;
  p.rmse = 0.1;
  p.efficiency = 100;
  const auto rows = lines_of(convergence_csv({p, p}));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "strategy,spp,runs,seconds,seconds_sd,relmse,relmse_sd,relmse_min,relmse_max,rmse,rmse_sd,efficiency");
  EXPECT_EQ(rows[1], "nee+rr,8,3,0.5,0,0.02,0,0,0,0.1,0,100");
}

TEST(PlotSvg, DecadeRanges) {
  EXPECT_EQ(decade_range(0.02, 7).lo, -2);
  EXPECT_EQ(decade_range(0.02, 7).hi, 1);
  EXPECT_EQ(decade_range(10, 100).lo, 1);
  EXPECT_EQ(decade_range(10, 100).hi, 2);
  EXPECT_EQ(decade_range(3, 3).hi, 1);  // at least one decade
  EXPECT_EQ(decade_range(3e-5, 4e-5).lo, -5);
}

// The SVG is well-formed XML with a polyline of every drawable point per series, a 10^k label per decade on each
// axis, a legend entry per series and the escaped title.
TEST(PlotSvg, WellFormedWithAxesSeriesAndLegend) {
  LogLogPlot plot;
  plot.title = "relMSE <&> time";
  plot.x_label = "seconds";
  plot.y_label = "relMSE";
  plot.guide_slope = -1;
  plot.series.push_back({"a", {0.01, 0.1, 1.0}, {3, 0.3, 0.03}, {2, 0.2, 0.02}, {4, 0.4, 0.04}});
  plot.series.push_back({"b&c", {0.02, 0.2, 2.0, 0.0}, {1, 0.1, 0.01, 5}, {}, {}});  // x = 0 cannot be drawn
  const std::string svg = loglog_svg(plot);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(svg.c_str())) << svg.substr(0, 400);
  const pugi::xml_node root = doc.child("svg");
  ASSERT_TRUE(root);
  EXPECT_STREQ(root.attribute("xmlns").value(), "http://www.w3.org/2000/svg");

  std::vector<std::string> series_names;
  std::vector<size_t> points;
  std::vector<std::string> texts;
  size_t guides = 0;
  std::function<void(pugi::xml_node)> walk = [&](pugi::xml_node n) {
    for (pugi::xml_node c : n.children()) {
      if (std::string(c.attribute("class").value()) == "series") {
        series_names.push_back(c.attribute("data-name").value());
        const pugi::xml_node pl = c.child("polyline");
        std::stringstream ss(pl.attribute("points").value());
        size_t k = 0;
        for (std::string p; ss >> p;) ++k;
        points.push_back(k);
      }
      if (std::string(c.attribute("class").value()) == "guide") ++guides;
      if (std::string(c.name()) == "text") texts.push_back(c.child_value() + std::string("^") + c.child("tspan").child_value());
      walk(c);
    }
  };
  walk(root);
  EXPECT_EQ(series_names, (std::vector<std::string>{"a", "b&c"}));
  EXPECT_EQ(points, (std::vector<size_t>{3, 3}));
  EXPECT_EQ(guides, 1u);
  auto has_text = [&](const std::string& t) { return std::find(texts.begin(), texts.end(), t) != texts.end(); };
  EXPECT_TRUE(has_text("relMSE <&> time^"));
  // x spans 0.01 .. 2 -> decades -2 .. 1; y spans 0.01 .. 4 -> -2 .. 1.
  for (int k = -2; k <= 1; ++k) EXPECT_TRUE(has_text("10^" + std::to_string(k))) << k;
  EXPECT_FALSE(has_text("10^2"));
  EXPECT_FALSE(has_text("10^-3"));
  EXPECT_TRUE(has_text("a^"));
  EXPECT_TRUE(has_text("b&c^"));
}

// End to end, in-process: no reference given, so one is rendered; the CSV, the SVG and the ranking come out; bad
// input is a kiln::Error naming the option or file.
TEST(ConvergeCommand, WritesReferenceCsvAndPlot) {
  const std::string dir = tmp_dir("converge_cmd");
  std::filesystem::remove_all(dir);
  ConvergeArgs a;
  a.scene = std::string(KILN_SOURCE_DIR) + "/scenes/default.xml";
  a.strategies = "cosine,nee+rr";
  a.budget_seconds = 0.6;
  a.runs = 2;
  a.out_dir = dir;
  a.resolution_scale = 0.05;  // 400x400 -> 20x20
  a.reference_spp = 64;
  a.quiet = true;
  ASSERT_EQ(cmd_converge(a), 0);
  const ExrFile ref = read_exr(dir + "/reference.exr");
  EXPECT_EQ(ref.rgb.width(), 20);
  EXPECT_EQ(ref.rgb.height(), 20);
  const auto rows = lines_of(read_file(dir + "/convergence.csv"));
  ASSERT_GE(rows.size(), 5u);
  size_t cosine = 0, nee_rr = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    cosine += rows[i].rfind("cosine,", 0) == 0;
    nee_rr += rows[i].rfind("nee+rr,", 0) == 0;
  }
  EXPECT_GE(cosine, 2u);
  EXPECT_GE(nee_rr, 2u);
  pugi::xml_document svg;
  EXPECT_TRUE(svg.load_file((dir + "/convergence.svg").c_str()));

  // The rendered reference is accepted back as --reference.
  ConvergeArgs b = a;
  b.reference = dir + "/reference.exr";
  b.out_dir = dir + "/again";
  b.strategies = "mis";
  EXPECT_EQ(cmd_converge(b), 0);
  EXPECT_FALSE(std::filesystem::exists(dir + "/again/reference.exr"));

  ConvergeArgs bad = b;
  bad.resolution_scale = 0.1;  // reference is 20x20, the camera now 40x40
  try {
    cmd_converge(bad);
    ADD_FAILURE() << "accepted a reference of the wrong size";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("reference.exr"), std::string::npos) << e.what();
  }
  bad = a;
  bad.strategies = "mis,bogus";
  EXPECT_THROW(cmd_converge(bad), Error);
  bad = a;
  bad.camera = "7";
  EXPECT_THROW(cmd_converge(bad), Error);
}

// ---- the budget (renderer/analysis/convergence_budget.h) ----

// Why: `--budget 60` on the course's diffuse Cornell box ran 13 minutes, its 4096-spp reference at ~0.19 s per spp
// outside the budget. The default reference now takes as many spp as its measured cost lets fit half the budget,
// so reference plus strategies stay within it.
TEST(ConvergeBudget, DefaultReferenceFitsItsShare) {
  struct Case {
    double budget, cost;  // seconds; seconds per spp
    uint32_t pilot_spp;
  };
  for (const Case& c : {Case{60, 0.19, 8}, Case{60, 0.1, 16}, Case{5, 0.001, 64}, Case{600, 0.19, 64}}) {
    SCOPED_TRACE(testing::Message() << "budget " << c.budget << " s, " << c.cost << " s/spp");
    const double share = kReferenceShare * c.budget, pilot_seconds = c.cost * c.pilot_spp;
    const ReferencePlan plan = plan_reference(share, c.pilot_spp, pilot_seconds, c.cost, kDefaultReferenceMaxSpp, 0);
    EXPECT_LE(plan.spp * c.cost, share);
    EXPECT_NEAR(plan.estimated_seconds, plan.spp * c.cost, 1e-9);
    EXPECT_TRUE(plan.fits);
    EXPECT_LE(plan.spp, kDefaultReferenceMaxSpp);
    // The share is used, not wasted: one more sample would pass the planning margin, unless the cap stopped it.
    if (plan.spp < kDefaultReferenceMaxSpp) {
      EXPECT_GT((plan.spp + 1) * c.cost, kPlanningMargin * share - 1e-6);
    }
    EXPECT_LE(plan.estimated_seconds + strategies_budget(c.budget, plan.estimated_seconds), c.budget + 1e-9);
  }
  // The case: 142 spp in ~27 s instead of 4096 in ~780 s.
  const ReferencePlan cornell = plan_reference(30, 8, 8 * 0.19, 0.19, kDefaultReferenceMaxSpp, 0);
  EXPECT_EQ(cornell.spp, 8u + uint32_t((0.9 * 30 - 8 * 0.19) / 0.19));
  // A cheap scene stops at the cap; a pilot that already spent the share is the reference.
  EXPECT_EQ(plan_reference(30, 64, 0.064, 0.001, kDefaultReferenceMaxSpp, 0).spp, kDefaultReferenceMaxSpp);
  const ReferencePlan spent = plan_reference(30, 64, 40, 0.6, kDefaultReferenceMaxSpp, 0);
  EXPECT_EQ(spent.spp, 64u);
  EXPECT_FALSE(spent.fits);
}

// Why: an explicit --reference-spp is honoured, but its cost is estimated (and announced) before it starts, and
// the strategies keep their half of the budget.
TEST(ConvergeBudget, ExplicitReferenceSppIsEstimated) {
  const ReferencePlan p = plan_reference(30, 16, 16 * 0.19, 0.19, 4096, 4096);
  EXPECT_EQ(p.spp, 4096u);
  EXPECT_NEAR(p.estimated_seconds, 4096 * 0.19, 1e-6);
  EXPECT_FALSE(p.fits);
  EXPECT_TRUE(plan_reference(30, 16, 16 * 0.01, 0.01, 256, 256).fits);
  EXPECT_DOUBLE_EQ(strategies_budget(60, p.estimated_seconds), 30.0);
  EXPECT_DOUBLE_EQ(strategies_budget(60, 20.0), 40.0);
  EXPECT_DOUBLE_EQ(strategies_budget(60, 0.0), 60.0);  // a reference given as a file
}

// Why: the user hears the reference's spp and estimated time before it renders, and gets the spp announced.
TEST(ConvergeBudget, CommandAnnouncesTheReferencePlan) {
  const std::string dir = tmp_dir("converge_budget"), scene = std::string(KILN_SOURCE_DIR) + "/scenes/default.xml";
  const std::string common = " --resolution-scale 0.05 --strategies mis --runs 1 --budget 2";
  auto [code, out] = run_kiln_command("converge " + scene + common + " -o " + dir + "/auto");
  ASSERT_EQ(code, 0) << out;
  const std::string announced = "rendering one with mis at ";
  const size_t at = out.find(announced);
  ASSERT_NE(at, std::string::npos) << out;
  const uint32_t spp = uint32_t(std::stoul(out.substr(at + announced.size())));
  EXPECT_NE(out.find("within 50% of the --budget"), std::string::npos) << out;
  EXPECT_NE(out.find(": about "), std::string::npos) << out;
  EXPECT_EQ(read_exr(dir + "/auto/reference.exr").find("kiln:spp"), std::to_string(spp));
  EXPECT_GE(spp, 1u);
  EXPECT_LE(spp, kDefaultReferenceMaxSpp);

  std::tie(code, out) = run_kiln_command("converge " + scene + common + " --reference-spp 24 -o " + dir + "/explicit");
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find(announced + "24 spp"), std::string::npos) << out;
  EXPECT_NE(out.find("as --reference-spp asks"), std::string::npos) << out;
  EXPECT_EQ(read_exr(dir + "/explicit/reference.exr").find("kiln:spp"), "24");

  // A budget below one spp per run: the overrun is announced before the strategies start.
  std::tie(code, out) = run_kiln_command("converge " + scene +
                                         " --resolution-scale 0.05 --strategies mis,nee,cosine --runs 3 --budget 0.001"
                                         " -o " + dir + "/tiny");
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("need at least 1 spp each"), std::string::npos) << out;
  EXPECT_LT(out.find("need at least 1 spp each"), out.find("kiln: converge: mis ")) << out;
}

}  // namespace
}  // namespace kiln::test
