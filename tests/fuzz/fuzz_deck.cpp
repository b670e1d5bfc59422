// libFuzzer harness for the deck reader (`make fuzz`, tools/fuzz.sh).
// Every input must either be read, or be refused with a DeckError naming the deck and a
// line ("fuzz.mpm:LINE: problem", one line). A read deck must pass the checks the program
// relies on (particles generated, finite positive dt), and small ones are advanced two steps
// through the solver (a HealthError, the program's exit status 3, is a clean outcome).
// Anything else - another exception, a signal, a sanitizer report, a leak, a hang or an
// allocation beyond the memory budget - is a finding.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "input/data_in.hpp"
#include "input/ffi.hpp"
#include "mpm3d.hpp"

using namespace mpm3d;

namespace {
const char* const kName = "fuzz.mpm";

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "FUZZ FINDING: %s: %s\n", what, detail.c_str());
  std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Keep each input well inside libFuzzer's -rss_limit_mb: the reader refuses decks whose
  // particles and grid would need more than this (the program uses the machine's memory).
  // (MPM3D_FUZZ_NO_BUDGET: for fuzzing readers older than the budget.)
#ifndef MPM3D_FUZZ_NO_BUDGET
  set_deck_memory_budget(64.0 * 1024 * 1024);
#endif
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Model m;
  try {
    m = read_deck_text(text, kName);
  } catch (const DeckError& e) {
    const std::string msg = e.what();
    const std::string head = std::string(kName) + ":";
    if (msg.compare(0, head.size(), head) != 0) finding("deck error without the file name", msg);
    if (e.line() < 1) finding("deck error without a line number", msg);
    if (msg.find('\n') != std::string::npos) finding("deck error on several lines", msg);
    return 0;
  } catch (const std::exception& e) {
    finding("reader threw something other than a DeckError", e.what());
  }
  const Particles& P = m.particles;
  if (P.np != m.nbmp || P.np < 1) finding("particle count", std::to_string(P.np));
  if (!(m.dt > 0.0) || !std::isfinite(m.dt)) finding("time step", std::to_string(m.dt));
  for (int p = 0; p < P.np; ++p)
    if (!(P.mass[p] > 0.0) || !(P.vol[p] > 0.0) || !std::isfinite(P.mass[p]) || !std::isfinite(P.vol[p]))
      finding("particle mass/volume", std::to_string(p));
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) nodes *= std::floor((m.box_hi[a] - m.box_lo[a]) / m.dcell + 0.5) + 1.0;
  if (P.np > 4000 || nodes > 200000.0) return 0;  // only small scenes through the solver
  try {
    Simulation sim(std::move(m), 8);
    sim.step();
    sim.step();
  } catch (const HealthError&) {
    return 0;
  } catch (const std::exception& e) {
    finding("solver set-up or step threw", e.what());
  }
  return 0;
}
