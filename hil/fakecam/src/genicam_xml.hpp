// The GenICam description syncap-fakecam serves: Aravis' stock fake-camera XML with two changes.
//  - PixelFormat offers Mono8 only.
//  - TriggerMode, TriggerSource and TriggerSoftware live in shadow registers. Aravis' fake camera
//    thread streams by itself whenever its own trigger registers say free-running or software
//    trigger; syncap-fakecam sends the frames itself, so it keeps those registers at "hardware
//    trigger on Line0", where the thread stays silent, and reads the client's settings and
//    TriggerSoftware commands from the shadow registers instead.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace syncap::fakecam {

// Aravis' own registers (arvfakecamera.h), moved to the shadow ones below.
inline constexpr std::uint32_t kStockTriggerModeRegister = 0x300;
inline constexpr std::uint32_t kStockTriggerSourceRegister = 0x304;
inline constexpr std::uint32_t kStockTriggerSoftwareRegister = 0x30c;
// In the fake camera's register memory (0x10000 bytes), far from everything Aravis uses.
inline constexpr std::uint32_t kShadowTriggerModeRegister = 0x9300;
inline constexpr std::uint32_t kShadowTriggerSourceRegister = 0x9304;
inline constexpr std::uint32_t kShadowTriggerSoftwareRegister = 0x930c;
// TriggerSource values of the stock XML.
inline constexpr std::uint32_t kTriggerSourceLine0 = 0;
inline constexpr std::uint32_t kTriggerSourceSoftware = 1;

// The patched XML; throws std::runtime_error naming the node it could not find or change (the
// stock XML of another Aravis version).
std::string patch_genicam_xml(std::string_view stock);

}  // namespace syncap::fakecam
