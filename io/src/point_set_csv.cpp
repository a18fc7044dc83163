#include "shoremesh/io/point_set_csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "shoremesh/error.hpp"
#include "shoremesh/io/atomic_file.hpp"

namespace shoremesh::io {

std::string format_double(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip representation
  return std::string(buf, res.ptr);
}

template <int D>
void write_point_set_csv(const std::filesystem::path& path, const BoxTransform<D>& box, std::span<const Point<D>> points) {
  write_atomically(path, [&](std::ostream& out) {
    out << "# box";
    for (int i = 0; i < D; ++i) out << ' ' << format_double(box.origin[i]);
    out << ' ' << format_double(box.side) << '\n';
    std::string line;
    for (const auto& p : points) {
      line.clear();
      for (int i = 0; i < D; ++i) {
        if (i) line += ',';
        line += format_double(p[i]);
      }
      line += '\n';
      out << line;
    }
  });
}

namespace {

double parse_number(std::string_view field, const std::string& file, std::size_t line) {
  while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
  while (!field.empty() && (field.back() == ' ' || field.back() == '\t' || field.back() == '\r')) field.remove_suffix(1);
  double x = 0;
  const auto res = std::from_chars(field.data(), field.data() + field.size(), x);
  if (res.ec != std::errc() || res.ptr != field.data() + field.size())
    throw InputError("'" + std::string(field) + "' is not a number", file, line);
  if (!std::isfinite(x)) throw InputError("not a finite number", file, line);
  return x;
}

}  // namespace

template <int D>
PointSetFile<D> read_point_set_csv(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the file", file);
  PointSetFile<D> result;
  std::string text;
  std::size_t line = 0;
  bool have_box = false;
  while (std::getline(in, text)) {
    ++line;
    if (text.empty() || text == "\r") continue;
    if (text.rfind("# box", 0) == 0) {
      std::istringstream fields(text.substr(5));
      std::string f;
      std::vector<double> values;
      while (fields >> f) values.push_back(parse_number(f, file, line));
      if (values.size() != D + 1) throw InputError("the box line needs " + std::to_string(D + 1) + " numbers", file, line);
      for (int i = 0; i < D; ++i) result.box.origin[i] = values[std::size_t(i)];
      result.box.side = values[D];
      have_box = true;
      continue;
    }
    if (text[0] == '#') continue;
    Point<D> p;
    std::string_view rest(text);
    for (int i = 0; i < D; ++i) {
      const auto comma = rest.find(',');
      if ((i < D - 1) != (comma != std::string_view::npos))
        throw InputError("expected " + std::to_string(D) + " comma-separated numbers", file, line);
      p[i] = parse_number(rest.substr(0, comma), file, line);
      rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
    }
    result.points.push_back(p);
  }
  if (!have_box) throw InputError("no '# box' line", file);
  return result;
}

template void write_point_set_csv<2>(const std::filesystem::path&, const BoxTransform<2>&, std::span<const Point<2>>);
template void write_point_set_csv<3>(const std::filesystem::path&, const BoxTransform<3>&, std::span<const Point<3>>);
template PointSetFile<2> read_point_set_csv<2>(const std::filesystem::path&);
template PointSetFile<3> read_point_set_csv<3>(const std::filesystem::path&);

}  // namespace shoremesh::io
