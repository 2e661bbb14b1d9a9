#include "core/media/medium_sampling.h"

namespace pathlab {

const char* mediumSamplingName(MediumSampling m) {
  switch (m) {
    case MediumSampling::Distance: return "distance";
    case MediumSampling::Equiangular: return "equiangular";
    case MediumSampling::Mis: return "mis";
  }
  return "?";
}

std::optional<MediumSampling> parseMediumSampling(std::string_view name) {
  for (MediumSampling m : {MediumSampling::Distance, MediumSampling::Equiangular, MediumSampling::Mis})
    if (name == mediumSamplingName(m)) return m;
  return std::nullopt;
}

}  // namespace pathlab
