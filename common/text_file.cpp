#include "common/text_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace zonesim {

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << text << '\n';
    if (!f.flush()) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace zonesim
