// DataOut: the Fortran E12.4 numbers of the legacy plot files and the particle variables
// of the animation and curve output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "input/data_in.hpp"
#include "io/ascii_out.hpp"
#include "io/data_out.hpp"

TEST(DataOut, FortranE12_4) {
  // E12.4: 12 characters, right-aligned, mantissa 0.dddd, signed two-digit exponent.
  EXPECT_EQ(mpm3d::fortran_e12_4(1.326e-4), "  0.1326E-03");
  EXPECT_EQ(mpm3d::fortran_e12_4(187258.43), "  0.1873E+06");
  EXPECT_EQ(mpm3d::fortran_e12_4(-39.99), " -0.3999E+02");
  EXPECT_EQ(mpm3d::fortran_e12_4(0.0), "  0.0000E+00");
  EXPECT_EQ(mpm3d::fortran_e12_4(1.0), "  0.1000E+01");
  EXPECT_EQ(mpm3d::fortran_e12_4(0.5), "  0.5000E+00");
  // Rounding carries into the exponent: 9.99996 -> 0.1000E+02.
  EXPECT_EQ(mpm3d::fortran_e12_4(9.99996), "  0.1000E+02");
  EXPECT_EQ(mpm3d::fortran_e12_4(-2.5e-17), " -0.2500E-16");
}

// The same E12.4 text as printf's "%.3E" digits rearranged (the formatter's first form),
// over every exponent: the plot files are compared with the original's as text.
TEST(DataOut, FortranE12_4AsPrintfsDigits) {
  std::mt19937_64 bits(11);
  for (int i = 0; i < 100000; ++i) {
    const uint64_t b = bits();
    double v;
    std::memcpy(&v, &b, sizeof v);
    if (!std::isfinite(v) || v == 0.0) continue;
    char e[32], want[64];
    std::snprintf(e, sizeof e, "%.3E", std::fabs(v));
    const int exponent = std::atoi(e + 6) + 1;
    std::snprintf(want, sizeof want, "%12s", (std::string(v < 0 ? "-" : "") + "0." + e[0] + e[2] + e[3] + e[4] + "E" +
                                              (exponent < 0 ? "-" : "+") + (std::abs(exponent) < 10 ? "0" : "") +
                                              std::to_string(std::abs(exponent))).c_str());
    ASSERT_EQ(mpm3d::fortran_e12_4(v), want) << v;
  }
}

TEST(DataOut, ParticleVariables) {
  mpm3d::Model m = mpm3d::read_deck_text(
      "nbmp 2 nbbo 1 nmat 1 spx 0 4 spy 0 4 spz 0 4 dcel 1 endt 1\n"
      "mate 1 sjcf 2.0 200.0 0.25 0.1 0.2 1.0 0.0 1.0 0.5\n"
      "part poin 1 2\n 1 1 0.25 1 1 1\n 2 1 0.25 2 1 1\n"
      "velo node 1 3 -4 0 endv\nendi\n",
      "vars.mpm");
  auto& P = m.particles;
  // Particle 1: sigma = (0.2, 0.1, 0.1, 0, 0, 0): p = -0.4/3, deviator (0.2/3, -0.1/3,
  // -0.1/3), von Mises sqrt(3/2 s:s) = 0.1; |v| = 5, mass 0.25: engk = 3.125.
  const double s1[6] = {0.2, 0.1, 0.1, 0.0, 0.0, 0.0};
  for (int c = 0; c < 6; ++c) P.sig[c] = s1[c];
  EXPECT_NEAR(mpm3d::particle_variable(m, "seqv", 0), 0.1, 1e-15);
  EXPECT_NEAR(mpm3d::particle_variable(m, "pres", 0), -0.4 / 3.0, 1e-16);
  EXPECT_EQ(mpm3d::particle_variable(m, "engk", 0), 3.125);
  EXPECT_EQ(mpm3d::particle_variable(m, "velx", 0), 3.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "vely", 0), -4.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "mat", 0), 1.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "volu", 0), 0.125);  // mass / rho0
  // Particle 2: pure shear sigma_xy = 0.3: seqv = sqrt(3) * 0.3, pressure 0.
  P.sig[6 + 5] = 0.3;
  EXPECT_NEAR(mpm3d::particle_variable(m, "seqv", 1), std::sqrt(3.0) * 0.3, 1e-15);
  EXPECT_EQ(mpm3d::particle_variable(m, "pres", 1), 0.0);
  // Failure strain 0.5: damage = epeff / 0.5 (capped at 1), failed once epeff >= 0.5.
  P.epeff[1] = 0.2;
  EXPECT_NEAR(mpm3d::particle_variable(m, "damg", 1), 0.4, 1e-16);
  EXPECT_EQ(mpm3d::particle_variable(m, "fail", 1), 0.0);
  P.epeff[1] = 0.7;
  EXPECT_EQ(mpm3d::particle_variable(m, "damg", 1), 1.0);
  EXPECT_EQ(mpm3d::particle_variable(m, "fail", 1), 1.0);
  // Sound speed sqrt((lambda + 2G) / rho) at the current density 0.25 / 0.125 = 2: sqrt(120).
  EXPECT_NEAR(mpm3d::particle_variable(m, "sspd", 1), std::sqrt(120.0), 1e-13);
}

// smoo: the pressure smoothed through the grid is the pressure itself where the pressure is
// uniform (the weights of each node sum to one over its particles' volumes, the shape
// functions of each particle to one), with trilinear and with GIMP shape functions; 'smoo'
// adds spre to the animation variables.
TEST(SmoothedPressure, UniformPressureIsKept) {
  for (const char* shape : {"", "gimp\n"}) {
    mpm3d::Model m = mpm3d::read_deck_text(std::string("nbmp 48 nbbo 1 nmat 1 spx 0 4 spy 0 4 spz 0 4 dcel 1 endt 1\n"
                                                       "smoo\n") +
                                               shape +
                                               "mate 1 elas 1 100 0.25\npart bloc 1 1 1.0 0.5 0.9 1.3 0.7 4 4 3\nendi\n",
                                           "s.mpm");
    ASSERT_NE(std::find(m.anim_vars.begin(), m.anim_vars.end(), "spre"), m.anim_vars.end());
    for (int p = 0; p < m.particles.np; ++p)
      for (int c = 0; c < 3; ++c) m.particles.sig[6 * size_t(p) + size_t(c)] = -2.5e3;
    mpm3d::update_smoothed_pressure(m);
    ASSERT_EQ(m.spre.size(), 48u);
    for (int p = 0; p < m.particles.np; ++p) {
      EXPECT_NEAR(m.spre[size_t(p)], 2.5e3, 1e-9) << shape << p;
      EXPECT_EQ(mpm3d::particle_variable(m, "spre", p), m.spre[size_t(p)]);
    }
    // A pressure that varies: the smoothed field lies within its range and differs from it.
    for (int p = 0; p < m.particles.np; ++p)
      for (int c = 0; c < 3; ++c) m.particles.sig[6 * size_t(p) + size_t(c)] = -double(p % 7);
    mpm3d::update_smoothed_pressure(m);
    double diff = 0.0;
    for (int p = 0; p < m.particles.np; ++p) {
      EXPECT_GE(m.spre[size_t(p)], -1e-12);
      EXPECT_LE(m.spre[size_t(p)], 6.0 + 1e-12);
      diff += std::fabs(m.spre[size_t(p)] - double(p % 7));
    }
    EXPECT_GT(diff, 1.0);
  }
}

// The animation writers' numbers (AsciiOut, by std::to_chars) are printf's text byte for
// byte: ParaView and TecPlot frames are compared with the original's as text.
TEST(DataOut, AsciiOutWritesPrintfsText) {
  std::vector<double> v = {0.0, -0.0, 1.0, -1.0, 0.5, 9.9999999995e99, 9.99999949999e-5, 1.0e300, -2.5e-308,
                           4.9e-324, std::numeric_limits<double>::max(), std::numeric_limits<double>::quiet_NaN(),
                           -std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity(), 123456789.5, 0.1, 1.0 / 3.0};
  std::mt19937_64 bits(7);
  for (int i = 0; i < 20000; ++i) {  // any bit pattern: every exponent, subnormals, NaNs
    const uint64_t b = bits();
    double x;
    std::memcpy(&x, &b, sizeof x);
    v.push_back(x);
  }
  std::uniform_real_distribution<double> u(-1.0e3, 1.0e3);
  for (int i = 0; i < 20000; ++i) v.push_back(u(bits));  // the usual magnitudes, ties of the last digit
  for (const int digits : {6, 9}) {
    std::string want;
    char one[64];
    for (const double x : v) {
      std::snprintf(one, sizeof one, "%.*E", digits, x);
      want += one;
      want += ' ';
    }
    want += "-12 0 2147483647\n";
    FILE* f = std::tmpfile();
    ASSERT_NE(f, nullptr);
    {
      mpm3d::AsciiOut out(f);
      for (const double x : v) {
        out.sci(x, digits);
        out.put(' ');
      }
      out.integer(-12);
      out.put(' ');
      out.integer(0);
      out.put(' ');
      out.integer(2147483647);
      out.put('\n');
    }
    std::string got(size_t(std::ftell(f)), '\0');
    std::rewind(f);
    ASSERT_EQ(std::fread(&got[0], 1, got.size(), f), got.size());
    std::fclose(f);
    EXPECT_EQ(got, want) << "digits " << digits;
  }
}
