// The deck reader (data_in.hpp): the memory budget, the card loop and the cards it reads;
// the cards with bodies of their own are in data_in_cards.cpp, the end of the deck ('endi')
// in data_in_finish.cpp, the particles of the 'part' cards come from particle_gen.cpp.
#include "input/data_in.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "input/data_in_reader.hpp"
#include "input/output_variables.hpp"

namespace mpm3d {

// The names of outr, curv and curx: those of the one list of output variables (output_variables.cpp).
bool is_output_variable(const std::string& name) { return output_variable(name) != nullptr; }

// The process-wide default of the memory budget (set_deck_memory_budget): the one piece of
// state this file keeps; each read takes its budget once, as a parameter of the DeckReader.
static std::atomic<double> g_memory_budget{0.0};

void set_deck_memory_budget(double bytes) { g_memory_budget.store(bytes); }

double deck_memory_budget() {
  const double set = g_memory_budget.load();
  if (set > 0.0) return set;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 1.0e18;
}

std::string DeckReader::megabytes(double bytes) { return std::to_string(long(bytes / 1048576.0 + 0.5)) + " MB"; }

bool DeckReader::on_off(const Token& key) {
  if (ts_.at_end()) fail(key.line, "'" + key.text + "' needs 'on' or 'off'");
  const Token& t = ts_.next();
  const std::string k = key4(t.text);
  if (k == "on") return true;
  if (k == "off") return false;
  fail(t.line, "'" + key.text + "' needs 'on' or 'off', found '" + t.text + "'");
}

void DeckReader::need_counts(const Token& key, bool particles, bool materials, bool bodies) {
  if (particles && m_.nbmp < 0) fail(key.line, "'" + key.text + "' before 'nbmp' (number of particles)");
  if (materials && m_.nmat < 0) fail(key.line, "'" + key.text + "' before 'nmat' (number of materials)");
  if (bodies && m_.nbbo < 0) fail(key.line, "'" + key.text + "' before 'nbbo' (number of bodies)");
}

// Keywords only the current MPM3D-F90 knows: a deck that uses one is read and run with the
// current version's behaviours where the two versions differ (Model::current_version).
static const std::vector<std::string> kCurrentKeywords = {"neoh", "uvfp", "vsin", "qulo", "damp", "smoo", "bimp",
                                                          "sgmp", "tlmp", "drda", "blod", "cicl", "ksin", "nuli",
                                                          "clay"};

Model DeckReader::read() {
  m_.deck_path = ts_.name();
  m_.deck_current = ts_.has_keyword(kCurrentKeywords);
  m_.rules = resolve_rules(rules_, m_.deck_current);
  m_.current_version = m_.rules.program == 1;
  m_.dt_per_step = m_.rules.time_step == 1;
  ts_.set_single_reals(m_.rules.deck_reals == 1);
  while (!ts_.at_end()) {
    const Token key = ts_.next();
    const std::string k = key4(key.text);
    if (k == "mpm3") {
      m_.title = ts_.rest_of_line(key);
    } else if (k == "nbmp" || k == "nbco" || k == "nbbo" || k == "nmat") {
      const long n = ts_.integer(std::string(key.text).c_str());
      if (n < 1 || n > kMaxParticles)
        fail(key.line, "'" + key.text + "' must be a count in 1.." + std::to_string(kMaxParticles) + ", got " + std::to_string(n));
      if (k == "nbmp") {
        if (m_.nbmp >= 0) fail(key.line, "'nbmp' given twice");
        const double need = double(n) * kBytesPerParticle, budget = memory_budget_;
        if (need > budget)
          fail(key.line, "'nbmp' = " + std::to_string(n) + " particles need about " + megabytes(need) +
                             ", more than the " + megabytes(budget) + " of memory available");
        m_.nbmp = int(n);
        m_.particles.resize(0);  // grows as the particle cards generate particles
        parts_.set_limit(m_.nbmp);
      } else if (k == "nbco") {
        if (n > 2) fail(key.line, "'nbco' must be 1 or 2");
        m_.nbco = int(n);
      } else if (k == "nbbo") {
        m_.nbbo = int(n);
      } else {
        if (n > 1000) fail(key.line, "'nmat' too large");
        m_.nmat = int(n);
        m_.mats.assign(size_t(n), MaterialParams{});
        for (auto& mp : m_.mats) mp.type = 0;
      }
    } else if (k == "endt") {
      m_.endtime = ts_.real("the end time");
      if (!(m_.endtime > 0.0)) fail(key.line, "end time must be positive");
      m_.outtime = m_.endtime;
    } else if (k == "grid") {
      for (int a = 0; a < 3; ++a) {
        m_.box_lo[a] = ts_.real("the grid box");
        m_.box_hi[a] = ts_.real("the grid box");
        m_.box_set[a] = true;
        box_line_[a] = key.line;
        if (!(m_.box_hi[a] > m_.box_lo[a]))
          fail(key.line, std::string("'grid': maximum must exceed minimum along ") + char('x' + a));
      }
    } else if (k == "spx" || k == "spy" || k == "spz") {
      const int a = k[2] - 'x';
      m_.box_lo[a] = ts_.real("the box minimum");
      m_.box_hi[a] = ts_.real("the box maximum");
      m_.box_set[a] = true;
      box_line_[a] = key.line;
      if (!(m_.box_hi[a] > m_.box_lo[a])) fail(key.line, "'" + key.text + "': maximum must exceed minimum");
    } else if (k == "dcel") {
      m_.dcell = ts_.real("the cell size");
      if (!(m_.dcell > 0.0)) fail(key.line, "cell size must be positive");
      dcell_line_ = key.line;
    } else if (k == "dtsc") {
      m_.dtscale = ts_.real("the time-step scale");
      if (!(m_.dtscale > 0.0) || m_.dtscale > 2.5) fail(key.line, "time-step scale must lie in (0, 2.5]");
    } else if (k == "outt") {
      m_.outtime = ts_.real("the output interval");
      if (!(m_.outtime > 0.0)) fail(key.line, "output interval must be positive");
    } else if (k == "rptt") {
      m_.rpttime = ts_.real("the report interval");
      if (!(m_.rpttime > 0.0)) fail(key.line, "report interval must be positive");
    } else if (k == "adgr") {  // extension: adaptive background grid every N steps
      const long n = ts_.integer("the regrid interval");
      if (n < 0 || n > 1000000000) fail(key.line, "'adgr' needs a step interval, 0 (off) or more");
      m_.regrid_every = int(n);
    } else if (k == "fixe") {
      for (int f = 0; f < 6; ++f) {
        const long v = ts_.integer("a face condition");
        if (v < 0 || v > 2) fail(key.line, "face conditions are 0 (free), 1 (fixed) or 2 (symmetry)");
        m_.fix[f] = int(v);
      }
    } else if (k == "mate") {
      read_materials(key);
    } else if (k == "part") {
      read_particles(key);
    } else if (k == "musl" || k == "usf" || k == "usl") {
      if (on_off(key)) m_.scheme = k == "musl" ? SCHEME_MUSL : (k == "usf" ? SCHEME_USF : SCHEME_USL);
    } else if (k == "jaum") {
      m_.jaumann = on_off(key);
      if (!m_.jaumann) m_.warnings.push_back("jaum off: stresses are rotated with the Jaumann rate all the same");
    } else if (k == "load") {
      read_loads(key);
    } else if (k == "velo") {
      read_velocities(key);
    } else if (k == "seos") {
      read_eos(key);
    } else if (k == "pmin") {  // extension: a null material's cavitation cut-off
      read_pressure_floor(key);
    } else if (k == "outr") {
      // A variable asked for twice is written once (the animation files name their
      // variables; an HDF5 frame cannot hold two datasets of one name).
      const std::string v = output_var(key.line);
      if (std::find(m_.anim_vars.begin(), m_.anim_vars.end(), v) == m_.anim_vars.end())
        m_.anim_vars.push_back(v);
      else
        m_.warnings.push_back("line " + std::to_string(key.line) + ": 'outr " + v + "' given again: written once");
    } else if (k == "curv") {
      CurveRequest c;
      c.var = output_var(key.line);
      long pid = 1;
      if (!ts_.at_end() && ts_.peek().line == key.line && parse_integer(ts_.peek().text, pid)) ts_.next();
      need_counts(key, true, false, false);
      c.particle = particle_index(key, pid);
      m_.curves.push_back(c);
    } else if (k == "curx") {
      CurveRequest c;
      c.var = output_var(key.line);
      double xyz[3];
      for (double& v : xyz) v = ts_.real("a curve position");
      if (parts_.count() == 0) fail(key.line, "'curx' must follow the particle cards");
      const double tol = 0.25 * m_.dcell;
      int found = -1;
      for (int p = 0; p < parts_.count() && found < 0; ++p) {
        const double* x = &m_.particles.x[3 * size_t(p)];
        if (std::fabs(x[0] - xyz[0]) <= tol && std::fabs(x[1] - xyz[1]) <= tol && std::fabs(x[2] - xyz[2]) <= tol)
          found = p;
      }
      if (found < 0) fail(key.line, "'curx': no particle within 0.25 h of the point");
      c.particle = found;
      m_.curves.push_back(c);
    } else if (k == "pt2d") {
      for (double& v : m_.pt2d) v = ts_.real("the pt2d box");
      m_.has_pt2d = true;
    } else if (k == "tecp" || k == "para") {
      bool on = true;
      if (!ts_.at_end() && (key4(ts_.peek().text) == "on" || key4(ts_.peek().text) == "off")) on = on_off(key);
      (k == "tecp" ? m_.tecplot : m_.paraview) = on;
    } else if (k == "smoo") {  // the current version's smoothed pressure (an output)
      if (std::find(m_.anim_vars.begin(), m_.anim_vars.end(), "spre") == m_.anim_vars.end())
        m_.anim_vars.push_back("spre");
    } else if (k == "qulo") {
      m_.load_ramp_time = ts_.real("the load ramp time");
      if (!(m_.load_ramp_time > 0.0)) fail(key.line, "'QuLo': the load ramp time must be positive");
    } else if (k == "damp") {
      m_.damping = ts_.real("the damping coefficient");
      if (!(m_.damping >= 0.0)) fail(key.line, "'Damp': the damping coefficient must not be negative");
    } else if (k == "tlmp") {  // total Lagrangian MPM (the current version)
      m_.tl = true;
      m_.tl_line = key.line;
    } else if (k == "drda") {  // dynamic-relaxation damping (the current version)
      m_.dynamic_relaxation = true;
    } else if (k == "uvfp") {  // the current version's volume update from F
      m_.uvf = true;
    } else if (k == "hdf5") {  // extension: HDF5 + XDMF animation series
      bool on = true;
      if (!ts_.at_end() && (key4(ts_.peek().text) == "on" || key4(ts_.peek().text) == "off")) on = on_off(key);
      m_.hdf5 = on;
    } else if (k == "deto") {
      double xyz[3];
      for (double& v : xyz) v = ts_.real("the detonation point");
      if (m_.deto.size() >= 30) fail(key.line, "at most 10 detonation points ('deto')");
      for (double v : xyz) m_.deto.push_back(v);
    } else if (k == "bulk") {
      m_.bulk_q1 = ts_.real("q1");
      m_.bulk_q2 = ts_.real("q2");
      if (!(m_.bulk_q1 >= 0.0) || !(m_.bulk_q2 >= 0.0))
        fail(key.line, "bulk viscosity coefficients must not be negative");
      m_.has_bulk = true;
    } else if (k == "gimp") {
      m_.gimp = true;
      gimp_line_ = key.line;
    } else if (k == "bimp") {
      m_.bspline = true;
      bimp_line_ = key.line;
    } else if (k == "cont") {
      if (ts_.at_end()) fail(key.line, "'cont' needs 'lagr mu normbody'");
      const Token& how = ts_.next();
      if (key4(how.text) != "lagr")
        fail(how.line, "'cont': only 'lagr' (multi-velocity grid contact) is supported, found '" + how.text + "'");
      m_.contact_mu = ts_.real("the friction coefficient");
      if (!(m_.contact_mu >= 0.0)) fail(key.line, "'cont': friction coefficient must not be negative");
      const Token& nbt = ts_.peek();
      const long nb = ts_.integer("the normal body (0, 1 or 2)");
      if (nb < 0 || nb > 2) fail(nbt.line, "'cont': normal body must be 0 (average), 1 or 2");
      m_.contact_normbody = int(nb);
      m_.contact = true;
      m_.contact_line = key.line;
    } else if (k == "endi") {
      ended_ = true;
      finish(key.line);
      break;
    } else if (k == "sgmp") {
      m_.sg = true;
      sgmp_line_ = key.line;
    } else {
      double number;
      if (parse_real(key.text, number))
        fail(key.line, "'" + key.text + "' is a number where a card's keyword was expected: the card before it has more numbers than it "
                     "takes (docs/DECK_FORMAT.md lists each card's; a null material takes density, bulk modulus and "
                     "viscosity in a current deck, density and wave speed in a book deck)");
      fail(key.line, "unknown keyword '" + key.text + "'");
    }
  }
  if (!ended_) fail(ts_.line(), "end of file reached before 'endi'");
  return std::move(m_);
}

std::string DeckReader::output_var(int line) {
  if (ts_.at_end()) fail(line, "missing output variable name");
  const Token& t = ts_.next();
  std::string v = t.text;
  for (char& ch : v) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (v.size() > 4) v = v.substr(0, 4);
  if (!is_output_variable(v)) fail(t.line, "unknown output variable '" + t.text + "'");
  return v;
}

int DeckReader::body_index(const Token& at, long ib) {
  if (ib < 1 || ib > long(m_.bodies.size()))
    fail(at.line, "body " + std::to_string(ib) + " does not exist (" + std::to_string(m_.bodies.size()) +
                      " bodies defined so far)");
  return int(ib - 1);
}

int DeckReader::particle_index(const Token& at, long pid) {
  if (pid < 1 || pid > m_.nbmp)
    fail(at.line, "particle " + std::to_string(pid) + " out of range 1.." + std::to_string(m_.nbmp));
  return int(pid - 1);
}

Model read_deck(const std::string& path, double memory_budget, const RuleRequest& rules) {
  return DeckReader(TokenStream::from_file(path), memory_budget, rules).read();
}

Model read_deck_text(const std::string& text, const std::string& name, double memory_budget,
                     const RuleRequest& rules) {
  return DeckReader(TokenStream::from_string(text, name), memory_budget, rules).read();
}

}  // namespace mpm3d
