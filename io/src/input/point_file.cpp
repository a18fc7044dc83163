#include "shoremesh/io/point_file.hpp"

#include <fstream>
#include <sstream>

#include "duplicates.hpp"
#include "shoremesh/error.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace detail {

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open file", path);
  // A file of known size read in one piece (not copied through a growing stream buffer); the rest, if it
  // grew or has no size (a pipe), as it comes.
  std::string text;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0 && in) {
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), size);
    text.resize(static_cast<std::size_t>(in.gcount()));
  }
  in.clear();
  std::ostringstream rest;
  rest << in.rdbuf();
  if (in.bad()) throw InputError("cannot read file", path);
  if (rest.tellp() > 0) text += rest.str();
  return text;
}

}  // namespace detail

PointFile parse_point_file_text(std::string_view text, const std::string& name) {
  using namespace detail;
  PointFile out;
  bool seen_record = false;  // a header is allowed only before the first record
  std::size_t first_data_line = 0;
  for_each_line(text, [&](std::string_view raw, std::size_t line) {
    const std::string_view body = strip_comment(raw);
    if (body.empty()) return;
    const auto fields = split_fields(body);
    if (!seen_record) {
      seen_record = true;
      bool any_numeric = false, all_names = true;
      for (auto f : fields) {
        if (looks_numeric(f)) any_numeric = true;
        if (f.empty()) all_names = false;
      }
      if (!any_numeric && all_names) return;  // header line of column names
    }
    if (fields.size() != 2 && fields.size() != 3)
      throw InputError("expected 2 or 3 numbers, found " + std::to_string(fields.size()) + " columns", name, line);
    if (out.dimension == 0) {
      out.dimension = static_cast<int>(fields.size());
      first_data_line = line;
    } else if (static_cast<int>(fields.size()) != out.dimension) {
      throw InputError("mixed 2 and 3 columns: " + std::to_string(fields.size()) + " columns here, " +
                           std::to_string(out.dimension) + " on line " + std::to_string(first_data_line),
                       name, line);
    }
    std::array<double, 3> v{};
    for (std::size_t c = 0; c < fields.size(); ++c) {
      if (fields[c].empty()) throw InputError("empty field in column " + std::to_string(c + 1), name, line);
      switch (parse_double(fields[c], v[c])) {
        case NumberStatus::Ok: break;
        case NumberStatus::NotANumber:
          throw InputError("column " + std::to_string(c + 1) + ": " + quoted(fields[c]) + " is not a number", name, line);
        case NumberStatus::NotFinite:
          throw InputError("column " + std::to_string(c + 1) + ": " + quoted(fields[c]) + " is not a finite number",
                           name, line);
      }
    }
    if (out.dimension == 2)
      out.points2.push_back({v[0], v[1]});
    else
      out.points3.push_back({v[0], v[1], v[2]});
    out.lines.push_back(line);
  });
  if (out.lines.empty()) throw InputError("no points", name);
  std::optional<std::pair<std::size_t, std::size_t>> dup =
      out.dimension == 2 ? find_duplicate(out.points2) : find_duplicate(out.points3);
  if (dup) {
    const std::size_t later = out.lines[dup->first], earlier = out.lines[dup->second];
    throw InputError("duplicate point: line " + std::to_string(later) + " repeats line " + std::to_string(earlier), name,
                     later);
  }
  return out;
}

PointFile read_point_file(const std::string& path) {
  return parse_point_file_text(detail::read_text_file(path), path);
}

}  // namespace shoremesh::io
