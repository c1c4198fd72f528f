#include "scenes/ply_loader.h"

#include <bit>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.h"
#include "scenes/parse_util.h"

namespace kiln {
namespace {

enum class PlyType : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

constexpr size_t kPlyTypeSize[] = {1, 1, 2, 2, 4, 4, 4, 8};
constexpr size_t type_size(PlyType t) { return kPlyTypeSize[static_cast<int>(t)]; }
constexpr bool is_integer(PlyType t) { return t != PlyType::F32 && t != PlyType::F64; }

std::optional<PlyType> parse_type(std::string_view s) {
  struct Name {
    std::string_view name;
    PlyType type;
  };
  static constexpr Name kNames[] = {
      {"char", PlyType::I8},   {"int8", PlyType::I8},     {"uchar", PlyType::U8},   {"uint8", PlyType::U8},
      {"short", PlyType::I16}, {"int16", PlyType::I16},   {"ushort", PlyType::U16}, {"uint16", PlyType::U16},
      {"int", PlyType::I32},   {"int32", PlyType::I32},   {"uint", PlyType::U32},   {"uint32", PlyType::U32},
      {"float", PlyType::F32}, {"float32", PlyType::F32}, {"double", PlyType::F64}, {"float64", PlyType::F64}};
  for (const auto& n : kNames)
    if (n.name == s) return n.type;
  return std::nullopt;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::F32;  // list: the element type
  bool is_list = false;
  PlyType count_type = PlyType::U8;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
  int header_line = 0;
  bool has_list() const {
    for (const auto& p : props)
      if (p.is_list) return true;
    return false;
  }
  int find(std::string_view prop) const {
    for (size_t i = 0; i < props.size(); ++i)
      if (!props[i].is_list && props[i].name == prop) return int(i);
    return -1;
  }
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;
  int data_line = 0;  // line on which the body starts (ASCII messages)
};

// Which vertex properties feed which MeshDesc field (property index, or -1).
struct VertexLayout {
  int pos[3] = {-1, -1, -1};
  int normal[3] = {-1, -1, -1};
  int uv[2] = {-1, -1};
  bool has_normals() const { return normal[0] >= 0; }
  bool has_uvs() const { return uv[0] >= 0; }
};

// Error context for one file.
struct Ctx {
  const std::string& file;
  [[noreturn]] void fail(const std::string& where, const std::string& what) const { throw Error(file, where, what); }
};

std::string element_where(const PlyElement& e, uint64_t index) {
  return "element '" + e.name + "' #" + std::to_string(index);
}

PlyHeader parse_header(std::string_view data, const Ctx& ctx) {
  PlyHeader h;
  size_t pos = 0;
  int line_no = 0;
  bool have_format = false;
  auto next_line = [&](std::string_view& line) {
    if (pos >= data.size()) return false;
    size_t nl = data.find('\n', pos);
    if (nl == std::string_view::npos) nl = data.size();
    line = data.substr(pos, nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = nl + 1;
    ++line_no;
    return true;
  };
  std::string_view line;
  if (!next_line(line) || trim(line) != "ply") ctx.fail("", "not a PLY file (first line is not 'ply')");
  for (;;) {
    if (!next_line(line)) ctx.fail("header", "missing end_header (header is truncated)");
    const std::string where = "header line " + std::to_string(line_no);
    const auto tok = split_whitespace(line);
    if (tok.empty()) continue;
    const std::string_view key = tok[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") break;
    if (key == "format") {
      if (tok.size() != 3) ctx.fail(where, "malformed format line");
      if (tok[1] == "ascii")
        h.format = PlyFormat::Ascii;
      else if (tok[1] == "binary_little_endian")
        h.format = PlyFormat::BinaryLittleEndian;
      else if (tok[1] == "binary_big_endian")
        h.format = PlyFormat::BinaryBigEndian;
      else
        ctx.fail(where, "unknown format '" + std::string(tok[1]) + "'");
      if (tok[2] != "1.0" && tok[2] != "1") ctx.fail(where, "unsupported PLY version '" + std::string(tok[2]) + "'");
      have_format = true;
    } else if (key == "element") {
      if (tok.size() != 3) ctx.fail(where, "malformed element line (expected: element NAME COUNT)");
      const auto count = to_int64(tok[2]);
      if (!count || *count < 0) ctx.fail(where, "element count '" + std::string(tok[2]) + "' is not a count");
      h.elements.push_back({std::string(tok[1]), uint64_t(*count), {}, line_no});
    } else if (key == "property") {
      if (h.elements.empty()) ctx.fail(where, "property before any element");
      PlyProperty p;
      if (tok.size() >= 2 && tok[1] == "list") {
        if (tok.size() != 5) ctx.fail(where, "malformed list property (expected: property list COUNT_TYPE TYPE NAME)");
        const auto ct = parse_type(tok[2]), it = parse_type(tok[3]);
        if (!ct) ctx.fail(where, "unknown type '" + std::string(tok[2]) + "'");
        if (!it) ctx.fail(where, "unknown type '" + std::string(tok[3]) + "'");
        if (!is_integer(*ct)) ctx.fail(where, "list count type must be an integer type");
        p = {std::string(tok[4]), *it, true, *ct};
      } else {
        if (tok.size() != 3) ctx.fail(where, "malformed property line (expected: property TYPE NAME)");
        const auto t = parse_type(tok[1]);
        if (!t) ctx.fail(where, "unknown type '" + std::string(tok[1]) + "'");
        p = {std::string(tok[2]), *t, false, PlyType::U8};
      }
      h.elements.back().props.push_back(std::move(p));
    } else {
      ctx.fail(where, "unknown header keyword '" + std::string(key) + "'");
    }
  }
  if (!have_format) ctx.fail("header", "missing format line");
  h.data_offset = std::min(pos, data.size());
  h.data_line = line_no + 1;
  return h;
}

VertexLayout vertex_layout(const PlyElement& e, const Ctx& ctx) {
  VertexLayout l;
  const std::string where = "element 'vertex' (header line " + std::to_string(e.header_line) + ")";
  const char* const pos_names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    l.pos[k] = e.find(pos_names[k]);
    if (l.pos[k] < 0) ctx.fail(where, std::string("missing property '") + pos_names[k] + "'");
  }
  const int n[3] = {e.find("nx"), e.find("ny"), e.find("nz")};
  if ((n[0] >= 0) != (n[1] >= 0) || (n[0] >= 0) != (n[2] >= 0)) ctx.fail(where, "normals need all of nx, ny, nz");
  if (n[0] >= 0) std::copy(n, n + 3, l.normal);
  static constexpr std::string_view kUvNames[][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& names : kUvNames) {
    const int a = e.find(names[0]), b = e.find(names[1]);
    if (a >= 0 && b >= 0) {
      l.uv[0] = a;
      l.uv[1] = b;
      break;
    }
  }
  return l;
}

int face_index_list(const PlyElement& e, const Ctx& ctx) {
  for (size_t i = 0; i < e.props.size(); ++i) {
    const auto& p = e.props[i];
    if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
      if (!is_integer(p.type))
        ctx.fail("element 'face' (header line " + std::to_string(e.header_line) + ")",
                 "vertex index type must be an integer type");
      return int(i);
    }
  }
  ctx.fail("element 'face' (header line " + std::to_string(e.header_line) + ")",
           "no vertex_indices (or vertex_index) list property");
}

// Adds the fan triangulation of one polygon, validating its size and indices.
struct FaceSink {
  const Ctx& ctx;
  const PlyElement& elem;
  uint64_t vertex_count;
  std::vector<uint32_t>& indices;
  int ascii_line = 0;  // line of the current record in ASCII files; 0 for binary

  std::string where(uint64_t face) const {
    return ascii_line > 0 ? "line " + std::to_string(ascii_line) + " (" + element_where(elem, face) + ")"
                          : element_where(elem, face);
  }
  [[noreturn]] void bad_index(uint64_t face, int64_t index) const {
    ctx.fail(where(face), "vertex index " + std::to_string(index) + " is out of range (" +
                              std::to_string(vertex_count) + " vertices)");
  }
  void check_size(uint64_t face, int64_t n) const {
    if (n < 3) ctx.fail(where(face), "face has " + std::to_string(n) + " vertices (need at least 3)");
  }
  uint32_t checked(uint64_t face, int64_t index) const {
    if (index < 0 || uint64_t(index) >= vertex_count) bad_index(face, index);
    return uint32_t(index);
  }
  // poly[k] for k in [0, n): an index reader.
  template <typename Get>
  void add_polygon(uint64_t face, int64_t n, Get&& poly) {
    check_size(face, n);
    const uint32_t v0 = checked(face, poly(0));
    uint32_t prev = checked(face, poly(1));
    for (int64_t k = 2; k < n; ++k) {
      const uint32_t cur = checked(face, poly(k));
      indices.push_back(v0);
      indices.push_back(prev);
      indices.push_back(cur);
      prev = cur;
    }
  }
};

// ---------------------------------------------------------------------------------------------------------------
// Binary decoding.

template <typename T>
T load_raw(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

template <typename T>
T byte_swapped(T v) {
  if constexpr (sizeof(T) == 1) {
    return v;
  } else {
    using U = std::conditional_t<sizeof(T) == 2, uint16_t, std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>;
    U u;
    std::memcpy(&u, &v, sizeof(T));
    if constexpr (sizeof(T) == 2)
      u = __builtin_bswap16(u);
    else if constexpr (sizeof(T) == 4)
      u = __builtin_bswap32(u);
    else
      u = __builtin_bswap64(u);
    std::memcpy(&v, &u, sizeof(T));
    return v;
  }
}

template <typename T, bool Swap>
T load(const uint8_t* p) {
  const T v = load_raw<T>(p);
  if constexpr (Swap)
    return byte_swapped(v);
  else
    return v;
}

// Calls f.template operator()<T>() with T the C++ type of t.
template <typename F>
decltype(auto) with_type(PlyType t, F&& f) {
  switch (t) {
    case PlyType::I8:
      return f.template operator()<int8_t>();
    case PlyType::U8:
      return f.template operator()<uint8_t>();
    case PlyType::I16:
      return f.template operator()<int16_t>();
    case PlyType::U16:
      return f.template operator()<uint16_t>();
    case PlyType::I32:
      return f.template operator()<int32_t>();
    case PlyType::U32:
      return f.template operator()<uint32_t>();
    case PlyType::F32:
      return f.template operator()<float>();
    case PlyType::F64:
      break;
  }
  return f.template operator()<double>();
}

// Generic single value (slow path only: lists and odd layouts).
double read_number(const uint8_t* p, PlyType t, bool swap) {
  return with_type(t, [&]<typename T>() { return double(swap ? load<T, true>(p) : load<T, false>(p)); });
}
int64_t read_integer(const uint8_t* p, PlyType t, bool swap) {
  return with_type(t, [&]<typename T>() -> int64_t {
    if constexpr (std::is_integral_v<T>)
      return int64_t(swap ? load<T, true>(p) : load<T, false>(p));
    else
      return 0;  // unreachable: list count and index types are checked to be integers in the header
  });
}

// out[i].*field = value of one fixed-offset property in record i (column decode: one type dispatch per column).
template <typename Out>
void decode_column(const uint8_t* base, size_t stride, size_t count, PlyType t, bool swap, std::vector<Out>& out,
                   float Out::*field) {
  with_type(t, [&]<typename T>() {
    if (swap) {
      for (size_t i = 0; i < count; ++i) out[i].*field = float(load<T, true>(base + i * stride));
    } else {
      for (size_t i = 0; i < count; ++i) out[i].*field = float(load<T, false>(base + i * stride));
    }
  });
}

std::vector<size_t> fixed_offsets(const PlyElement& e, size_t& stride) {
  std::vector<size_t> off(e.props.size());
  stride = 0;
  for (size_t i = 0; i < e.props.size(); ++i) {
    off[i] = stride;
    stride += type_size(e.props[i].type);
  }
  return off;
}

// Vertex element with only scalar properties: fixed stride, column decode.
void decode_vertices_fixed(const uint8_t* base, const PlyElement& e, const VertexLayout& l, bool swap, MeshDesc& m) {
  size_t stride = 0;
  const auto off = fixed_offsets(e, stride);
  const size_t n = size_t(e.count);
  m.positions.resize(n);
  const bool packed_xyz =
      !swap && e.props[size_t(l.pos[0])].type == PlyType::F32 && e.props[size_t(l.pos[1])].type == PlyType::F32 &&
      e.props[size_t(l.pos[2])].type == PlyType::F32 && off[size_t(l.pos[1])] == off[size_t(l.pos[0])] + 4 &&
      off[size_t(l.pos[2])] == off[size_t(l.pos[0])] + 8;
  static_assert(sizeof(Vec3f) == 3 * sizeof(float) && std::is_trivially_copyable_v<Vec3f>);
  if (packed_xyz) {
    const uint8_t* p = base + off[size_t(l.pos[0])];
    for (size_t i = 0; i < n; ++i) std::memcpy(&m.positions[i], p + i * stride, sizeof(Vec3f));
  } else {
    constexpr float Vec3f::*kComp[3] = {&Vec3f::x, &Vec3f::y, &Vec3f::z};
    for (int k = 0; k < 3; ++k) {
      const auto pi = size_t(l.pos[k]);
      decode_column(base + off[pi], stride, n, e.props[pi].type, swap, m.positions, kComp[k]);
    }
  }
  if (l.has_normals()) {
    m.normals.resize(n);
    constexpr float Vec3f::*kComp[3] = {&Vec3f::x, &Vec3f::y, &Vec3f::z};
    for (int k = 0; k < 3; ++k) {
      const auto pi = size_t(l.normal[k]);
      decode_column(base + off[pi], stride, n, e.props[pi].type, swap, m.normals, kComp[k]);
    }
  }
  if (l.has_uvs()) {
    m.uvs.resize(n);
    constexpr float Vec2f::*kComp[2] = {&Vec2f::x, &Vec2f::y};
    for (int k = 0; k < 2; ++k) {
      const auto pi = size_t(l.uv[k]);
      decode_column(base + off[pi], stride, n, e.props[pi].type, swap, m.uvs, kComp[k]);
    }
  }
}

// Walks records of an element that has list properties (variable size), validating every length against the
// buffer. on_record(i, ptr, len): ptr[k] = start of property k's data (after the count for lists), len[k] = list
// length. Returns the end of the element's data.
template <typename F>
const uint8_t* walk_records(const PlyElement& e, const uint8_t* p, const uint8_t* end, bool swap, const Ctx& ctx,
                            F&& on_record) {
  std::vector<const uint8_t*> ptr(e.props.size());
  std::vector<uint64_t> len(e.props.size(), 1);
  for (uint64_t i = 0; i < e.count; ++i) {
    for (size_t k = 0; k < e.props.size(); ++k) {
      const auto& prop = e.props[k];
      const size_t avail = size_t(end - p);
      if (!prop.is_list) {
        if (avail < type_size(prop.type)) ctx.fail(element_where(e, i), "file is truncated");
        ptr[k] = p;
        p += type_size(prop.type);
        continue;
      }
      const size_t cs = type_size(prop.count_type);
      if (avail < cs) ctx.fail(element_where(e, i), "file is truncated");
      const int64_t n = read_integer(p, prop.count_type, swap);
      if (n < 0) ctx.fail(element_where(e, i), "negative list length " + std::to_string(n));
      p += cs;
      if (uint64_t(n) > (avail - cs) / type_size(prop.type)) ctx.fail(element_where(e, i), "file is truncated");
      ptr[k] = p;
      len[k] = uint64_t(n);
      p += size_t(n) * type_size(prop.type);
    }
    on_record(i, ptr, len);
  }
  return p;
}

// Fast path: the face element is exactly one list with a 1-byte count and 4-byte indices in native byte order.
template <typename CountT, typename IndexT>
const uint8_t* decode_faces_fast(const uint8_t* p, const uint8_t* end, FaceSink& sink) {
  const uint64_t nv = sink.vertex_count;
  for (uint64_t f = 0; f < sink.elem.count; ++f) {
    if (p >= end) sink.ctx.fail(element_where(sink.elem, f), "file is truncated");
    const int64_t n = int64_t(load_raw<CountT>(p));
    ++p;
    if (n == 3 && end - p >= 12) {
      const IndexT a = load_raw<IndexT>(p), b = load_raw<IndexT>(p + 4), c = load_raw<IndexT>(p + 8);
      // For signed indices a negative value converts to a huge unsigned one and fails the same test.
      if (uint64_t(uint32_t(a)) >= nv || uint64_t(uint32_t(b)) >= nv || uint64_t(uint32_t(c)) >= nv) {
        sink.bad_index(f, uint64_t(uint32_t(a)) >= nv   ? int64_t(a)
                          : uint64_t(uint32_t(b)) >= nv ? int64_t(b)
                                                        : int64_t(c));
      }
      sink.indices.insert(sink.indices.end(), {uint32_t(a), uint32_t(b), uint32_t(c)});
      p += 12;
      continue;
    }
    if (n < 0) sink.ctx.fail(element_where(sink.elem, f), "negative list length " + std::to_string(n));
    if (uint64_t(n) > uint64_t(end - p) / 4) sink.ctx.fail(element_where(sink.elem, f), "file is truncated");
    sink.add_polygon(f, n, [&](int64_t k) { return int64_t(load_raw<IndexT>(p + 4 * k)); });
    p += 4 * n;
  }
  return p;
}

void parse_binary(std::string_view data, const PlyHeader& h, const Ctx& ctx, MeshDesc& m) {
  const bool swap = (h.format == PlyFormat::BinaryLittleEndian) != (std::endian::native == std::endian::little);
  const auto* p = reinterpret_cast<const uint8_t*>(data.data()) + h.data_offset;
  const auto* end = reinterpret_cast<const uint8_t*>(data.data()) + data.size();
  bool have_vertices = false;
  for (const auto& e : h.elements) {
    if (!e.has_list()) {
      size_t stride = 0;
      fixed_offsets(e, stride);
      if (stride > 0 && e.count > uint64_t(end - p) / stride)
        ctx.fail("element '" + e.name + "'", "file is truncated (" + std::to_string(e.count) + " records of " +
                                                 std::to_string(stride) + " bytes declared, " +
                                                 std::to_string(end - p) + " bytes left)");
      if (e.name == "vertex") {
        decode_vertices_fixed(p, e, vertex_layout(e, ctx), swap, m);
        have_vertices = true;
      }
      p += size_t(e.count) * stride;
      continue;
    }
    if (e.name == "vertex") {  // unusual: a list inside vertex records; slow but general
      const VertexLayout l = vertex_layout(e, ctx);
      p = walk_records(e, p, end, swap, ctx, [&](uint64_t, const auto& ptr, const auto&) {
        auto get = [&](int k) { return float(read_number(ptr[size_t(k)], e.props[size_t(k)].type, swap)); };
        m.positions.push_back({get(l.pos[0]), get(l.pos[1]), get(l.pos[2])});
        if (l.has_normals()) m.normals.push_back({get(l.normal[0]), get(l.normal[1]), get(l.normal[2])});
        if (l.has_uvs()) m.uvs.push_back({get(l.uv[0]), get(l.uv[1])});
      });
      have_vertices = true;
    } else if (e.name == "face") {
      if (!have_vertices) ctx.fail("element 'face'", "face element comes before the vertex element");
      const int li = face_index_list(e, ctx);
      const PlyProperty& list = e.props[size_t(li)];
      FaceSink sink{ctx, e, m.positions.size(), m.indices};
      const uint64_t min_record = type_size(list.count_type);
      if (e.count <= uint64_t(end - p) / min_record) m.indices.reserve(size_t(e.count) * 3);
      const bool fast = e.props.size() == 1 && !swap && type_size(list.count_type) == 1 &&
                        (list.type == PlyType::I32 || list.type == PlyType::U32);
      if (fast && list.count_type == PlyType::U8)
        p = list.type == PlyType::I32 ? decode_faces_fast<uint8_t, int32_t>(p, end, sink)
                                      : decode_faces_fast<uint8_t, uint32_t>(p, end, sink);
      else if (fast)
        p = list.type == PlyType::I32 ? decode_faces_fast<int8_t, int32_t>(p, end, sink)
                                      : decode_faces_fast<int8_t, uint32_t>(p, end, sink);
      else
        p = walk_records(e, p, end, swap, ctx, [&](uint64_t f, const auto& ptr, const auto& len) {
          const uint8_t* q = ptr[size_t(li)];
          const size_t sz = type_size(list.type);
          sink.add_polygon(f, int64_t(len[size_t(li)]),
                           [&](int64_t k) { return read_integer(q + size_t(k) * sz, list.type, swap); });
        });
    } else {
      p = walk_records(e, p, end, swap, ctx, [](uint64_t, const auto&, const auto&) {});
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// ASCII decoding: a token stream that knows its line for messages.

class AsciiCursor {
 public:
  AsciiCursor(std::string_view s, int first_line) : s_(s), line_(first_line) {}
  std::string_view next() {
    while (pos_ < s_.size() && is_space(s_[pos_])) {
      if (s_[pos_] == '\n') ++line_;
      ++pos_;
    }
    const size_t start = pos_;
    while (pos_ < s_.size() && !is_space(s_[pos_])) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  int line() const { return line_; }
  size_t remaining() const { return s_.size() - pos_; }

 private:
  std::string_view s_;
  size_t pos_ = 0;
  int line_;
};

void parse_ascii(std::string_view data, const PlyHeader& h, const Ctx& ctx, MeshDesc& m) {
  AsciiCursor cur(data.substr(h.data_offset), h.data_line);
  auto where = [&](const PlyElement& e, uint64_t i) {
    return "line " + std::to_string(cur.line()) + " (" + element_where(e, i) + ")";
  };
  auto token = [&](const PlyElement& e, uint64_t i) {
    const auto t = cur.next();
    if (t.empty()) ctx.fail(where(e, i), "file is truncated (expected more values)");
    return t;
  };
  auto number = [&](const PlyElement& e, uint64_t i, PlyType type) -> double {
    const auto t = token(e, i);
    if (is_integer(type)) {
      if (auto v = to_int64(t)) return double(*v);
      ctx.fail(where(e, i), "expected an integer, got '" + std::string(t.substr(0, 40)) + "'");
    }
    if (auto v = to_double(t)) return *v;
    ctx.fail(where(e, i), "expected a finite number, got '" + std::string(t.substr(0, 40)) + "'");
  };
  auto integer = [&](const PlyElement& e, uint64_t i) -> int64_t {
    const auto t = token(e, i);
    if (auto v = to_int64(t)) return *v;
    ctx.fail(where(e, i), "expected an integer, got '" + std::string(t.substr(0, 40)) + "'");
  };

  bool have_vertices = false;
  std::vector<double> values;
  std::vector<int64_t> poly;
  for (const auto& e : h.elements) {
    // A record without properties has no text: nothing to read, whatever the count (looping over a count of
    // 9e18 empty records would hang).
    if (e.props.empty()) continue;
    // Every value takes at least one character plus a separator: bounds the count before reserving memory.
    if (e.count > (cur.remaining() + 1) / (2 * e.props.size()))
      ctx.fail("element '" + e.name + "'", "file is truncated (" + std::to_string(e.count) + " records declared)");
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    VertexLayout l;
    int li = -1;
    if (is_vertex) {
      l = vertex_layout(e, ctx);
      m.positions.reserve(size_t(e.count));
    }
    if (is_face) {
      if (!have_vertices) ctx.fail("element 'face'", "face element comes before the vertex element");
      li = face_index_list(e, ctx);
      m.indices.reserve(size_t(e.count) * 3);
    }
    FaceSink sink{ctx, e, m.positions.size(), m.indices};
    values.assign(e.props.size(), 0.0);
    for (uint64_t i = 0; i < e.count; ++i) {
      for (size_t k = 0; k < e.props.size(); ++k) {
        const auto& prop = e.props[k];
        if (!prop.is_list) {
          values[k] = number(e, i, prop.type);
          continue;
        }
        const int64_t n = integer(e, i);
        if (n < 0) ctx.fail(where(e, i), "negative list length " + std::to_string(n));
        if (int(k) == li) {
          poly.clear();
          for (int64_t j = 0; j < n; ++j) poly.push_back(integer(e, i));
          sink.ascii_line = cur.line();
          sink.add_polygon(i, n, [&](int64_t j) { return poly[size_t(j)]; });
        } else {
          for (int64_t j = 0; j < n; ++j) number(e, i, prop.type);
        }
      }
      if (is_vertex) {
        auto get = [&](int k) { return float(values[size_t(k)]); };
        m.positions.push_back({get(l.pos[0]), get(l.pos[1]), get(l.pos[2])});
        if (l.has_normals()) m.normals.push_back({get(l.normal[0]), get(l.normal[1]), get(l.normal[2])});
        if (l.has_uvs()) m.uvs.push_back({get(l.uv[0]), get(l.uv[1])});
      }
    }
    if (is_vertex) have_vertices = true;
  }
}

void validate(const MeshDesc& m, const Ctx& ctx) {
  for (size_t i = 0; i < m.positions.size(); ++i)
    if (!is_finite(m.positions[i])) ctx.fail("element 'vertex' #" + std::to_string(i), "non-finite position");
  for (size_t i = 0; i < m.normals.size(); ++i)
    if (!is_finite(m.normals[i])) ctx.fail("element 'vertex' #" + std::to_string(i), "non-finite normal");
  for (size_t i = 0; i < m.uvs.size(); ++i)
    if (!std::isfinite(m.uvs[i].x) || !std::isfinite(m.uvs[i].y))
      ctx.fail("element 'vertex' #" + std::to_string(i), "non-finite texture coordinate");
}

}  // namespace

MeshDesc parse_ply(std::string_view data, const std::string& file) {
  const Ctx ctx{file};
  const PlyHeader h = parse_header(data, ctx);
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  for (const auto& e : h.elements) {
    if (e.name == "vertex" && !vertex)
      vertex = &e;
    else if (e.name == "face" && !face)
      face = &e;
    else if (e.name == "vertex" || e.name == "face")
      ctx.fail("header", "duplicate element '" + e.name + "'");
  }
  if (!vertex) ctx.fail("header", "no 'vertex' element");
  if (!face) ctx.fail("header", "no 'face' element");
  // Validate the layouts before touching the body, so header problems are reported as such.
  vertex_layout(*vertex, ctx);
  face_index_list(*face, ctx);
  if (vertex->count > std::numeric_limits<uint32_t>::max())
    ctx.fail("header", "too many vertices (" + std::to_string(vertex->count) + ")");

  MeshDesc m;
  m.name = std::filesystem::path(file).filename().string();
  if (h.format == PlyFormat::Ascii)
    parse_ascii(data, h, ctx, m);
  else
    parse_binary(data, h, ctx, m);
  validate(m, ctx);
  return m;
}

MeshDesc load_ply(const std::string& path) { return parse_ply(read_file_bytes(path), path); }

}  // namespace kiln
