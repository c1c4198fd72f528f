// Typed parameter lists of the pbrt-v4 scene language: `"float fov" [ 39 ]`, `"rgb L" [1 1 1]`, `"bool twosided"
// true`, `"string filename" "x.exr"` (a single value may go without brackets). Declared types: integer, float,
// point2, vector2, point3, vector3, normal (normal3), rgb, spectrum, blackbody, bool, string, texture; pbrt-v3's
// point, vector and color are read as point3, vector3 and rgb.
//
// Parsing checks the syntax and each value against its declared type (an integer must be a whole number, a float
// finite, a string quoted, a bool true or false; point3 / vector3 / normal counts a multiple of 3, point2 of 2).
// Lookups check the declared type against what the directive expects and mark the parameter used; the parameters
// nobody asked for are reported afterwards as warnings. Every error is a kiln::Error naming the file, the line of
// the parameter and the directive, e.g.
//   scene.pbrt: line 12 (Camera "perspective"): parameter "fov" is declared "integer"; expected float
#pragma once
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/color.h"
#include "core/vec.h"
#include "scenes/pbrt/spectrum.h"
#include "scenes/pbrt/tokenizer.h"

namespace kiln {

enum class PbrtType : uint8_t {
  Integer,
  Float,
  Point2,
  Vector2,
  Point3,
  Vector3,
  Normal,
  Rgb,
  Spectrum,
  Blackbody,
  Bool,
  String,
  Texture
};
const char* pbrt_type_name(PbrtType t);
// s between double quotes, for messages.
std::string in_quotes(std::string_view s);

struct PbrtParam {
  PbrtType type = PbrtType::Float;
  std::string name;
  int line = 0;
  std::vector<float> floats;         // every numeric type except integer
  std::vector<int64_t> ints;         // integer
  std::vector<std::string> strings;  // string, texture, and a spectrum given by name or file
  std::vector<uint8_t> bools;
  mutable bool used = false;
  size_t count() const { return floats.size() + ints.size() + strings.size() + bools.size(); }
};

class PbrtParams {
 public:
  PbrtParams() = default;
  // `context` names the directive in messages (`Shape "sphere"`); `dir` resolves spectrum files.
  PbrtParams(std::string file, std::string context, int line, std::string dir = ".")
      : file_(std::move(file)), context_(std::move(context)), dir_(std::move(dir)), line_(line) {}

  // Reads `"type name" value(s)` pairs from the cursor until the next token is not a quoted string.
  void parse(PbrtCursor& cursor);
  // A name given twice keeps its last value (pbrt-v4 looks parameters up from the end of the list), with a remark.
  void add(PbrtParam p);
  struct Remark {
    int line = 0;
    std::string message;
  };
  const std::vector<Remark>& remarks() const { return remarks_; }
  // Parameters of an `Attribute` directive, consulted when the list itself lacks a name (never reported unused).
  void set_defaults(const PbrtParams* defaults) { defaults_ = defaults; }

  // One value; `def` (or empty) when absent. A present parameter of another type, or with a number of values other
  // than one, is an error.
  std::optional<float> find_float(std::string_view name) const;
  float get_float(std::string_view name, float def) const { return find_float(name).value_or(def); }
  std::optional<int> find_int(std::string_view name) const;
  int get_int(std::string_view name, int def) const { return find_int(name).value_or(def); }
  bool get_bool(std::string_view name, bool def) const;
  std::optional<std::string> find_string(std::string_view name) const;
  std::string get_string(std::string_view name, const std::string& def) const {
    return find_string(name).value_or(def);
  }
  std::optional<Vec3f> find_point3(std::string_view name) const;
  std::optional<Vec3f> find_vector3(std::string_view name) const;
  // Arrays (empty when absent).
  std::vector<float> get_floats(std::string_view name) const;
  std::vector<int64_t> get_ints(std::string_view name) const;
  std::vector<Vec3f> get_point3s(std::string_view name) const;
  std::vector<Vec3f> get_normals(std::string_view name) const;
  std::vector<Vec2f> get_point2s(std::string_view name) const;  // also pbrt-v3's "float uv" (pairs)
  std::vector<Rgb> get_rgbs(std::string_view name) const;       // an "rgb" array (a medium's lattice)
  std::vector<std::string> get_strings(std::string_view name) const;
  // A spectrum: rgb, blackbody, or spectrum (wavelength-value pairs, a named spectrum, or a file of pairs), reduced
  // to RGB for `use` (scenes/pbrt/spectrum.h). Empty when absent or given as a texture (see find_texture).
  std::optional<Rgb> find_spectrum(std::string_view name, SpectrumUse use) const;
  // The spectrum itself when given as a spectrum or blackbody (empty when absent, RGB or a texture).
  std::optional<PiecewiseSpectrum> find_piecewise_spectrum(std::string_view name) const;
  // A float that may also be written as a spectrum (a dielectric's eta): the spectrum's green channel.
  std::optional<float> find_float_or_spectrum(std::string_view name, bool* was_spectrum = nullptr) const;
  // The texture name when the parameter is given as "texture NAME".
  std::optional<std::string> find_texture(std::string_view name) const;

  bool has(std::string_view name) const;
  // Messages for the parameters no lookup asked for ("parameter \"foo\" is not used by Shape ...; ignored").
  std::vector<std::string> unused_messages() const;
  const std::vector<PbrtParam>& params() const { return params_; }
  const std::string& file() const { return file_; }
  const std::string& context() const { return context_; }
  int line() const { return line_; }
  std::string location(int line) const;
  [[noreturn]] void fail(int line, const std::string& message) const;

 private:
  const PbrtParam* find(std::string_view name, std::initializer_list<PbrtType> accepted, const char* expected) const;
  const PbrtParam* find_one(std::string_view name, std::initializer_list<PbrtType> accepted,
                            const char* expected) const;
  std::vector<float> numbers(std::string_view name, PbrtType type, size_t arity) const;
  std::optional<Vec3f> find_triple(std::string_view name, PbrtType type, const char* one) const;
  std::optional<PiecewiseSpectrum> piecewise_spectrum(const PbrtParam& p) const;
  std::string spectrum_file(const PbrtParam& p) const;

  std::string file_, context_, dir_ = ".";
  int line_ = 0;
  std::vector<PbrtParam> params_;
  std::vector<Remark> remarks_;
  const PbrtParams* defaults_ = nullptr;
};

}  // namespace kiln
