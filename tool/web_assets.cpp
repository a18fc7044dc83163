// The browser editor's files (web/, bundled at build time by tool/CMakeLists.txt), embedded in the binary
// so that `serve` needs no install folder and fetches nothing at run time.
#include <string_view>

#define SHOREMESH_EMBED(name, path)                                            \
  asm(".section .rodata\n"                                                    \
      ".balign 16\n"                                                          \
      ".global " #name "_begin\n" #name "_begin:\n"                          \
      ".incbin \"" path "\"\n"                                                \
      ".global " #name "_end\n" #name "_end:\n"                              \
      ".byte 0\n"                                                             \
      ".previous\n");                                                         \
  extern "C" const char name##_begin[];                                       \
  extern "C" const char name##_end[];

SHOREMESH_EMBED(shoremesh_web_index, SHOREMESH_WEB_INDEX)
SHOREMESH_EMBED(shoremesh_web_app, SHOREMESH_WEB_APP)

namespace shoremesh::tool {

std::string_view web_index_html() {
  return {shoremesh_web_index_begin, std::size_t(shoremesh_web_index_end - shoremesh_web_index_begin)};
}
std::string_view web_app_js() {
  return {shoremesh_web_app_begin, std::size_t(shoremesh_web_app_end - shoremesh_web_app_begin)};
}

}  // namespace shoremesh::tool
