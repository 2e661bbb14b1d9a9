// Test support for the glTF loader's tests (tests/gltf_*_test.cpp, material_test.cpp): a builder of small glTF
// documents (JSON, embedded or GLB buffer), a minimal PNG encoder, and checks on loaded scenes and
// on SceneError messages.
#pragma once

#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace pathlab::gltf_test {

namespace fs = std::filesystem;

// ---- helpers ---------------------------------------------------------------------------------

inline fs::path tempDir() {
#ifdef PATHLAB_TEST_TMP
  fs::path dir = fs::path(PATHLAB_TEST_TMP) / "gltf_loader";
#else
  fs::path dir = fs::temp_directory_path() / ("pathlab_gltf_loader_" + std::to_string(getpid()));
#endif
  fs::create_directories(dir);
  return dir;
}

inline std::string writeFile(const std::string& name, const std::string& bytes) {
  const fs::path path = tempDir() / name;
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  return path.string();
}

inline std::string base64(const std::string& in) {
  static const char* kChars = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v =
        uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 | uint8_t(in[i + 2]);
    for (int k = 3; k >= 0; --k) out += kChars[(v >> (6 * k)) & 63];
  }
  if (i + 1 == in.size()) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16;
    out += kChars[(v >> 18) & 63];
    out += kChars[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8;
    out += kChars[(v >> 18) & 63];
    out += kChars[(v >> 12) & 63];
    out += kChars[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// A minimal PNG encoder (stored deflate blocks), enough to give stb real 8- and 16-bit images.
inline uint32_t crc32(const std::string& data) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : data) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

inline void putU32be(std::string& s, uint32_t v) {
  for (int k = 3; k >= 0; --k) s += char((v >> (8 * k)) & 0xff);
}

inline std::string encodePng(int w, int h, int channels, int bits,
                             const std::vector<uint16_t>& samples) {
  std::string raw;
  for (int y = 0; y < h; ++y) {
    raw += char(0);
    for (int x = 0; x < w * channels; ++x) {
      const uint16_t v = samples[size_t(y * w * channels + x)];
      if (bits == 16) raw += char(v >> 8);
      raw += char(v & 0xff);
    }
  }
  std::string z = "\x78\x01";
  uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  for (size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    const size_t len = std::min<size_t>(65535, raw.size() - off);
    z += char(off + len >= raw.size() ? 1 : 0);
    z += char(len & 0xff);
    z += char(len >> 8);
    z += char(~len & 0xff);
    z += char((~len >> 8) & 0xff);
    z += raw.substr(off, len);
    if (off + len >= raw.size()) break;
  }
  putU32be(z, (b << 16) | a);
  auto chunk = [](const std::string& type, const std::string& data) {
    std::string c;
    putU32be(c, uint32_t(data.size()));
    c += type + data;
    putU32be(c, crc32(type + data));
    return c;
  };
  std::string ihdr;
  putU32be(ihdr, uint32_t(w));
  putU32be(ihdr, uint32_t(h));
  const int colourType = channels == 1 ? 0 : channels == 2 ? 4 : channels == 3 ? 2 : 6;
  ihdr += char(bits);
  ihdr += char(colourType);
  ihdr += std::string(3, '\0');
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) +
         chunk("IEND", "");
}

inline std::string str(int v) { return std::to_string(v); }

// Builds a small glTF document: one binary buffer, arrays of raw JSON objects, and by default a
// point light (so the scene has an emitter) appended as an extra root node.
class TestGltf {
 public:
  int view(const void* data, size_t size, size_t stride = 0) {
    while (bin.size() % 4) bin += '\0';
    const size_t offset = bin.size();
    bin.append(static_cast<const char*>(data), size);
    std::string v = R"({"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" +
                    std::to_string(size);
    if (stride) v += R"(,"byteStride":)" + std::to_string(stride);
    return add("bufferViews", v + "}");
  }
  int accessor(int bufferView, int componentType, size_t count, const std::string& type,
               size_t byteOffset = 0, bool normalized = false) {
    return add("accessors", R"({"bufferView":)" + str(bufferView) + R"(,"componentType":)" +
                                str(componentType) + R"(,"count":)" + std::to_string(count) +
                                R"(,"type":")" + type + R"(","byteOffset":)" +
                                std::to_string(byteOffset) +
                                (normalized ? R"(,"normalized":true})" : "}"));
  }
  int vec3(const std::vector<Vec3>& v) {
    return accessor(view(v.data(), v.size() * sizeof(Vec3)), 5126, v.size(), "VEC3");
  }
  int vec2(const std::vector<Vec2>& v) {
    return accessor(view(v.data(), v.size() * sizeof(Vec2)), 5126, v.size(), "VEC2");
  }
  template <class T>
  int indices(const std::vector<T>& v) {
    const int type = sizeof(T) == 1 ? 5121 : sizeof(T) == 2 ? 5123 : 5125;
    return accessor(view(v.data(), v.size() * sizeof(T)), type, v.size(), "SCALAR");
  }
  static std::string primitive(int position, int indices = -1, int normal = -1, int uv = -1,
                               int material = -1, int mode = -1) {
    std::string p = R"({"attributes":{"POSITION":)" + str(position);
    if (normal >= 0) p += R"(,"NORMAL":)" + str(normal);
    if (uv >= 0) p += R"(,"TEXCOORD_0":)" + str(uv);
    p += "}";
    if (indices >= 0) p += R"(,"indices":)" + str(indices);
    if (material >= 0) p += R"(,"material":)" + str(material);
    if (mode >= 0) p += R"(,"mode":)" + str(mode);
    return p + "}";
  }
  int mesh(const std::vector<std::string>& primitives, const std::string& name = "") {
    std::string m = R"({"name":")" + name + R"(","primitives":[)";
    for (size_t i = 0; i < primitives.size(); ++i) m += (i ? "," : "") + primitives[i];
    return add("meshes", m + "]}");
  }
  int add(const std::string& array, const std::string& json) {
    arrays[array].push_back(json);
    return int(arrays[array].size()) - 1;
  }
  int node(const std::string& json) { return add("nodes", json); }
  int root(const std::string& json) {
    const int n = node(json);
    roots.push_back(n);
    return n;
  }
  int scene(const std::vector<int>& nodes) {
    scenes.push_back(nodes);
    return int(scenes.size()) - 1;
  }

  std::string json(bool glb = false) const {
    auto arraysCopy = arrays;
    auto scenesCopy = scenes;
    std::vector<int> rootsCopy = roots;
    std::string lights;
    if (light) {
      const int n = int(arraysCopy["nodes"].size());
      arraysCopy["nodes"].push_back(
          R"({"name":"testLight","translation":[0,10,0],"extensions":{"KHR_lights_punctual":{"light":0}}})");
      for (auto& s : scenesCopy) s.push_back(n);
      rootsCopy.push_back(n);
      lights = R"("KHR_lights_punctual":{"lights":[{"type":"point","intensity":5}]})";
    }
    if (scenesCopy.empty() && withScenes) scenesCopy.push_back(rootsCopy);
    std::ostringstream o;
    o << R"({"asset":{"version":"2.0"})";
    for (const auto& [name, items] : arraysCopy) {
      o << ",\"" << name << "\":[";
      for (size_t i = 0; i < items.size(); ++i) o << (i ? "," : "") << items[i];
      o << "]";
    }
    if (!scenesCopy.empty()) {
      o << R"(,"scenes":[)";
      for (size_t i = 0; i < scenesCopy.size(); ++i) {
        o << (i ? "," : "") << R"({"nodes":[)";
        for (size_t k = 0; k < scenesCopy[i].size(); ++k) o << (k ? "," : "") << scenesCopy[i][k];
        o << "]}";
      }
      o << "]";
    }
    if (!bin.empty()) {
      o << R"(,"buffers":[{"byteLength":)" << bin.size();
      if (!glb) o << R"(,"uri":"data:application/octet-stream;base64,)" << base64(bin) << "\"";
      o << "}]";
    }
    std::string ext = extensions;
    if (!lights.empty()) ext += (ext.empty() ? "" : ",") + lights;
    if (!ext.empty()) o << R"(,"extensions":{)" << ext << "}";
    for (const std::string& member : members) o << "," << member;
    o << "}";
    return o.str();
  }
  std::string write(const std::string& name) const { return writeFile(name, json()); }
  std::string glb() const {
    std::string j = json(true), b = bin;
    while (j.size() % 4) j += ' ';
    while (b.size() % 4) b += '\0';
    std::string out = "glTF";
    auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(uint32_t(12 + 8 + j.size() + (b.empty() ? 0 : 8 + b.size())));
    u32(uint32_t(j.size()));
    u32(0x4E4F534A);
    out += j;
    if (!b.empty()) {
      u32(uint32_t(b.size()));
      u32(0x004E4942);
      out += b;
    }
    return out;
  }

  std::string bin;
  std::map<std::string, std::vector<std::string>> arrays;
  std::vector<std::vector<int>> scenes;
  std::vector<int> roots;
  std::vector<std::string> members;  // raw top-level members, e.g. "\"scene\":1"
  std::string extensions;            // raw members of the top-level "extensions" object
  bool light = true;
  bool withScenes = true;
};

inline const std::vector<Vec3> kTriangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
inline const std::vector<Vec3> kUp = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};

// A one-triangle mesh (normals +z) instanced by one root node with `nodeJson` members.
inline std::string oneTriangle(const std::string& name, const std::string& nodeMembers) {
  TestGltf g;
  const int m = g.mesh({TestGltf::primitive(g.vec3(kTriangle), -1, g.vec3(kUp))});
  g.root(R"({"mesh":)" + str(m) + (nodeMembers.empty() ? "" : "," + nodeMembers) + "}");
  return g.write(name);
}

// One triangle (with uvs) using material 0 of `g`; `g.arrays["materials"]` is filled by the caller.
inline void addTexturedTriangle(TestGltf& g, int material = 0) {
  const std::vector<Vec2> uv = {{0, 0}, {1, 0}, {0, 1}};
  g.root(
      R"({"mesh":)" +
      str(g.mesh({TestGltf::primitive(g.vec3(kTriangle), -1, g.vec3(kUp), g.vec2(uv), material)})) +
      "}");
}

// `text` with the first occurrence of `from` replaced by `to` (a failure if there is none).
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The world-space corners of every triangle, in order: equal for equal geometry however stored.
inline std::vector<Vec3> corners(const SceneDesc& d) {
  std::vector<Vec3> out;
  for (const TriangleMesh& m : d.meshes) {
    for (uint32_t i : m.indices) out.push_back(m.positions[i]);
  }
  return out;
}

inline void expectNear(const Vec3& a, const Vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

inline bool hasWarning(const SceneDesc& d, const std::string& needle) {
  for (const std::string& w : d.warnings) {
    if (w.find(needle) != std::string::npos) return true;
  }
  return false;
}

inline size_t totalTriangles(const SceneDesc& d) {
  size_t n = 0;
  for (const TriangleMesh& m : d.meshes) n += m.triangleCount();
  return n;
}

// Loads `path` expecting SceneError; checks the one-line "PATH: problem" shape and returns it.
inline std::string loadError(const std::string& path) {
  try {
    loadGltf(path);
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\r'), std::string::npos) << msg;
    EXPECT_GT(msg.size(), path.size() + 2) << msg;
    return msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected SceneError, got " << e.what();
    return {};
  }
  ADD_FAILURE() << path << " loaded without error";
  return {};
}

// Every triangle's winding normal agrees with its vertices' shading normals, which are unit.
inline void expectConsistentWinding(const TriangleMesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const Vec3 ng =
        glm::cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(glm::length(m.normals[i[k]]), 1.f, 1e-5f);
      EXPECT_GT(glm::dot(ng, m.normals[i[k]]), 0.f) << "triangle " << t;
    }
  }
}

}  // namespace pathlab::gltf_test
