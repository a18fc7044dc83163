#pragma once
// Number formatting shared by the text writers: the shortest decimal that reads back as the same double,
// so that exported coordinates round-trip exactly.
#include <charconv>
#include <string>

namespace shoremesh::io {

inline void append_number(std::string& out, double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, end);
}

inline std::string number(double x) {
  std::string s;
  append_number(s, x);
  return s;
}

}  // namespace shoremesh::io
