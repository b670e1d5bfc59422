// The rules: every place where mpm3d deliberately differs from the original programs, as a
// named rule with two values (0 ours, 1 the original's), held in StepRules
// (core/step_state.hpp) and chosen once when the deck is bound. `--rules` picks a preset,
// `--rule NAME=VALUE` sets one rule (app/cli.cpp); the Fortran reference's table
// (fortran_ref/rules.f90) is the same, checked by the rules.* tests.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/step_state.hpp"

namespace mpm3d {

constexpr int kRuleCount = 18;

struct RuleInfo {
  const char* name;
  const char* value[2];  // the names of values 0 (ours) and 1
  signed char book, current;  // the value in the book program and in the current program
  const char* what;     // one line for --help
};

// In the order of StepRules' members.
extern const RuleInfo kRules[kRuleCount];

int& rule_value(StepRules& r, int i);
int rule_value(const StepRules& r, int i);

// ours: today's behaviour; original: the rules of the program the deck's keywords name;
// book, current: that program's rules whatever the deck's keywords.
enum class RulePreset { ours, original, book, current };

struct RuleRequest {
  RulePreset preset = RulePreset::ours;
  std::vector<std::pair<int, int>> set;  // (rule, value) from --rule, in order; the last wins
};

// "ours", "original", "book", "current"; throws std::invalid_argument naming the choices.
RulePreset parse_rule_preset(const std::string& name);
// Adds "NAME=VALUE" to the request; throws std::invalid_argument naming the choices.
void add_rule_setting(RuleRequest& request, const std::string& name_eq_value);
// The rules of a run of a deck whose keywords name the current program (deck_current) or
// the book's. time_step follows the program unless it is set on its own.
StepRules resolve_rules(const RuleRequest& request, bool deck_current);
// "program=book time_step=book ...": every rule, for the summary and the .out file.
std::string rules_text(const StepRules& r);
// The rules whose values differ from ours ("" when none), e.g. "burn=step dp_return=original";
// program and time_step count when they differ from the deck's own program.
std::string rules_changed(const StepRules& r, bool deck_current);
// The block of --help that lists the rules.
std::string rules_usage();

}  // namespace mpm3d
