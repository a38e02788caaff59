// Fuzz-style test of the scene loader: seeded random mutations of real scenes must either
// load or throw ConfigError. Any other exception fails the test; a crash or hang of the
// parser in this process kills the test binary, which fails it too. Each mutant costs one
// fork() of the TOML guard (about 1-2 ms), so a few thousand run in a few seconds.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "src/scene/config.hpp"
#include "tests/unit/support/config_error.hpp"

namespace panoptic {
namespace {

// Handwritten scenes that use every TOML construct a scene may contain, and some it may
// not (so the mutants reach the validation code as well as the parser).
const char* const kHandwritten[] = {
    "[grid]\nn_cells = 100\nr_in_au = 0.5\nr_out_au = 200.0\n",
    "# ring\n[dust]\ninit = \"gaussian_ring\"\nring_r_au = 30.0\nring_width_au = 2\n"
    "[output]\ntimes_yr = [1e3, 1e4,\n  1e5]  # trailing comment\nfile = 'out/ring.h5'\n",
    "[meta]\ndescription = \"\"\"multi\nline \\\"quoted\\\" \\u00e9 \\U0001F30D\"\"\"\n"
    "reference = '''raw \\ string'''\n[disk]\nmodel = \"lbp\"\ngamma = -0.5\n",
    "grid.r_in_au = 2\nstar = { mass_msun = 0.8, luminosity_lsun = 0.5 }\n"
    "[transport]\ndrift = false\nSt = 1e-2\n",
    "[solver]\nrtol = 1e-8\nmax_steps = 1_000_000\nmax_dt_yr = +0.0\n[gas]\nevolve = "
    "true\n",
    "[grid]\nr_in_au = 1.0\n[unknown]\nx = [1, [2, {a = 1979-05-27T07:32:00Z}]]\n"
    "t = 07:32:00\nd = 1979-05-27\nh = 0x1F\no = 0o17\nb = 0b101\nn = -inf\n",
};

// Fragments that are likely to confuse a TOML parser.
const char* const kTokens[] = {
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    "=",
    ",",
    ".",
    "\"",
    "'",
    "\"\"\"",
    "'''",
    "#",
    "\n",
    "\r\n",
    "\r",
    "\t",
    " ",
    "\\",
    "\\u",
    "\\U",
    "\\u00",
    "\\uD800",
    "\\U00110000",
    "\\x",
    "inf",
    "nan",
    "-",
    "+",
    "_",
    "0x",
    "0o",
    "0b",
    "1e",
    "e+",
    "1979-05-27",
    "T07:32:00",
    "Z",
    "+01:00",
    "true",
    "false",
    "\xc3\xa9",
    "\xe2\x88\x9d",
    "\xf0\x9f\x8c\x8d",
    "\xe2\x82",
    "\xc0\xaf",
    "\xed\xa0\x80",
    "\xff",
    "\xfe",
    "\x7f",
    "\x01",
    "\x1b",
};

// Values that exercise the validation: wrong types, out of range, odd literals.
const char* const kValues[] = {
    "-1",         "0",
    "1e400",      "inf",
    "nan",        "\"x\"",
    "[1, -1]",    "true",
    "250.0",      "1979-05-27",
    "{a = 1}",    "[[1]]",
    "[]",         "\"lbp\"",
    "3",          "1e-3",
    "-0.0",       "9223372036854775807",
    "\"\"",       "[1e3, 1e4]",
    "'''",        "\"\\u00\"",
    "0x7FFFFFFF", "1_000",
    "[1, \"a\"]", "\"powerlaw\"",
};

class Mutator {
 public:
  explicit Mutator(unsigned seed) : rng_(seed) {}

  size_t below(size_t n) { return n == 0 ? 0 : rng_() % n; }

  std::string mutate(std::string s, const std::vector<std::string>& corpus) {
    const size_t n = 1 + below(4);
    for (size_t i = 0; i < n; ++i) mutate_once(s, corpus);
    return s;
  }

  std::string random_override() {
    const auto& keys = scene_keys();
    std::string key = keys[below(keys.size())].key;
    std::string item = key + "=" + kValues[below(std::size(kValues))];
    switch (below(4)) {
      case 0:
        mutate_once(item, {});
        break;
      case 1:
        item = key;  // no '='
        break;
      default:
        break;
    }
    return item;
  }

 private:
  void mutate_once(std::string& s, const std::vector<std::string>& corpus) {
    const size_t at = below(s.size() + 1);
    switch (below(14)) {
      case 0:  // flip a bit
        if (!s.empty()) s[below(s.size())] ^= static_cast<char>(1u << below(8));
        break;
      case 1:  // a random byte, NUL and 0xFF included
        s.insert(at, 1, static_cast<char>(below(256)));
        break;
      case 2:
      case 3:  // a token
        s.insert(at, kTokens[below(std::size(kTokens))]);
        break;
      case 4:
        s.insert(at, 1, '\0');
        break;
      case 5:  // truncate
        s.resize(at);
        break;
      case 6:  // delete a few bytes
        if (at < s.size()) s.erase(at, 1 + below(8));
        break;
      case 7: {  // delete a line
        const auto [b, e] = line_around(s, at);
        s.erase(b, e - b);
        break;
      }
      case 8: {  // duplicate a line
        const auto [b, e] = line_around(s, at);
        s.insert(e, s.substr(b, e - b));
        break;
      }
      case 9: {  // a very long line
        const std::string fill(1 + below(100000), "ax\"[{=#\\ 9."[below(11)]);
        s.insert(at, below(2) ? "\nk = \"" + fill + "\"\n" : fill);
        break;
      }
      case 10: {  // deep nesting
        const size_t depth = 1 + below(3000);
        switch (below(5)) {
          case 0:
            s.insert(at, std::string(depth, '['));
            break;
          case 1:
            s.insert(at, std::string(depth, '{'));
            break;
          case 2:
            s.insert(at, "\na = " + std::string(depth, '[') + "1" +
                             std::string(depth, ']') + "\n");
            break;
          case 3: {
            std::string inline_tables = "\nb = ";
            for (size_t i = 0; i < depth; ++i) inline_tables += "{c = ";
            s.insert(at, inline_tables + "1" + std::string(depth, '}') + "\n");
            break;
          }
          default: {  // dotted keys (deep enough, they crash toml++ 3.3.0)
            std::string dotted = "\nd";
            const size_t levels = below(16) ? depth : 40000;
            for (size_t i = 0; i < levels; ++i) dotted += ".d";
            s.insert(at, dotted + " = 1\n");
          }
        }
        break;
      }
      case 11: {  // a known key with an odd value
        const auto& keys = scene_keys();
        const std::string& key = keys[below(keys.size())].key;
        const size_t dot = key.find('.');
        s += "\n[" + key.substr(0, dot) + "]\n" + key.substr(dot + 1) + " = " +
             kValues[below(std::size(kValues))] + "\n";
        break;
      }
      case 12:  // splice in part of another scene
        if (!corpus.empty()) {
          const std::string& other = corpus[below(corpus.size())];
          const size_t b = below(other.size() + 1);
          s.insert(at, other.substr(b, below(other.size() - b + 1)));
        }
        break;
      default: {  // swap two bytes
        if (s.size() > 1) std::swap(s[below(s.size())], s[below(s.size())]);
      }
    }
  }

  static std::pair<size_t, size_t> line_around(const std::string& s, size_t at) {
    at = std::min(at, s.size());
    const size_t nl = at == 0 ? std::string::npos : s.rfind('\n', at - 1);
    const size_t b = nl == std::string::npos ? 0 : nl + 1;
    const size_t e0 = s.find('\n', at);
    const size_t e = e0 == std::string::npos ? s.size() : e0 + 1;
    return {b, e};
  }

  std::mt19937 rng_;
};

// Printable form of a mutant for a failure message.
std::string escaped(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size() && i < 400; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c < 0x20 || c >= 0x7F || c == '\\') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (s.size() > 400) out += "... (" + std::to_string(s.size()) + " bytes)";
  return out;
}

// Loads one input. Returns true when it loaded; fails the test on anything but a
// ConfigError. A scene that loads must also survive its own resolved_toml().
bool check(const std::string& text, const std::vector<std::string>& overrides,
           const std::string& label) {
  try {
    const Config c = load_scene_text(text, "mutant.toml", overrides);
    const Config back = load_scene_text(c.resolved_toml(), "resolved.toml");
    EXPECT_TRUE(c.values_ == back.values_)
        << label << ": resolved_toml() does not read back";
    return true;
  } catch (const ConfigError& e) {
    EXPECT_GT(std::string(e.what()).size(), 0u) << label;
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << label << ": " << typeid(e).name() << ": " << e.what()
                  << "\ninput: " << escaped(text);
  } catch (...) {
    ADD_FAILURE() << label << ": a non-std exception\ninput: " << escaped(text);
  }
  return false;
}

std::vector<std::string> seed_corpus() {
  std::vector<std::string> corpus{reference_toml()};
  for (const char* scene : kHandwritten) corpus.emplace_back(scene);
  const std::filesystem::path params =
      std::filesystem::path(PANOPTIC_SOURCE_DIR) / "params";
  std::error_code ec;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(params, ec)) {
    if (entry.path().extension() != ".toml") continue;
    // params/scans/ holds scan files (panoptic scan), not scenes
    if (entry.path().parent_path().filename() == "scans") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    // a scene with a base (params/bump.toml) reads it from its folder, which a text has
    // not: its resolved scene stands for it
    if (text.str().starts_with("base = ") ||
        text.str().find("\nbase = ") != std::string::npos)
      corpus.push_back(load_scene(entry.path()).resolved_toml());
    else
      corpus.push_back(text.str());
  }
  return corpus;
}

TEST(ConfigFuzz, SeedCorpusLoads) {
  for (const std::string& scene : seed_corpus()) {
    if (scene.find("[unknown]") != std::string::npos) continue;  // invalid on purpose
    EXPECT_TRUE(check(scene, {}, "seed")) << escaped(scene);
  }
}

TEST(ConfigFuzz, MutantsLoadOrThrowConfigError) {
  constexpr int kMutants = 2500;
  // Fork costs 2-4 ms on a loaded CI machine; the deadline keeps the test short there
  // (the mutants are the same sequence every run, only fewer of them).
  constexpr double kMaxSeconds = 12.0;
  const std::vector<std::string> corpus = seed_corpus();
  Mutator mutator(20240611);
  int loaded = 0;
  const auto start = std::chrono::steady_clock::now();
  int i = 0;
  for (; i < kMutants; ++i) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
        kMaxSeconds) {
      break;
    }
    const std::string text = mutator.mutate(corpus[mutator.below(corpus.size())], corpus);
    std::vector<std::string> overrides;
    if (mutator.below(8) == 0) overrides.push_back(mutator.random_override());
    if (check(text, overrides, "mutant " + std::to_string(i))) ++loaded;
    if (HasFailure()) break;  // one reported input is enough to debug
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ fuzz     ] %d of %d mutants, %d loaded, %.1f s\n", i, kMutants, loaded,
              seconds);
  // The mutants must not all be rejected at the first byte: some reach the validation.
  EXPECT_GT(loaded, 0);
}

// Inputs known to break toml++ (3.3.0 or upstream): each must give a ConfigError.
TEST(ConfigFuzz, KnownParserBreakers) {
  const std::string dotted = [] {
    std::string s = "a";
    for (int i = 0; i < 40000; ++i) s += ".a";
    return s;
  }();
  const std::vector<std::pair<std::string, std::string>> cases = {
      // Upstream issue #294 and PR #301: UB / assertion in parse_key() on these headers
      // (an abort in builds with assertions; Debian's build reports a syntax error).
      {"issue294_bracket_ampersand", "[&"},
      {"pr301_triple_bracket_int", "[[[1]]]"},
      {"pr301_triple_bracket_key", "[[[a]]]"},
      {"pr301_triple_bracket_empty", "[[[]]"},
      {"pr301_double_bracket_equals", "[[="},
      // Found for this test: toml++ 3.3.0 (Debian) recurses once per level of a dotted
      // key and dies of a stack overflow (SIGSEGV) at about 30800 levels with an 8 MiB
      // stack, i.e. on a 62 kB file. The guard turns it into a ConfigError.
      {"deep_dotted_key_segfault", dotted + " = 1\n"},
      {"deep_dotted_table_header_segfault", "[" + dotted + "]\n"},
      {"deep_dotted_array_of_tables_segfault", "[[" + dotted + "]]\n"},
      {"deep_arrays", "a = " + std::string(100000, '[')},
      {"deep_inline_tables", "a = " + std::string(100000, '{')},
      {"many_open_brackets", std::string(100000, '[')},
  };
  for (const auto& [name, text] : cases) {
    const std::string what =
        config_error_message([&] { load_scene_text(text, name + ".toml"); }, name);
    if (what.empty()) continue;  // the failure is recorded
    EXPECT_EQ(what.find(name + ".toml"), 0u) << what;
    if (what.find("crashed") != std::string::npos) {
      std::printf("[ info     ] %s: %s\n", name.c_str(), what.c_str());
    }
  }
  // Large but valid: loads.
  EXPECT_TRUE(check("[meta]\ndescription = \"" + std::string(1 << 20, 'x') + "\"\n", {},
                    "long_string"));
}

TEST(ConfigFuzz, DeepDottedKeyCrashIsLocated) {
  std::string text = "[grid]\nr_in_au = 1.0\n";
  text += "a";
  for (int i = 0; i < 40000; ++i) text += ".a";
  text += " = 1\n";
  try {
    load_scene_text(text, "deep.toml");
    ADD_FAILURE() << "loaded";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    // Where the stack is large enough for toml++ not to crash, the key is just unknown.
    if (what.find("crashed") == std::string::npos) GTEST_SKIP() << "no crash: " << what;
    EXPECT_EQ(what.rfind("deep.toml:3:", 0), 0u) << what;
    EXPECT_NE(what.find("SIGSEGV"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace panoptic
