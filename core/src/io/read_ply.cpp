// Stanford PLY: ASCII, binary little- and big-endian. The vertex element
// gives x, y, z of any numeric type; the face element a list property
// vertex_indices (or vertex_index) of any list type; polygons are
// triangulated. Every other element and property is skipped.
#include <cstring>

#include "readers.h"

namespace crestline::io::detail {
namespace {

enum class Encoding { Ascii, Little, Big };

struct Type {
  uint8_t size = 0;  // 0: unknown
  bool is_float = false;
  bool is_signed = false;
};

Type type_named(std::string_view name) {
  if (name == "char" || name == "int8") return {1, false, true};
  if (name == "uchar" || name == "uint8") return {1, false, false};
  if (name == "short" || name == "int16") return {2, false, true};
  if (name == "ushort" || name == "uint16") return {2, false, false};
  if (name == "int" || name == "int32") return {4, false, true};
  if (name == "uint" || name == "uint32") return {4, false, false};
  if (name == "float" || name == "float32") return {4, true, true};
  if (name == "double" || name == "float64") return {8, true, true};
  return {};
}

struct Property {
  std::string name;
  Type type;
  bool is_list = false;
  Type count_type;
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

// Reads one binary value and advances `p` (the caller checked the bounds).
double binary_value(const uint8_t*& p, Type type, bool big_endian) {
  uint8_t bytes[8];
  for (uint8_t k = 0; k < type.size; ++k) bytes[k] = p[big_endian ? type.size - 1 - k : k];
  p += type.size;
  switch (type.size) {
    case 1:
      return type.is_signed ? double(int8_t(bytes[0])) : double(bytes[0]);
    case 2: {
      uint16_t v;
      std::memcpy(&v, bytes, 2);
      return type.is_signed ? double(int16_t(v)) : double(v);
    }
    case 4: {
      if (type.is_float) {
        float f;
        std::memcpy(&f, bytes, 4);
        return double(f);
      }
      uint32_t v;
      std::memcpy(&v, bytes, 4);
      return type.is_signed ? double(int32_t(v)) : double(v);
    }
    default: {
      double d;
      std::memcpy(&d, bytes, 8);
      return d;
    }
  }
}

// Values of one element instance, in property order; a list property
// contributes its count followed by its items.
class ValueReader {
 public:
  ValueReader(const Input& in, Encoding encoding, const uint8_t* data, TextScanner* text)
      : in_(in), encoding_(encoding), p_(data), end_(in.data + in.size), text_(text) {}

  void start_instance(const Element& element, uint64_t index) {
    element_ = &element;
    index_ = index;
    if (encoding_ == Encoding::Ascii && !text_->next_line()) truncated();
  }
  double value(Type type) {
    if (encoding_ == Encoding::Ascii) {
      double v = 0;
      if (!text_->number(v)) truncated();
      return v;
    }
    if (size_t(end_ - p_) < type.size) truncated();
    return binary_value(p_, type, encoding_ == Encoding::Big);
  }
  /// A list's item count, refused when the rest of the file cannot hold it.
  uint64_t list_count(const Property& property) {
    const double count = value(property.count_type);
    const size_t room = encoding_ == Encoding::Ascii ? text_->bytes_left() + 4096 : size_t(end_ - p_);
    if (!(count >= 0) || count > double(room)) {
      fail(ErrorKind::InvalidInput, in_,
           element_->name + " " + std::to_string(index_) + " has a " + property.name + " list of impossible length " +
               std::to_string(count) + ".");
    }
    return uint64_t(count);
  }

 private:
  [[noreturn]] void truncated() {
    fail(ErrorKind::InvalidInput, in_,
         "the data ends inside " + element_->name + " " + std::to_string(index_) + " (the header claims " +
             std::to_string(element_->count) + ").");
  }
  const Input& in_;
  Encoding encoding_;
  const uint8_t* p_;
  const uint8_t* end_;
  TextScanner* text_;
  const Element* element_ = nullptr;
  uint64_t index_ = 0;
};

}  // namespace

TriangleSoup read_ply(const Input& in, const ReadOptions& options) {
  TextScanner header(in.data, in.size, false);
  std::string_view word;
  if (!header.next_line() || !header.word(word) || word != "ply") {
    fail(ErrorKind::InvalidInput, in, "the file does not start with the ply keyword.");
  }
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  bool ended = false;
  while (!ended && header.next_line()) {
    header.word(word);
    if (word == "format") {
      header.word(word);
      if (word == "ascii")
        encoding = Encoding::Ascii;
      else if (word == "binary_little_endian")
        encoding = Encoding::Little;
      else if (word == "binary_big_endian")
        encoding = Encoding::Big;
      else
        fail(ErrorKind::Unsupported, in, "the PLY format '" + std::string(word) + "' is unknown.");
    } else if (word == "element") {
      Element element;
      int64_t count = -1;
      if (!header.word(word) || !header.integer(count) || count < 0) {
        fail(ErrorKind::InvalidInput, in, "line " + std::to_string(header.line_number()) + " is a malformed element.");
      }
      element.name = std::string(word);
      element.count = uint64_t(count);
      elements.push_back(element);
    } else if (word == "property") {
      if (elements.empty()) fail(ErrorKind::InvalidInput, in, "a property comes before any element.");
      Property property;
      std::string_view type_word, name;
      header.word(type_word);
      if (type_word == "list") {
        property.is_list = true;
        header.word(type_word);
        property.count_type = type_named(type_word);
        header.word(type_word);
        if (property.count_type.size == 0 || property.count_type.is_float) property.count_type = {};
      }
      property.type = type_named(type_word);
      if (!header.word(name) || property.type.size == 0 || (property.is_list && property.count_type.size == 0)) {
        fail(ErrorKind::InvalidInput, in,
             "line " + std::to_string(header.line_number()) + " declares a property of unknown type.");
      }
      property.name = std::string(name);
      elements.back().properties.push_back(property);
    } else if (word == "end_header") {
      ended = true;
    }
  }
  if (!ended) fail(ErrorKind::InvalidInput, in, "the header has no end_header line.");

  // Refuse impossible claims before allocating: every instance needs at
  // least one byte per value (binary: the declared sizes; ASCII: a digit and
  // a separator).
  const size_t data_size = size_t(in.data + in.size - reinterpret_cast<const uint8_t*>(header.after_line()));
  for (const Element& element : elements) {
    uint64_t min_bytes = 0;
    for (const Property& p : element.properties) {
      min_bytes += encoding == Encoding::Ascii ? 2 : (p.is_list ? p.count_type.size : p.type.size);
    }
    check_claim(in, options, element.count, min_bytes, data_size, (element.name + " elements").c_str());
  }

  TriangleSoup soup;
  TextScanner body(reinterpret_cast<const uint8_t*>(header.after_line()), data_size, false);
  ValueReader reader(in, encoding, reinterpret_cast<const uint8_t*>(header.after_line()), &body);
  size_t vertices = 0;
  bool have_faces = false;
  std::vector<uint32_t> polygon;
  size_t short_faces = 0;
  for (const Element& element : elements) {
    const bool is_vertex = element.name == "vertex";
    const bool is_face = element.name == "face";
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    for (size_t k = 0; k < element.properties.size(); ++k) {
      const Property& p = element.properties[k];
      if (is_vertex && !p.is_list && p.name.size() == 1 && p.name[0] >= 'x' && p.name[0] <= 'z') {
        xyz[p.name[0] - 'x'] = int(k);
      }
      if (is_face && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = int(k);
    }
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) {
      fail(ErrorKind::InvalidInput, in, "the vertex element lacks an x, y or z property.");
    }
    if (is_vertex) {
      vertices = size_t(element.count);
      soup.positions.resize(3 * vertices);
    }
    have_faces = have_faces || (is_face && indices >= 0);
    for (uint64_t i = 0; i < element.count; ++i) {
      reader.start_instance(element, i);
      for (size_t k = 0; k < element.properties.size(); ++k) {
        const Property& p = element.properties[k];
        if (!p.is_list) {
          const double v = reader.value(p.type);
          for (int c = 0; c < 3; ++c) {
            if (is_vertex && xyz[c] == int(k)) soup.positions[3 * i + c] = v;
          }
          continue;
        }
        const uint64_t n = reader.list_count(p);
        const bool wanted = is_face && int(k) == indices;
        if (wanted) polygon.clear();
        for (uint64_t j = 0; j < n; ++j) {
          const double v = reader.value(p.type);
          if (!wanted) continue;
          if (!(v >= 0 && v < double(vertices))) {
            fail(ErrorKind::InvalidInput, in,
                 "face " + std::to_string(i) + " refers to vertex " + number_text(v) + " but the file has " +
                     std::to_string(vertices) + " vertices.");
          }
          polygon.push_back(uint32_t(v));
        }
        if (!wanted) continue;
        if (n < 3) {
          ++short_faces;
        } else {
          add_polygon(soup, polygon.data(), polygon.size());
        }
      }
      if (is_face && soup.triangle_count() > options.max_triangles) {
        fail(ErrorKind::TooLarge, in,
             "the file has more than " + std::to_string(options.max_triangles) + " triangles.");
      }
    }
  }
  if (!have_faces) fail(ErrorKind::InvalidInput, in, "the file contains no triangles (no face element).");
  if (short_faces > 0) {
    soup.notes.push_back(std::to_string(short_faces) + " faces with fewer than 3 vertices were skipped.");
  }
  finish_soup(soup, in);
  return soup;
}

}  // namespace crestline::io::detail
