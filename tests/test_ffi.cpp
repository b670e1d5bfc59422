// FFI: the free-format deck tokenizer (DECK_FORMAT.md "Reading rules").
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include <string>
#include <vector>

#include "input/data_in.hpp"
#include "input/ffi.hpp"

using mpm3d::DeckError;
using mpm3d::TokenStream;

namespace {

// The tokens view their stream's text: the stream goes with them.
struct AllTokens : std::vector<mpm3d::Token> {
  TokenStream source;
};

AllTokens all_tokens(const std::string& text) {
  AllTokens v;
  v.source = TokenStream::from_string(text, "t.mpm");
  TokenStream reader = v.source;  // a copy shares the text
  while (!reader.at_end()) v.push_back(reader.next());
  return v;
}

// A minimal valid deck body (1 elastic particle) to wrap keyword tests in.
const char* kTail =
    "nmat 1\n"
    "spx 0 4\nspy 0 4\nspz 0 4\n"
    "dcel 1\n"
    "mate 1 elas 1.0 100.0 0.25\n"
    "nbbo 1\n"
    "part bloc 1 1 1.0 0.5 1 1 1 1 1 1\n"
    "endi\n";

}  // namespace

TEST(Ffi, KeywordsAreFirstFourCharactersCaseInsensitive) {
  EXPECT_EQ(mpm3d::key4("endtime"), "endt");
  EXPECT_EQ(mpm3d::key4("endt"), "endt");
  EXPECT_EQ(mpm3d::key4("EndT"), "endt");
  EXPECT_EQ(mpm3d::key4("ENDTIME"), "endt");
  EXPECT_EQ(mpm3d::key4("fixed"), "fixe");
  EXPECT_EQ(mpm3d::key4("Particle"), "part");
  EXPECT_EQ(mpm3d::key4("usf"), "usf");  // shorter than four: kept whole
  EXPECT_NE(mpm3d::key4("endi"), mpm3d::key4("endt"));
}

TEST(Ffi, KeywordSpellingsReachTheSameSetting) {
  // endtime / endt / EndT set the end time (and reset the output interval to it).
  for (const char* kw : {"endtime", "endt", "EndT", "ENDTIME"}) {
    const std::string deck = std::string("nbmp 1\n") + kw + " 0.25\n" + kTail;
    mpm3d::Model m = mpm3d::read_deck_text(deck, "k.mpm");
    EXPECT_EQ(m.endtime, 0.25) << kw;
    EXPECT_EQ(m.outtime, 0.25) << kw;
  }
}

TEST(Ffi, CommentsSeparatorsAndBlankLines) {
  // '!' runs to the end of the line; blanks, tabs and commas all separate; blank lines
  // are skipped but still counted for the line numbers.
  const auto t = all_tokens("nbmp 5 ! comment 7 eight\n\n\t\nspx\t-1.0,,1.0 ,\t2\n!only a comment\nendi!x");
  ASSERT_EQ(t.size(), 7u);
  const char* text[] = {"nbmp", "5", "spx", "-1.0", "1.0", "2", "endi"};
  const int line[] = {1, 1, 4, 4, 4, 4, 6};
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(t[i].text, text[i]) << i;
    EXPECT_EQ(t[i].line, line[i]) << i;
  }
}

TEST(Ffi, CarriageReturnsAreNotPartOfTokens) {
  const auto t = all_tokens("nbmp 5\r\nendi\r\n");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[1].text, "5");
  EXPECT_EQ(t[2].text, "endi");
  EXPECT_EQ(t[2].line, 2);
}

TEST(Ffi, FortranNumbersParse) {
  struct Case {
    const char* text;
    double value;
  } cases[] = {
      {"1.0d-3", 1.0e-3}, {"1.0D3", 1000.0}, {"1e-3", 1.0e-3}, {"-5", -5.0},   {".5", 0.5},
      {"+1.0", 1.0},      {"8.93d-3", 8.93e-3}, {"117.0d3", 117000.0}, {"1E+2", 100.0},
      {"0", 0.0},         {"-.25", -0.25},     {"5.", 5.0},       {"3940", 3940.0},
  };
  for (const auto& c : cases) {
    double v = -999.0;
    EXPECT_TRUE(mpm3d::parse_real(c.text, v)) << c.text;
    // Each literal is the correctly rounded double of the decimal value, as is the C++
    // literal on the right.
    EXPECT_EQ(v, c.value) << c.text;
  }
  long i = 0;
  EXPECT_TRUE(mpm3d::parse_integer("-5", i));
  EXPECT_EQ(i, -5);
  EXPECT_TRUE(mpm3d::parse_integer("+12", i));
  EXPECT_EQ(i, 12);
  EXPECT_TRUE(mpm3d::parse_integer("21172", i));
  EXPECT_EQ(i, 21172);
  EXPECT_TRUE(mpm3d::parse_integer("-99999999999999999", i));  // 18 characters, the most accepted
  EXPECT_EQ(i, -99999999999999999L);
}

TEST(Ffi, GarbageNumbersAreRefused) {
  for (const char* bad : {"1.2.3", "abc", "1e", "--1", "", "-", "+", ".", "e5", "d3", "1.0-3",
                          "1e5.0", "1ee5", "1e--3", "+-1", "1,0", "0x10", "nan", "inf", "1e999",
                          "12abc", "1.0d", "1.0q3x", "1e+"}) {
    double v = 0.0;
    EXPECT_FALSE(mpm3d::parse_real(bad, v)) << "'" << bad << "' was accepted as " << v;
  }
  for (const char* bad : {"1.5", "abc", "1e3", "--1", "", "-", "+", "5x", "1,0"}) {
    long v = 0;
    EXPECT_FALSE(mpm3d::parse_integer(bad, v)) << "'" << bad << "' was accepted as " << v;
  }
}

TEST(Ffi, NonNumericFieldIsAnErrorNamingTheLine) {
  TokenStream ts = TokenStream::from_string("dcel\n\n  1.2.3\n", "deck.mpm");
  ts.next();
  try {
    ts.real("the cell size");
    FAIL() << "1.2.3 accepted";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.file(), "deck.mpm");
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("deck.mpm:3: ", 0), 0u) << w;
    EXPECT_NE(w.find("1.2.3"), std::string::npos) << w;
    EXPECT_NE(w.find("Non Numeric"), std::string::npos) << w;
  }
}

TEST(Ffi, LineOf4096CharactersIsAcceptedAnd4097IsAnError) {
  // 4 + 1 + 4091 = 4096 characters: accepted (a comment fills the rest). The original
  // reads lines of any length and keeps the first 256 characters; the current public
  // decks have comment lines past 200.
  const std::string ok = "endi " + std::string("!") + std::string(4090, 'x');
  ASSERT_EQ(ok.size(), 4096u);
  EXPECT_NO_THROW(TokenStream::from_string("nbmp 1\n" + ok + "\n", "a.mpm"));
  const std::string too_long = ok + "y";
  try {
    TokenStream::from_string("nbmp 1\n\n" + too_long + "\nendi\n", "long.mpm");
    FAIL() << "4097-character line accepted";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.line(), 3);
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("long.mpm:3: ", 0), 0u) << w;
    EXPECT_NE(w.find("4096"), std::string::npos) << w;
  }
}

TEST(Ffi, ValuesContinueOnFollowingLines) {
  TokenStream ts = TokenStream::from_string("grid -1.0\n  2.0 ! half\n\n -3\n4,\n-5 6.5\n", "g.mpm");
  EXPECT_EQ(ts.word("keyword"), "grid");
  const double expect[6] = {-1.0, 2.0, -3.0, 4.0, -5.0, 6.5};
  for (double e : expect) EXPECT_EQ(ts.real("a grid value"), e);
  EXPECT_TRUE(ts.at_end());
  // The same through the deck reader: a box and a material card split over lines.
  const std::string deck =
      "nbmp 1 nmat\n 1\ngrid 0\n 4 0 4\n 0\n 4\ndcel\n1\nendt 1\n"
      "mate 1 elas\n 1.0\n 100.0\n 0.25\nnbbo 1\npart bloc 1 1 1.0 0.5\n1 1 1\n1 1 1\nendi\n";
  mpm3d::Model m = mpm3d::read_deck_text(deck, "split.mpm");
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(m.box_lo[a], 0.0);
    EXPECT_EQ(m.box_hi[a], 4.0);
  }
  ASSERT_EQ(m.mats.size(), 1u);
  EXPECT_EQ(m.mats[0].young, 100.0);
  EXPECT_EQ(m.mats[0].poisson, 0.25);
  // Particle at o + dp/2 = 1.25 along each axis.
  EXPECT_EQ(m.particles.x[0], 1.25);
  EXPECT_EQ(m.particles.x[2], 1.25);
}

TEST(Ffi, EndOfFileInsideAValueIsAnError) {
  TokenStream ts = TokenStream::from_string("spx 0\n", "e.mpm");
  ts.next();
  EXPECT_EQ(ts.real("min"), 0.0);
  EXPECT_THROW(ts.real("max"), DeckError);
}

TEST(Ffi, BinaryCharactersAreRefused) {
  // A control or non-ASCII byte is refused wherever it stands, with its line: at the start
  // of a token and inside one (else "endi\x01" would pass as the keyword endi).
  const std::string cases[] = {std::string("nbmp 1\n\x01x 2\n"), std::string("nbmp 1\nab\x01 2\n"),
                               std::string("nbmp 1\nendi\x7f\n"), std::string("nbmp 1\n1.0\xc3\xa9\n")};
  for (const auto& text : cases) {
    try {
      TokenStream::from_string(text, "b.mpm");
      ADD_FAILURE() << "accepted a binary character in: " << ::testing::PrintToString(text);
    } catch (const DeckError& e) {
      EXPECT_EQ(e.line(), 2) << e.what();
    }
  }
}

TEST(Ffi, MissingFileIsAnErrorNamingTheFile) {
  try {
    TokenStream::from_file("/nonexistent/dir/none.mpm");
    FAIL();
  } catch (const DeckError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/none.mpm"), std::string::npos);
  }
}

// A regular file is read in one piece of its size, a pipe as a stream: both give the same
// tokens and lines (a pipe's size reads 0).
TEST(Ffi, FileAndPipeReadAlike) {
  const std::string text = "mpm3d *** title\nnbmp 2 ! two\n\nendt 1.5e-3\r\nlast line without newline";
  char dir[] = "/tmp/ffi_read_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string file = std::string(dir) + "/deck.mpm", fifo = std::string(dir) + "/pipe.mpm";
  {
    std::ofstream out(file, std::ios::binary);
    out << text;
  }
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] {
    std::ofstream out(fifo, std::ios::binary);
    out << text;
  });
  TokenStream from_pipe = TokenStream::from_file(fifo);
  writer.join();
  TokenStream from_file = TokenStream::from_file(file), from_text = TokenStream::from_string(text, "t");
  for (TokenStream* ts : {&from_file, &from_pipe}) {
    std::vector<std::string> got, want;
    while (!ts->at_end()) got.push_back(ts->next().text + "@" + std::to_string(ts->line()));
    while (!from_text.at_end()) want.push_back(from_text.next().text + "@" + std::to_string(from_text.line()));
    from_text = TokenStream::from_string(text, "t");
    EXPECT_EQ(got, want);
    EXPECT_EQ(got.size(), 9u);
  }
  std::remove(file.c_str());
  std::remove(fifo.c_str());
  rmdir(dir);
}

TEST(Ffi, CommentsAndTheTitleMayHoldAnyText) {
  // The title is the rest of the first line as written (DECK_FORMAT.md: "mpm3... rest of
  // line"), and comments are skipped whatever they hold: UTF-8 (the original group writes
  // Chinese comments), '!' or commas in the title are all kept or skipped as text.
  const std::string deck = std::string("mpm3d *** Taylor bar, \xe6\xb3\xb0\xe5\x8b\x92 (copper)\n") +
                           "! \xe6\xb3\xa8\xe9\x87\x8a: comment\n" + "nbmp 1 ! \xc3\xa9\n" + "endt 0.5\n" + kTail;
  mpm3d::Model m = mpm3d::read_deck_text(deck, "utf8.mpm");
  EXPECT_EQ(m.title, "*** Taylor bar, \xe6\xb3\xb0\xe5\x8b\x92 (copper)");
  EXPECT_EQ(m.nbmp, 1);
}


// A token views its stream's text, which stays put when the stream is moved or copied, also
// where the text is short enough to live inside a std::string.
TEST(Ffi, TokensStayValidWhenTheStreamMoves) {
  TokenStream a = TokenStream::from_string("spx 0 4\n", "m.mpm");
  const mpm3d::Token t = a.peek();
  TokenStream b = std::move(a);
  TokenStream c = b;
  b = TokenStream::from_string("dcel 1\n", "n.mpm");
  EXPECT_EQ(std::string(t.text), "spx");
  EXPECT_EQ(std::string(c.next().text), "spx");
  EXPECT_EQ(std::string(b.next().text), "dcel");
}
