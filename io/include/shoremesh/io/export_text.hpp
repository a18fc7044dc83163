#pragma once
// Text building shared by the writers: numbers as the shortest decimal that reads back as the same
// double (coordinates round-trip exactly), and `append` to add several pieces to a string in place
// (cheaper than chains of operator+, and free of GCC 12's false -Wrestrict warnings on them).
#include <charconv>
#include <concepts>
#include <string>
#include <string_view>

namespace shoremesh::io {

inline void append_number(std::string& out, double x) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  out.append(buffer, end);
}

inline void append_piece(std::string& out, std::string_view s) { out.append(s); }
inline void append_piece(std::string& out, char c) { out.push_back(c); }
template <std::integral I>
  requires(!std::same_as<I, char>)
void append_piece(std::string& out, I i) {
  char buffer[24];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, i);
  out.append(buffer, end);
}
inline void append_piece(std::string& out, double x) { append_number(out, x); }

template <class... Parts>
void append(std::string& out, const Parts&... parts) {
  (append_piece(out, parts), ...);
}

}  // namespace shoremesh::io
