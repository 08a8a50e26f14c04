#include "memory.h"

#include <cstdio>
#include <cstring>

namespace crestline::bench {
namespace {

size_t status_kilobytes(const char* field) {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  size_t kb = 0;
  const size_t n = std::strlen(field);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, field, n) == 0 && line[n] == ':') {
      std::sscanf(line + n + 1, "%zu", &kb);
      break;
    }
  std::fclose(f);
  return kb * 1024;
}

}  // namespace

size_t current_rss() { return status_kilobytes("VmRSS"); }
size_t peak_rss() { return status_kilobytes("VmHWM"); }

bool reset_peak_rss() {
  FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  const bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

}  // namespace crestline::bench
