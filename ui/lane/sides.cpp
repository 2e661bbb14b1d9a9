// Side A and side B started, fed and polled alike.
#include "ui/lane/sides.h"

#include "ui/lane/compare.h"

namespace pathlab::ui {

void Sides::start(RenderLane& lane, const std::shared_ptr<const Scene>& scene, const RenderSettings& settings,
                  bool comparing, const Start& how) {
  lane.start(scene, settings, {comparing ? threadsPerSide(threads_) : threads_, how.targetSpp, how.thumbnailSide, errors_});
}

bool Sides::setComparing(bool on, const std::shared_ptr<const Scene>& scene, const EstimatorState& estimatorB,
                         const Start& how) {
  if (on == b().running()) return false;
  a().stop();
  b().stop();
  start(a(), scene, a().applied(), on, how);
  if (on) {
    start(b(), scene, compareRenderSettings(estimatorB, a().applied()), on, how);
    b().view().setReference(errors_->reference().get());
  } else {
    b() = RenderLane(1);
  }
  return true;
}

bool Sides::apply(const RenderSettings& settingsA, const RenderSettings& settingsB) {
  bool taken = false;
  for (RenderLane* lane : {&a(), &b()})
    if (lane->running() && lane->apply(lane == &a() ? settingsA : settingsB)) taken = true;
  return taken;
}

void Sides::sync(bool userPaused, uint64_t targetSpp, bool timingA, int outliersA) {
  // B pauses with the user, or when it enables no technique; not when only A has none.
  for (RenderLane* lane : {&a(), &b()})
    if (lane->running()) lane->sync(userPaused, targetSpp, lane == &a() && timingA, lane == &a() ? outliersA : 0);
}

bool Sides::poll(bool force) {
  bool arrived = false;
  for (RenderLane* lane : {&b(), &a()}) arrived = lane->poll(force) || arrived;
  return arrived;
}

void Sides::setReference(const Image* reference) {
  for (RenderLane* lane : {&a(), &b()})
    if (lane->running()) lane->view().setReference(reference);
}

void Sides::setScene(const std::shared_ptr<const Scene>& scene, const RenderSettings& settingsA,
                     const RenderSettings& settingsB) {
  for (RenderLane* lane : {&a(), &b()})
    if (lane->running()) lane->setScene(scene, lane == &a() ? settingsA : settingsB);
}

}  // namespace pathlab::ui
