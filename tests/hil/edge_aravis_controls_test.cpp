// syncap-edge's Aravis source against Aravis' own GigE Vision fake camera, inside the private
// network namespace of hil/netns-run (opened by address: nothing is broadcast). Checks that the
// controls the host commands (exposure, gain) reach the camera's registers.
#include <gtest/gtest.h>

#include <arv.h>

#include "sensor/aravis_source.hpp"

namespace syncap::edge {
namespace {

constexpr const char* kCameraAddress = "127.0.0.2";

struct FakeCameraDeleter {
  void operator()(ArvGvFakeCamera* camera) const { g_object_unref(camera); }
};

class EdgeAravisControlsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fake_.reset(arv_gv_fake_camera_new(kCameraAddress, "SYNCAP-FAKE-02"));
    ASSERT_TRUE(arv_gv_fake_camera_is_running(fake_.get())) << "fake camera on " << kCameraAddress;
  }
  uint32_t read_register(uint64_t address) {
    uint32_t value = 0;
    ArvFakeCamera* camera = arv_gv_fake_camera_get_fake_camera(fake_.get());
    EXPECT_TRUE(arv_fake_camera_read_register(camera, address, &value));
    return value;
  }
  AravisOptions options() const {
    AravisOptions o;
    o.device_address = kCameraAddress;
    o.interface_address = "127.0.0.1";
    o.trigger_source = "Software";
    o.udp_socket = true;  // no CAP_NET_RAW needed in the test
    o.buffers = 4;
    return o;
  }
  std::unique_ptr<ArvGvFakeCamera, FakeCameraDeleter> fake_;
};

TEST_F(EdgeAravisControlsTest, ExposureAndGainAtOpenAndByCommandReachTheCamera) {
  AravisOptions o = options();
  o.exposure_us = 2000;
  o.gain_db = 2;
  AravisSource source(o, 0);
  EXPECT_EQ(read_register(ARV_FAKE_CAMERA_REGISTER_EXPOSURE_TIME_US), 2000u);
  EXPECT_EQ(read_register(ARV_FAKE_CAMERA_REGISTER_GAIN_RAW), 2u);
  source.set_exposure_us(4500);
  source.set_gain_db(5);
  EXPECT_EQ(read_register(ARV_FAKE_CAMERA_REGISTER_EXPOSURE_TIME_US), 4500u);
  EXPECT_EQ(read_register(ARV_FAKE_CAMERA_REGISTER_GAIN_RAW), 5u);
}

}  // namespace
}  // namespace syncap::edge
