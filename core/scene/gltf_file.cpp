// Parsing a .gltf / .glb file through tinygltf, with the GLB layout checked first, and the small
// message helpers the loader's files share.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <new>

namespace pathlab::gltf {

namespace {

// Length of the well-formed UTF-8 sequence starting at s[i], or 0.
size_t utf8Length(const std::string& s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  const size_t n = b >= 0xF0 && b <= 0xF4 ? 4 : b >= 0xE0 ? 3 : b >= 0xC2 && b < 0xE0 ? 2 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  }
  return n;
}

}  // namespace

std::string elideDataUris(const std::string& text) {
  static const std::string kMarker = ";base64,";
  std::string out;
  size_t from = 0;
  for (size_t at; (at = text.find(kMarker, from)) != std::string::npos;) {
    size_t end = at + kMarker.size();
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) ||
                                 text[end] == '+' || text[end] == '/' || text[end] == '=')) {
      ++end;
    }
    out.append(text, from, at + kMarker.size() - from);
    if (end - (at + kMarker.size()) > 0) out += "...";
    from = end;
  }
  out.append(text, from, std::string::npos);
  return out;
}

std::string oneLine(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == ' ' || c == 0x7F) {
      // Line breaks, tabs and other control characters (tinygltf quotes raw input bytes).
      if (!out.empty() && out.back() != ' ') out.push_back(' ');
      ++i;
    } else if (c < 0x80) {
      out.push_back(char(c));
      ++i;
    } else if (const size_t n = utf8Length(text, i); n > 0) {
      out.append(text, i, n);  // names may be UTF-8
      i += n;
    } else {
      out.push_back('?');
      ++i;
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

std::string quotedName(const std::string& name) { return name.empty() ? "" : " '" + name + "'"; }

namespace {

uint32_t readU32(const std::vector<unsigned char>& bytes, size_t offset) {
  return uint32_t(bytes[offset]) | uint32_t(bytes[offset + 1]) << 8 |
         uint32_t(bytes[offset + 2]) << 16 | uint32_t(bytes[offset + 3]) << 24;
}

// glTF 2.0 spec, sec. 4.4 (GLB file format), checked before tinygltf so a truncated file gets a
// precise message. Returns the length the header declares.
uint32_t checkGlbLayout(const std::vector<unsigned char>& bytes) {
  const size_t size = bytes.size();
  if (size < 12) {
    throw LoadError("truncated binary glTF: " + std::to_string(size) +
                    " bytes, the header needs 12");
  }
  if (const uint32_t version = readU32(bytes, 4); version != 2) {
    throw LoadError("binary glTF version " + std::to_string(version) + " is not supported");
  }
  const uint32_t length = readU32(bytes, 8);
  if (length > size) {
    throw LoadError("truncated binary glTF: the header declares " + std::to_string(length) +
                    " bytes, the file has " + std::to_string(size));
  }
  if (length < 20) throw LoadError("truncated binary glTF: no JSON chunk");
  const uint64_t jsonLength = readU32(bytes, 12);
  if (readU32(bytes, 16) != 0x4E4F534Au)
    throw LoadError("binary glTF: the first chunk is not JSON");
  const uint64_t jsonEnd = 20 + jsonLength;
  if (jsonEnd > length) {
    throw LoadError("truncated binary glTF: the JSON chunk (" + std::to_string(jsonLength) +
                    " bytes) extends past the end of the file");
  }
  if (jsonEnd < length) {
    if (jsonEnd + 8 > length) throw LoadError("truncated binary glTF: incomplete BIN chunk header");
    const uint64_t binLength = readU32(bytes, size_t(jsonEnd));
    if (jsonEnd + 8 + binLength > length) {
      throw LoadError("truncated binary glTF: the BIN chunk (" + std::to_string(binLength) +
                      " bytes) extends past the end of the file");
    }
  }
  return length;
}

// tinygltf converts "extras" and "extensions" to its own values recursively: a hostile nesting
// depth overflows the stack (a crash, not an exception), so refuse it before parsing.
void checkJsonNesting(const unsigned char* json, size_t size) {
  constexpr int kMaxDepth = 512;
  int depth = 0;
  bool inString = false, escaped = false;
  for (size_t i = 0; i < size; ++i) {
    const unsigned char c = json[i];
    if (inString) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) {
        throw LoadError("JSON nested deeper than " + std::to_string(kMaxDepth) + " levels");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace

tinygltf::Model parseFile(const std::string& path, Warnings& warnings) {
  const std::vector<unsigned char> bytes = readRegularFile(path);
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (!binary && extension == ".glb") throw LoadError("not a binary glTF file (bad magic bytes)");
  if (bytes.empty()) throw LoadError("empty file");

  tinygltf::Model model;
  tinygltf::TinyGLTF context;
  context.SetImageLoader(&loadImageChecked, &model);
  const std::string baseDir = std::filesystem::path(path).parent_path().string();
  ExternalFiles files(baseDir);
  context.SetFsCallbacks(files.callbacks());
  std::string err, warn;
  bool ok = false;
  try {
    if (binary) {
      const uint32_t length = checkGlbLayout(bytes);
      checkJsonNesting(bytes.data() + 20, readU32(bytes, 12));
      ok = context.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), length, baseDir);
    } else {
      checkJsonNesting(bytes.data(), bytes.size());
      ok = context.LoadASCIIFromString(&model, &err, &warn,
                                       reinterpret_cast<const char*>(bytes.data()),
                                       unsigned(bytes.size()), baseDir);
    }
  } catch (const LoadError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    // tinygltf 2.7 can throw from inside (e.g. vector::at on a zero-length GLB buffer).
    throw LoadError(std::string("cannot load glTF: tinygltf failed on malformed input (") +
                    e.what() + ")");
  }
  // A buffer is required (its refusal fails the load and is in err); an image is not (tinygltf
  // only warns and goes on), but a scene referencing a special file is refused all the same.
  for (const ExternalFiles::Refusal& r : files.refusals()) {
    const bool buffer = !ok && err.find("File read error : " + r.path + " :") != std::string::npos;
    if (ok || buffer) {
      throw LoadError(std::string(buffer ? "buffer" : "image") + " '" + r.relative + "' " +
                      r.problem);
    }
  }
  if (!ok) {
    std::string reason = oneLine(elideDataUris(err));
    throw LoadError("cannot load glTF: " +
                    (reason.empty() ? std::string("tinygltf failed") : reason));
  }
  // tinygltf reports some non-fatal problems in err while succeeding.
  for (const std::string* text : {&err, &warn}) {
    size_t begin = 0;
    while (begin < text->size()) {
      size_t end = text->find('\n', begin);
      if (end == std::string::npos) end = text->size();
      std::string line = oneLine(elideDataUris(text->substr(begin, end - begin)));
      if (!line.empty()) warnings.add("tinygltf: " + line);
      begin = end + 1;
    }
  }
  return model;
}

}  // namespace pathlab::gltf
