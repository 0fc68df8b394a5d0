#include "io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "io/export_error.hpp"

namespace syncap::io {
namespace {

// Creates an empty, uniquely named file beside `path` and returns its name.
std::string create_temporary_beside(const std::string& path) {
  std::string pattern = path + ".partial-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw ExportError(path, std::string("cannot create a file: ") + std::strerror(errno));
  // mkstemp makes it private (0600); an export is an ordinary file others may read.
  ::fchmod(fd, 0644);
  ::close(fd);
  return std::string(name.data());
}

void write_and_close(const std::string& path, const std::string& temporary,
                     const std::function<void(std::ostream&)>& write_content) {
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) throw ExportError(path, "cannot open " + temporary + " for writing");
  write_content(out);
  out.flush();
  if (!out) throw ExportError(path, "writing failed (disk full?)");
  out.close();
  if (out.fail()) throw ExportError(path, "closing failed (disk full?)");
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write_content) {
  const std::string temporary = create_temporary_beside(path);
  try {
    write_and_close(path, temporary, write_content);
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
      throw ExportError(path, std::string("cannot replace the file: ") + std::strerror(errno));
    }
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
}

}  // namespace syncap::io
