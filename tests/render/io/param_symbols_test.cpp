// What the panel shows next to each parameter: a symbol keeps one meaning across the generators
// (τ is the self-organizing model's tropism weight, τₚ every generator's pipe taper), and help texts
// cite published papers, never the project's internal labels for them ("seed 001").
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "render/io/preset.h"

using namespace sylva;

namespace {

struct catalogue {
  std::map<std::string, std::set<std::string>> labels;   // symbol -> the labels that use it
  std::vector<std::string> helps;
  template <class P>
  void add(const P& p) {
    visit_params(p, [&](const auto&, const param_info& info) {
      if (info.symbol && *info.symbol) labels[info.symbol].insert(info.label);
      helps.push_back(info.help ? info.help : "");
    });
  }
};

}  // namespace

TEST(ParamSymbols, TauIsTheTropismWeightAndPipeTaperIsTauP) {
  catalogue c;
  for (int g = 0; g < generator_count; ++g) std::visit([&](const auto& p) { c.add(p); }, default_params(g));
  EXPECT_EQ(c.labels["τ"], std::set<std::string>{"Tropism weight"});
  EXPECT_EQ(c.labels["τₚ"], std::set<std::string>{"Pipe taper"});
}

TEST(ParamSymbols, HelpCitesPapersNotInternalLabels) {
  catalogue c;
  for (int g = 0; g < generator_count; ++g) std::visit([&](const auto& p) { c.add(p); }, default_params(g));
  const preset p;
  c.add(p.spec.wood);
  c.add(p.mesh);
  c.add(p.render);
  ASSERT_GT(c.helps.size(), 100u);
  for (std::string h : c.helps) {
    std::transform(h.begin(), h.end(), h.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    EXPECT_EQ(h.find("seed 00"), std::string::npos) << h;
  }
}
