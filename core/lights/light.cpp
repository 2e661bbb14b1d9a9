// Light: what is common to every kind (light.h); the kinds' own code is in their files.
#include "core/lights/light.h"

#include <cmath>
#include <utility>

namespace pathlab {

static_assert(Emitter<AreaLight> && Emitter<PointLight> && Emitter<SpotLight> && Emitter<DirectionalLight> &&
              Emitter<EnvironmentEmitter>);
namespace {
template <size_t... I>
constexpr bool typeIsIndex(std::index_sequence<I...>) {
  return ((std::variant_alternative_t<I, Light::Kind>::kType == static_cast<LightType>(I)) && ...);
}
}  // namespace
static_assert(typeIsIndex(std::make_index_sequence<std::variant_size_v<Light::Kind>>()),
              "type() reads the variant's index as a LightType");

LightBounds Light::lightBounds() const {
  LightBounds b = visit([](const auto& k) { return k.lightBounds(); });
  if (!(b.phi > 0.f) || !std::isfinite(b.phi)) b.phi = 0.f;
  return b;
}

}  // namespace pathlab
