// Pillow through /usr/bin/python3 (pillow.hpp).
#include "support/pillow.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace skybake::test {

PillowImage pillow_read(const std::string& path) {
  const std::string command =
      "/usr/bin/python3 -c 'import sys; from PIL import Image; im = Image.open(sys.argv[1]); "
      "print(im.mode, im.size[0], im.size[1]); print(im.tobytes().hex())' '" +
      path + "' 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run /usr/bin/python3");
  std::string out;
  char buf[4096];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pclose(pipe);
  if (status != 0) throw std::runtime_error("Pillow could not read " + path + ": " + out);
  std::istringstream in(out);
  PillowImage image;
  std::string hex;
  in >> image.mode >> image.width >> image.height >> hex;
  for (size_t i = 0; i + 1 < hex.size(); i += 2)
    image.bytes.push_back(uint8_t(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return image;
}

}  // namespace skybake::test
