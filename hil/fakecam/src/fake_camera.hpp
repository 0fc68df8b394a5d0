// An Aravis GigE Vision fake camera (ArvGvFakeCamera) that answers the control channel (GVCP:
// discovery by address, registers, GenICam XML, heartbeat) while syncap-fakecam sends the stream
// (GVSP) itself, one frame per trigger. See genicam_xml.hpp for why Aravis' own streaming thread
// stays silent.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "gvsp.hpp"
#include "options.hpp"

namespace syncap::fakecam {

struct Region {
  std::uint32_t x = 0;
  std::uint32_t y = 0;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

class FakeCamera {
 public:
  // Serves on address (an IPv4 address of an interface in this network namespace) with a sensor
  // of width x height Mono8 pixels; the region starts as the whole sensor. Frames go out no
  // faster than a link of link_mbps Mbit/s would carry them (0: as fast as the sockets take
  // them). Throws std::runtime_error naming the address when the camera cannot serve there.
  FakeCamera(const std::string& address, const std::string& serial, int width, int height,
             TriggerSpec::Kind trigger, std::uint32_t link_mbps);
  ~FakeCamera();
  FakeCamera(const FakeCamera&) = delete;
  FakeCamera& operator=(const FakeCamera&) = delete;

  // A client holds the control channel and has started acquisition.
  bool is_acquiring() const;
  // The region of interest the client has set (OffsetX/Y, Width, Height).
  Region region() const;
  // The stream channel's packet size (GevSCPSPacketSize).
  std::uint32_t packet_size() const;
  // True once per TriggerSoftware command the client has executed since the last call.
  bool take_software_trigger();
  // Sends the frame's packets to the stream channel's destination; false when the client has set
  // none or a packet could not be sent.
  bool send_frame(const GvspImage& image);

 private:
  struct Arv;
  std::unique_ptr<Arv> arv_;
  int socket_ = -1;
  std::uint32_t link_mbps_ = 0;
};

}  // namespace syncap::fakecam
