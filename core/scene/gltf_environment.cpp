// The environment light a loaded scene gets: the one asked for, or the default light for a file
// that brings no light of its own (ordinary glTF models: viewers light them with an environment),
// emissive textures aside (glowing details do not light a model).
#include "core/scene/gltf_internal.h"

namespace pathlab::gltf {

void addEnvironment(const LoadOptions& options, SceneDesc& desc, Warnings& warnings) {
  if (options.environment) {
    desc.environment = options.environment;
    return;
  }
  if (!options.defaultLight || hasLamp(desc)) return;
  const bool glows = hasEmitter(desc);
  auto white = std::make_shared<EnvironmentDesc>();
  white->source = "default light";
  white->constant = Spectrum(1.f);
  desc.environment = std::move(white);
  // A model whose only emission is textured glows in places but is not lit by it (DamagedHelmet).
  warnings.add(glows ? "the file's only light is its emissive textures: lit also by a uniform white environment "
                       "of radiance 1 (the default light; --no-default-light: without it)"
                     : "the file has no light: lit by a uniform white environment of radiance 1 (the default light)");
}

}  // namespace pathlab::gltf
