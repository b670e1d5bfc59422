#include "core/rules.hpp"

#include <algorithm>
#include <stdexcept>

namespace mpm3d {

const RuleInfo kRules[kRuleCount] = {
    {"program", {"book", "current"}, 0, 1,
     "part bloc numbering, default bulk viscosity, gimp size, held node layers"},
    {"time_step", {"book", "current"}, 0, 1, "the initial dt kept, or dt recomputed every step"},
    {"bulk_book", {"apply", "ignore"}, 1, 0, "book program: 'bulk q1 q2' applied, or read and ignored"},
    {"bulk_switch", {"volume", "stress"}, 0, 1,
     "bulk viscosity where the volume shrinks, or where the mean stress is compressive"},
    {"bulk_linear", {"all", "original"}, 0, 1,
     "bulk viscosity on every material with its wave speed, or as the current program:\n"
     "      none with a linear or JWL EOS (hiex), the linear term on elas, neoh and null only"},
    {"burn", {"ramp", "step"}, 1, 1, "programmed burn over 1.5 cells, or all at the lighting time"},
    {"dp_return", {"surface", "original"}, 1, 1,
     "Drucker-Prager returns onto the yield surface, or the original's branches"},
    {"deck_reals", {"double", "single"}, 1, 1, "deck reals read in double, or rounded to single precision"},
    {"tl_shape", {"particle", "centre"}, 0, 1,
     "TLmp shape functions at the reference position, or at the cell's centre"},
    {"sg_lower", {"nearest", "truncate"}, 0, 1,
     "sgmp auxiliary cell at a lower face: nearest centre, or truncated to zero"},
    {"sg_beyond", {"nearest", "drop"}, 0, 1,
     "sgmp weights beyond a one-layer grid: to the nearest centre, or dropped"},
    {"fluid_viscous", {"deviator", "full"}, 0, 1, "viscous null: stress 2 mu dev(D), or 2 mu D"},
    {"bulk_work", {"mean", "new"}, 0, 1,
     "bulk viscosity's work by the mean of the old and new q, or by the new q (john: twice)"},
    {"pressure_q", {"in", "out"}, 0, 1, "output pres: the stress's pressure with q in it, or without q"},
    {"clay_return", {"solved", "linear"}, 1, 1,
     "clay: return solved to the softening curve, or the newest program's one linearised step"},
    {"null_eos", {"deck", "wave_speed"}, 0, 1,
     "null's EOS as the deck gives it, or its first coefficient replaced by the null's\n"
     "      wave speed sqrt(K/rho0), as the current program's set-up does"},
    {"start_temp", {"room", "293"}, 1, 1,
     "particles' starting temperature: the material card's room temperature, or 293"},
    {"contact", {"twice", "original"}, 1, 1,
     "contact: the nodes in contact corrected again before the strain rates read them\n"
     "      (MUSL's remapped, USF's P2G momenta) and their forces by the step's momentum dt,\n"
     "      or once a step with forces by the full dt, as the original programs"},
};

int& rule_value(StepRules& r, int i) {
  int* v[kRuleCount] = {&r.program,  &r.time_step, &r.bulk_book, &r.bulk_switch, &r.bulk_linear, &r.burn,
                        &r.dp_return, &r.deck_reals, &r.tl_shape, &r.sg_lower,   &r.sg_beyond,  &r.fluid_viscous,
                        &r.bulk_work, &r.pressure_q, &r.clay_return, &r.null_eos, &r.start_temp,
                        &r.contact};
  return *v[i];
}

int rule_value(const StepRules& r, int i) { return rule_value(const_cast<StepRules&>(r), i); }

RulePreset parse_rule_preset(const std::string& name) {
  if (name == "ours") return RulePreset::ours;
  if (name == "original") return RulePreset::original;
  if (name == "book") return RulePreset::book;
  if (name == "current") return RulePreset::current;
  throw std::invalid_argument("--rules must be ours, original, book or current, got '" + name + "'");
}

void add_rule_setting(RuleRequest& request, const std::string& s) {
  const size_t eq = s.find('=');
  const std::string name = s.substr(0, eq), value = eq == std::string::npos ? "" : s.substr(eq + 1);
  for (int i = 0; i < kRuleCount; ++i) {
    if (name != kRules[i].name) continue;
    for (int v = 0; v < 2; ++v)
      if (value == kRules[i].value[v]) {
        request.set.emplace_back(i, v);
        return;
      }
    throw std::invalid_argument("--rule " + name + " must be " + kRules[i].value[0] + " or " + kRules[i].value[1] +
                                ", got '" + value + "'");
  }
  std::string names;
  for (const RuleInfo& r : kRules) names += std::string(names.empty() ? "" : ", ") + r.name;
  throw std::invalid_argument("--rule needs NAME=VALUE with NAME one of " + names + ", got '" + s + "'");
}

StepRules resolve_rules(const RuleRequest& request, bool deck_current) {
  StepRules r{};
  int program = deck_current ? 1 : 0;
  if (request.preset == RulePreset::book) program = 0;
  if (request.preset == RulePreset::current) program = 1;
  if (request.preset != RulePreset::ours)
    for (int i = 0; i < kRuleCount; ++i) rule_value(r, i) = program ? kRules[i].current : kRules[i].book;
  r.program = program;
  bool time_step_set = false;
  for (const auto& s : request.set) {
    rule_value(r, s.first) = s.second;
    time_step_set = time_step_set || s.first == 1;
  }
  if (!time_step_set) r.time_step = r.program;
  return r;
}

std::string rules_text(const StepRules& r) {
  std::string s;
  for (int i = 0; i < kRuleCount; ++i)
    s += std::string(i ? " " : "") + kRules[i].name + "=" + kRules[i].value[rule_value(r, i)];
  return s;
}

std::string rules_changed(const StepRules& r, bool deck_current) {
  std::string s;
  const int program = deck_current ? 1 : 0;
  for (int i = 0; i < kRuleCount; ++i) {
    const int ours = i == 0 ? program : i == 1 ? r.program : 0;
    if (rule_value(r, i) != ours) s += std::string(s.empty() ? "" : " ") + kRules[i].name + "=" + kRules[i].value[rule_value(r, i)];
  }
  return s;
}

std::string rules_usage() {
  std::string s;
  for (const RuleInfo& r : kRules) {
    std::string line = std::string("  ") + r.name + "=" + r.value[0] + "|" + r.value[1];
    line.resize(std::max<size_t>(line.size() + 1, 32), ' ');
    s += line + "book: " + r.value[int(r.book)] + ", current: " + r.value[int(r.current)] + "\n" +
         std::string(6, ' ') + r.what + "\n";
  }
  return s;
}

}  // namespace mpm3d
