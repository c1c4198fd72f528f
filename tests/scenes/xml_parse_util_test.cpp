// Strict number parsing shared by the loaders: whole tokens, finite, in range, with errors naming file/line/element.
#include <gtest/gtest.h>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no kiln::Error thrown";
  return {};
}

TEST(XmlParseUtil, TokensMustBeWholeFiniteNumbers) {
  EXPECT_EQ(to_float("1e+05"), 1e5f);
  EXPECT_EQ(to_float("+2.5"), 2.5f);
  EXPECT_EQ(to_float("-3.73896e-4"), -3.73896e-4f);
  EXPECT_EQ(to_float("7.7898e-009"), 7.7898e-9f);
  for (const char* bad : {"", "abc", "1e999", "1e39", "nan", "NaN", "inf", "-inf", "1.5x", "0x10", "1,5", "--1"})
    EXPECT_FALSE(to_float(bad).has_value()) << bad;
  EXPECT_EQ(to_int64("42"), 42);
  EXPECT_EQ(to_int64("-7"), -7);
  for (const char* bad : {"", "1.0", "1e3", "x", "12a"}) EXPECT_FALSE(to_int64(bad).has_value()) << bad;
  EXPECT_EQ(to_bool("TRUE"), true);
  EXPECT_EQ(to_bool("false"), false);
  EXPECT_FALSE(to_bool("yes").has_value());
  EXPECT_EQ(trim("  a b \r\n"), "a b");
  EXPECT_EQ(split_whitespace(" 1\t2\r\n 3 ").size(), 3u);
}

TEST(XmlParseUtil, ErrorsNameFileLineElementAndProblem) {
  const TextSource src{"scene.xml", 10, "Camera id=1 / Position"};
  EXPECT_EQ(parse_vec3(" 1 2\n 3 ", src), Vec3f(1, 2, 3));
  EXPECT_EQ(error_of([&] { parse_vec3("1 2", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected 3 numbers, got 2 ('1 2')");
  EXPECT_EQ(error_of([&] { parse_vec3("1 2 3 4", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected 3 numbers, got 4 ('1 2 3 4')");
  // The line of the offending token inside a multi-line value.
  EXPECT_EQ(error_of([&] { parse_floats("1 2 3\n4 5 6\n7 abc 9", src); }),
            "scene.xml: line 12 (Camera id=1 / Position): expected a number, got 'abc'");
  EXPECT_EQ(error_of([&] { parse_float("1e999", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): '1e999' is out of range");
  EXPECT_EQ(error_of([&] { parse_float("nan", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): 'nan' is not a finite number");
  EXPECT_EQ(error_of([&] { parse_int("1.5", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected an integer, got '1.5'");
  EXPECT_EQ(error_of([&] { parse_int("", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected an integer, got nothing");
  EXPECT_EQ(error_of([&] { parse_int("99999999999999999999", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): '99999999999999999999' is out of range");
  EXPECT_EQ(error_of([&] { parse_int("abc", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected an integer, got 'abc'");
  EXPECT_EQ(error_of([&] { parse_int("99999999999", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): '99999999999' is out of range");
  EXPECT_EQ(error_of([&] { parse_bool("yes", src); }),
            "scene.xml: line 10 (Camera id=1 / Position): expected true or false, got 'yes'");
  const TextSource no_line{"cfg.json", 0, "camera.fov"};
  EXPECT_EQ(error_of([&] { parse_float("x", no_line); }), "cfg.json: camera.fov: expected a number, got 'x'");
}

TEST(XmlParseUtil, IntegerListsAndLines) {
  const TextSource src{"f.xml", 3, "Faces"};
  EXPECT_EQ(parse_ints(" 1 2 3\n 4 5 6 ", src), (std::vector<int64_t>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(error_of([&] { parse_ints("1 2 3\n4 5.5 6", src); }),
            "f.xml: line 4 (Faces): expected an integer, got '5.5'");
  EXPECT_EQ(line_of_offset("a\r\nb\nc", 5), 3);
  EXPECT_EQ(line_of_offset("abc", 0), 1);
}

TEST(XmlParseUtil, ReadFileBytesNamesMissingFiles) {
  const std::string msg = error_of([] { read_file_bytes("/nonexistent/kiln/file.bin"); });
  EXPECT_EQ(msg.rfind("/nonexistent/kiln/file.bin: cannot open file", 0), 0u) << msg;
  EXPECT_NE(error_of([] { read_file_bytes("/"); }).find("directory"), std::string::npos);
}

}  // namespace
}  // namespace kiln
