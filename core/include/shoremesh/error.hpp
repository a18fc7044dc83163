#pragma once
// Errors as typed exceptions that carry their context (file, line, point index), caught once at the tool
// boundary and printed for a person. InputError is the user's data (exit code 1); everything else that
// escapes is an internal error (exit code 3).
#include <cstddef>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace shoremesh {

// A number for a message: up to 10 significant digits (1.0000001, 1e+300), not std::to_string's six
// decimals (1.000000) or a 300-digit integer.
inline std::string readable(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", x);
  return buffer;
}

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what, std::string file = {}, std::optional<std::size_t> line = {})
      : std::runtime_error(compose(what, file, line)), file_(std::move(file)), line_(line), message_(what) {}

  const std::string& file() const { return file_; }
  std::optional<std::size_t> line() const { return line_; }  // 1-based line (or element index)
  const std::string& message() const { return message_; }    // without the file:line prefix

 private:
  static std::string compose(const std::string& what, const std::string& file, std::optional<std::size_t> line) {
    std::string s;
    if (!file.empty()) s += file;
    if (line) s += (s.empty() ? "line " : ":") + std::to_string(*line);
    if (!s.empty()) s += ": ";
    return s + what;
  }
  std::string file_;
  std::optional<std::size_t> line_;
  std::string message_;
};

// A parameter choice the algorithm cannot honour (rho <= 1, beta <= rho, too few colours for Lemma 6.1).
class ParameterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace shoremesh

namespace shoremesh {

// An input error about particular points, by their 0-based index in the input given to the engine, so
// that a caller that knows where each point came from (a file line) can say so.
class PointInputError : public InputError {
 public:
  PointInputError(const std::string& what, std::vector<std::size_t> points)
      : InputError(what), points_(std::move(points)) {}
  const std::vector<std::size_t>& points() const { return points_; }

 private:
  std::vector<std::size_t> points_;
};

}  // namespace shoremesh
