#include "lib/input_file.h"

#include <sys/stat.h>

#include <fstream>
#include <sstream>

#include "lib/case_error.h"

namespace needle {

std::string ReadInputFile(const std::string& path, const std::string& what) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    throw CaseError(path + ": cannot open the " + what + " for reading");
  }
  if (S_ISDIR(st.st_mode)) throw CaseError(path + ": is a folder; expected a " + what);
  if (!S_ISREG(st.st_mode)) {
    throw CaseError(path + ": is not a regular file (a device, FIFO or socket); expected a " +
                    what);
  }
  if (st.st_size > kMaxInputBytes) {
    throw CaseError(path + ": is " + std::to_string(st.st_size >> 20) + " MiB; a " + what +
                    " is at most " + std::to_string(kMaxInputBytes >> 20) + " MiB");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CaseError(path + ": cannot open the " + what + " for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw CaseError(path + ": read error");
  return buffer.str();
}

}  // namespace needle
