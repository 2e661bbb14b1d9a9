// Environment maps from files (EXR, Radiance HDR) and constant environments from "R,G,B".
#include "core/lights/environment_file.h"

#include "core/image/image_read.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

namespace pathlab {

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// "R,G,B" -> the three numbers, or nullopt when the text is not three numbers.
std::optional<Spectrum> parseColour(const std::string& text) {
  std::istringstream in(text);
  Spectrum c;
  char comma1 = 0, comma2 = 0;
  if (!(in >> c.r >> comma1 >> c.g >> comma2 >> c.b) || comma1 != ',' || comma2 != ',') return std::nullopt;
  in >> std::ws;
  if (!in.eof()) return std::nullopt;
  return c;
}

void setTexels(EnvironmentDesc& desc, const Image& image) {
  const int width = image.width;
  desc.width = width;
  desc.height = image.height;
  desc.texels.resize(static_cast<size_t>(width) * static_cast<size_t>(image.height));
  for (size_t i = 0; i < desc.texels.size(); ++i) {
    const float* p = image.rgb.data() + 3 * i;
    const Spectrum c(p[0], p[1], p[2]);
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b))
      throw EnvironmentError(desc.source + ": texel (" + std::to_string(i % static_cast<size_t>(width)) + ", " +
                             std::to_string(i / static_cast<size_t>(width)) + ") is not a finite number");
    desc.texels[i] = glm::max(c, Spectrum(0.f));  // negative radiance emits nothing
  }
}

}  // namespace

EnvironmentDesc readEnvironment(const std::string& spec) {
  EnvironmentDesc desc;
  desc.source = spec;
  if (const std::optional<Spectrum> c = parseColour(spec)) {
    if (!std::isfinite(c->r + c->g + c->b) || glm::any(glm::lessThan(*c, Spectrum(0.f))))
      throw EnvironmentError(spec + ": an environment colour needs three finite non-negative numbers");
    desc.constant = *c;
    return desc;
  }
  const std::string ext = lowerExtension(spec);
  if (ext != ".exr" && ext != ".hdr")
    throw EnvironmentError(spec + ": an environment is an .exr or .hdr file or a colour R,G,B");
  // Existence by stat, never an open: the reader refuses a FIFO or a device by name.
  if (!std::filesystem::exists(spec)) throw EnvironmentError(spec + ": no such file");
  Image image;
  try {
    image = ext == ".exr" ? readImage(spec) : readRadianceHdr(spec);
  } catch (const ImageError& e) {
    throw EnvironmentError(e.what());
  }
  if (image.width <= 0 || image.height <= 0) throw EnvironmentError(spec + ": the image is empty");
  setTexels(desc, image);
  return desc;
}

}  // namespace pathlab
