// Reading fort.14 and Gmsh 4.1 ASCII meshes back (mesh_file.hpp).
#include "shoremesh/io/mesh_file.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <sstream>
#include <unordered_map>

#include "shoremesh/error.hpp"
#include "text_util.hpp"

namespace shoremesh::io {

namespace {

// The file's lines, read one at a time, split into blank-separated words (a '!' starts a comment in fort.14).
class Lines {
 public:
  Lines(const std::string& path, bool bang_comments) : path_(path), bang_(bang_comments) {
    text_ = detail::read_text_file(path);
    detail::for_each_line(text_, [&](std::string_view line, std::size_t) { lines_.push_back(line); });
  }
  bool done() const { return next_ >= lines_.size(); }
  std::size_t line() const { return next_; }  // 1-based number of the line last read
  std::string_view raw() {
    if (done()) fail("the file ends early");
    return lines_[next_++];
  }
  std::vector<std::string_view> words(std::size_t at_least, const char* what) {
    std::string_view l = raw();
    if (bang_) l = l.substr(0, l.find('!'));
    std::vector<std::string_view> w;
    std::size_t i = 0;
    while (i < l.size()) {
      while (i < l.size() && std::isspace(static_cast<unsigned char>(l[i]))) ++i;
      const std::size_t b = i;
      while (i < l.size() && !std::isspace(static_cast<unsigned char>(l[i]))) ++i;
      if (i > b) w.push_back(l.substr(b, i - b));
    }
    if (w.size() < at_least)
      fail(std::string("expected ") + what + " (" + std::to_string(at_least) + " values), found " +
           std::to_string(w.size()));
    return w;
  }
  long integer(std::string_view w, const char* what) {
    long v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc{} || end != w.data() + w.size()) fail(std::string(what) + " is not an integer: " + std::string(w));
    return v;
  }
  double real(std::string_view w, const char* what) {
    double v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc{} || end != w.data() + w.size() || !std::isfinite(v))
      fail(std::string(what) + " is not a finite number: " + std::string(w));
    return v;
  }
  std::size_t count(std::string_view w, const char* what) {
    const long v = integer(w, what);
    if (v < 0) fail(std::string(what) + " is negative");
    return static_cast<std::size_t>(v);
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(what, path_, std::max<std::size_t>(next_, 1)); }

 private:
  std::string path_;
  bool bang_;
  std::string text_;
  std::vector<std::string_view> lines_;
  std::size_t next_ = 0;
};

}  // namespace

MeshFile read_fort14(const std::string& path) {
  Lines in(path, true);
  MeshFile m;
  m.format = "ADCIRC fort.14";
  m.title = std::string(detail::trim(in.raw()));
  auto head = in.words(2, "NE NP");
  const std::size_t ne = in.count(head[0], "NE"), np = in.count(head[1], "NP");
  std::unordered_map<long, std::uint32_t> index;  // node number -> position
  for (std::size_t i = 0; i < np; ++i) {
    const auto w = in.words(4, "JN X Y DP");
    const long jn = in.integer(w[0], "node number");
    if (!index.emplace(jn, static_cast<std::uint32_t>(i)).second) in.fail("node " + std::to_string(jn) + " given twice");
    m.nodes.push_back({in.real(w[1], "X"), in.real(w[2], "Y"), 0.0});
    m.depths.push_back(in.real(w[3], "DP"));
  }
  auto node = [&](std::string_view w) {
    const long n = in.integer(w, "node number");
    const auto it = index.find(n);
    if (it == index.end()) in.fail("node " + std::to_string(n) + " does not exist");
    return it->second;
  };
  for (std::size_t e = 0; e < ne; ++e) {
    const auto w = in.words(5, "JE NHY NM1 NM2 NM3");
    if (in.integer(w[1], "NHY") != 3) in.fail("only triangles (NHY = 3) are read");
    m.triangles.push_back({node(w[2]), node(w[3]), node(w[4])});
  }
  if (in.done()) return m;  // a grid without boundary information
  auto read_segments = [&](const char* count_name, const char* total_name, std::vector<MeshFileBoundary>& out) {
    const std::size_t segments = in.count(in.words(1, count_name)[0], count_name);
    const std::size_t total = in.count(in.words(1, total_name)[0], total_name);
    std::size_t seen = 0;
    for (std::size_t k = 0; k < segments; ++k) {
      const auto w = in.words(1, "a segment's node count");
      MeshFileBoundary b;
      const std::size_t n = in.count(w[0], "the segment's node count");
      b.type = w.size() > 1 ? static_cast<int>(in.integer(w[1], "the boundary type")) : 0;
      for (std::size_t j = 0; j < n; ++j) b.nodes.push_back(node(in.words(1, "a boundary node")[0]));
      seen += n;
      out.push_back(std::move(b));
    }
    if (seen != total)
      in.fail(std::string(total_name) + " says " + std::to_string(total) + " nodes, the segments list " + std::to_string(seen));
  };
  read_segments("NOPE", "NETA", m.open);
  read_segments("NBOU", "NVEL", m.land);
  return m;
}

MeshFile read_gmsh(const std::string& path) {
  Lines in(path, false);
  MeshFile m;
  m.format = "Gmsh 4.1";
  std::map<long, std::string> physical_names;  // by tag (any dimension: names are for people here)
  std::map<long, long> entity_physical[4];      // entity tag -> its first physical tag, per dimension
  std::unordered_map<long, std::uint32_t> index;
  std::map<long, MeshFileBoundary> lines_by_physical;
  bool format_seen = false;
  while (!in.done()) {
    const std::string section(detail::trim(in.raw()));
    if (section.empty()) continue;
    if (section == "$MeshFormat") {
      const auto w = in.words(3, "version file-type data-size");
      if (w[0] != "4.1" || w[1] != "0") in.fail("only Gmsh 4.1 ASCII is read (version " + std::string(w[0]) + ")");
      format_seen = true;
    } else if (section == "$PhysicalNames") {
      const std::size_t n = in.count(in.words(1, "the name count")[0], "the name count");
      for (std::size_t i = 0; i < n; ++i) {
        const auto w = in.words(3, "dimension tag name");
        std::string name(w[2]);
        name.erase(std::remove(name.begin(), name.end(), '"'), name.end());
        physical_names[in.integer(w[1], "physical tag")] = name;
      }
    } else if (section == "$Entities") {
      const auto w = in.words(4, "entity counts");
      std::size_t counts[4];
      for (int d = 0; d < 4; ++d) counts[d] = in.count(w[static_cast<std::size_t>(d)], "entity count");
      for (int d = 0; d < 4; ++d)
        for (std::size_t i = 0; i < counts[d]; ++i) {
          const auto e = in.words(d == 0 ? 5 : 8, "an entity");
          const std::size_t at = d == 0 ? 4 : 7;  // the physical tag count
          const std::size_t n = in.count(e[at], "physical tag count");
          if (n > 0 && e.size() > at + 1)
            entity_physical[d][in.integer(e[0], "entity tag")] = in.integer(e[at + 1], "physical tag");
        }
    } else if (section == "$Nodes") {
      const auto w = in.words(4, "numEntityBlocks numNodes minNodeTag maxNodeTag");
      const std::size_t blocks = in.count(w[0], "block count");
      for (std::size_t b = 0; b < blocks; ++b) {
        const auto h = in.words(4, "entityDim entityTag parametric numNodesInBlock");
        const std::size_t n = in.count(h[3], "node count");
        std::vector<long> tags;
        for (std::size_t i = 0; i < n; ++i) tags.push_back(in.integer(in.words(1, "a node tag")[0], "node tag"));
        for (std::size_t i = 0; i < n; ++i) {
          const auto c = in.words(3, "x y z");
          if (!index.emplace(tags[i], static_cast<std::uint32_t>(m.nodes.size())).second)
            in.fail("node " + std::to_string(tags[i]) + " given twice");
          m.nodes.push_back({in.real(c[0], "x"), in.real(c[1], "y"), in.real(c[2], "z")});
        }
      }
    } else if (section == "$Elements") {
      const auto w = in.words(4, "numEntityBlocks numElements minElementTag maxElementTag");
      const std::size_t blocks = in.count(w[0], "block count");
      for (std::size_t b = 0; b < blocks; ++b) {
        const auto h = in.words(4, "entityDim entityTag elementType numElementsInBlock");
        const long dim = in.integer(h[0], "entity dimension"), entity = in.integer(h[1], "entity tag");
        const long type = in.integer(h[2], "element type");
        const std::size_t n = in.count(h[3], "element count");
        const std::size_t corners = type == 1 ? 2 : type == 2 ? 3 : type == 4 ? 4 : 0;
        if (corners == 0) in.fail("element type " + std::to_string(type) + " is not read (lines, triangles, tetrahedra)");
        for (std::size_t i = 0; i < n; ++i) {
          const auto e = in.words(1 + corners, "an element");
          std::array<std::uint32_t, 4> v{};
          for (std::size_t k = 0; k < corners; ++k) {
            const long t = in.integer(e[k + 1], "node tag");
            const auto it = index.find(t);
            if (it == index.end()) in.fail("node " + std::to_string(t) + " does not exist");
            v[k] = it->second;
          }
          if (type == 2) m.triangles.push_back({v[0], v[1], v[2]});
          else if (type == 4) ++m.tetrahedra;
          else {
            const long physical = dim >= 0 && dim < 4 && entity_physical[dim].count(entity) ? entity_physical[dim][entity] : 0;
            MeshFileBoundary& group = lines_by_physical[physical];
            group.type = static_cast<int>(physical);
            group.nodes.push_back(v[0]);
            group.nodes.push_back(v[1]);
          }
        }
      }
    } else if (section == "$NodeData") {
      const std::size_t strings = in.count(in.words(1, "string tag count")[0], "string tag count");
      std::string name;
      for (std::size_t i = 0; i < strings; ++i) {
        std::string s(detail::trim(in.raw()));
        s.erase(std::remove(s.begin(), s.end(), '"'), s.end());
        if (i == 0) name = s;
      }
      const std::size_t reals = in.count(in.words(1, "real tag count")[0], "real tag count");
      for (std::size_t i = 0; i < reals; ++i) in.raw();
      const std::size_t ints = in.count(in.words(1, "integer tag count")[0], "integer tag count");
      std::vector<long> tags;
      for (std::size_t i = 0; i < ints; ++i) tags.push_back(in.integer(in.words(1, "an integer tag")[0], "integer tag"));
      const std::size_t n = ints >= 3 ? static_cast<std::size_t>(tags[2]) : 0;
      std::vector<double> values(m.nodes.size(), 0.0);
      for (std::size_t i = 0; i < n; ++i) {
        const auto w = in.words(2, "node tag value");
        const auto it = index.find(in.integer(w[0], "node tag"));
        if (it == index.end()) in.fail("node " + std::string(w[0]) + " does not exist");
        values[it->second] = in.real(w[1], "value");
      }
      if (name == "depth") {
        if (n != m.nodes.size()) in.fail("the depth field covers " + std::to_string(n) + " of " + std::to_string(m.nodes.size()) + " nodes");
        m.depths = std::move(values);
      }
    }
    // Other sections are skipped to their end marker; a section's body never starts with '$'.
  }
  if (!format_seen) throw InputError("not a Gmsh file (no $MeshFormat)", path);
  for (auto& [tag, group] : lines_by_physical) {
    const auto it = physical_names.find(tag);
    group.name = it == physical_names.end() ? "" : it->second;
    m.land.push_back(std::move(group));
  }
  return m;
}

bool is_mesh_file(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  auto ends = [&](const std::string& s) { return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0; };
  return name == "fort.14" || ends(".14") || ends(".fort14") || ends(".msh");
}

MeshFile read_mesh_file(const std::string& path) {
  if (!is_mesh_file(path)) throw InputError("not a mesh file name (fort.14, .14, .fort14, .msh)", path);
  std::string name = std::filesystem::path(path).extension().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return name == ".msh" ? read_gmsh(path) : read_fort14(path);
}

}  // namespace shoremesh::io
