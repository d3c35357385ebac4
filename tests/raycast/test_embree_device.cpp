// Embree errors reach mote code as mote::Error, thrown after the Embree call has returned: the
// error callback runs inside Embree's C API and must not throw through it.
#include <embree3/rtcore.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "embree_device.hpp"
#include "mote/core/error.hpp"

namespace mote {
namespace {

using ::testing::HasSubstr;

TEST(EmbreeDevice, AnErrorIsRecordedAndThrownByTheCheckAfterTheCall) {
  RTCScene scene = nullptr;
  // The callback used to throw from inside rtcSetSceneBuildQuality; now the call returns.
  EXPECT_NO_THROW({
    scene = rtcNewScene(detail::embree_device());
    // REFIT is a geometry build quality, not a scene's.
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_REFIT);
  });
  try {
    detail::check_embree("setting the build quality");
    ADD_FAILURE() << "no error reported for an invalid build quality";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("Embree: setting the build quality: "));
    EXPECT_THAT(e.what(), HasSubstr("invalid build quality"));  // Embree's own message
  }
  EXPECT_NO_THROW(detail::check_embree("nothing since")) << "the error was not cleared";
  if (scene != nullptr) rtcReleaseScene(scene);
}

TEST(EmbreeDevice, TheThreadCheckSeesTheCallbacksRecord) {
  RTCScene scene = rtcNewScene(detail::embree_device());
  EXPECT_NO_THROW(rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_REFIT));
  EXPECT_THROW(detail::check_embree_thread("setting the build quality"), Error);
  rtcReleaseScene(scene);
  EXPECT_NO_THROW(detail::check_embree("nothing since"));
}

}  // namespace
}  // namespace mote
