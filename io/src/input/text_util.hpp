#pragma once
// Internal helpers shared by the text readers of io/src/input (not installed, not part of the API).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace shoremesh::io::detail {

inline std::string_view trim(std::string_view s) {
  const char* ws = " \t\r\n\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

// Strips a UTF-8 byte-order mark at the start of a file.
inline std::string_view strip_bom(std::string_view text) {
  if (text.size() >= 3 && static_cast<unsigned char>(text[0]) == 0xEF && static_cast<unsigned char>(text[1]) == 0xBB &&
      static_cast<unsigned char>(text[2]) == 0xBF)
    text.remove_prefix(3);
  return text;
}

// Calls f(line_text, line_number) for every line (1-based), '\n' or "\r\n" endings.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  text = strip_bom(text);
  std::size_t number = 0;
  while (!text.empty()) {
    ++number;
    const auto nl = text.find('\n');
    std::string_view line = text.substr(0, nl);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    f(line, number);
    if (nl == std::string_view::npos) break;
    text.remove_prefix(nl + 1);
  }
}

// Removes a '#' comment (whole-line or trailing) and surrounding blanks.
inline std::string_view strip_comment(std::string_view line) {
  const auto h = line.find('#');
  if (h != std::string_view::npos) line = line.substr(0, h);
  return trim(line);
}

// Splits a record into fields: on commas when the line has one (CSV; fields trimmed, empty fields kept so the
// caller can refuse them), otherwise on blanks (spaces and tabs). A CSV field in double quotes (RFC 4180)
// may hold commas: it is one field, given without its quotes (a doubled quote inside stays doubled; an
// unclosed quote runs to the end of the line).
inline std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  if (line.find(',') != std::string_view::npos) {
    while (true) {
      std::string_view rest = trim(line);
      if (!rest.empty() && rest.front() == '"') {
        std::size_t close = 1;
        while (close < rest.size() && !(rest[close] == '"' && (close + 1 == rest.size() || rest[close + 1] != '"')))
          close += rest[close] == '"' ? 2 : 1;
        out.push_back(rest.substr(1, std::min(close, rest.size()) - 1));
        const auto c = close < rest.size() ? rest.find(',', close) : std::string_view::npos;
        if (c == std::string_view::npos) break;
        line = rest.substr(c + 1);
        continue;
      }
      const auto c = line.find(',');
      out.push_back(trim(line.substr(0, c)));
      if (c == std::string_view::npos) break;
      line.remove_prefix(c + 1);
    }
    return out;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

enum class NumberStatus { Ok, NotANumber, NotFinite };

// Strict parse of a whole field as a double: std::from_chars must consume every character ("1.5abc" fails).
// An optional leading '+' is accepted. NaN and infinities parse but are reported as NotFinite.
inline NumberStatus parse_double(std::string_view s, double& value) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty() || s.front() == '+') return NumberStatus::NotANumber;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, value);
  if (ec == std::errc::result_out_of_range) return NumberStatus::NotFinite;
  if (ec != std::errc() || ptr != end) return NumberStatus::NotANumber;
  if (!std::isfinite(value)) return NumberStatus::NotFinite;
  return NumberStatus::Ok;
}

inline bool looks_numeric(std::string_view s) {
  double v;
  return parse_double(s, v) != NumberStatus::NotANumber;
}

// Strict parse of a non-negative integer field.
inline std::optional<long long> parse_integer(std::string_view s) {
  long long v = 0;
  const char* end = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(s.data(), end, v);
  if (s.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return v;
}

// Reads a whole file; throws InputError naming the file when it cannot be opened.
std::string read_text_file(const std::string& path);

inline std::string upper(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Quotes a field for an error message, shortened to 40 characters.
inline std::string quoted(std::string_view s) {
  std::string out = "\"";
  out += s.size() > 40 ? std::string(s.substr(0, 40)) + "..." : std::string(s);
  return out + "\"";
}

}  // namespace shoremesh::io::detail
