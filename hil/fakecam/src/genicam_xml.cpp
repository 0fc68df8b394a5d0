#include "genicam_xml.hpp"

#include <cstdio>
#include <stdexcept>

namespace syncap::fakecam {
namespace {

constexpr std::string_view kMono8Only =
    "<Enumeration Name=\"PixelFormat\" NameSpace=\"Standard\">\n"
    "\t\t<DisplayName>Pixel format</DisplayName>\n"
    "\t\t<EnumEntry Name=\"Mono8\" NameSpace=\"Standard\">\n"
    "\t\t\t<Value>17301505</Value>\n"
    "\t\t</EnumEntry>\n"
    "\t\t<pValue>PixelFormatRegister</pValue>\n"
    "\t</Enumeration>";

std::string hex(std::uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%x", value);
  return text;
}

// The [begin, end) of the element that starts with `start_tag` and ends with `end_tag`.
std::pair<std::size_t, std::size_t> find_element(const std::string& xml, std::string_view start_tag,
                                                 std::string_view end_tag) {
  const std::size_t begin = xml.find(start_tag);
  const std::size_t end = begin == std::string::npos ? begin : xml.find(end_tag, begin);
  if (end == std::string::npos) {
    throw std::runtime_error("Aravis' fake-camera GenICam XML has no " + std::string(start_tag) +
                             " element; syncap-fakecam knows the XML of Aravis 0.8");
  }
  return {begin, end + end_tag.size()};
}

void move_register(std::string& xml, std::string_view name, std::uint32_t from, std::uint32_t to) {
  const std::string start_tag = "<IntReg Name=\"" + std::string(name) + "\"";
  const auto [begin, end] = find_element(xml, start_tag, "</IntReg>");
  const std::string old_address = "<Address>" + hex(from) + "</Address>";
  const std::size_t at = xml.find(old_address, begin);
  if (at == std::string::npos || at > end) {
    throw std::runtime_error("Aravis' fake-camera GenICam XML: " + std::string(name) +
                             " is not at " + hex(from));
  }
  xml.replace(at, old_address.size(), "<Address>" + hex(to) + "</Address>");
}

}  // namespace

std::string patch_genicam_xml(std::string_view stock) {
  std::string xml(stock);
  const auto [begin, end] =
      find_element(xml, "<Enumeration Name=\"PixelFormat\"", "</Enumeration>");
  xml.replace(begin, end - begin, kMono8Only);
  move_register(xml, "TriggerModeRegister", kStockTriggerModeRegister, kShadowTriggerModeRegister);
  move_register(xml, "TriggerSourceRegister", kStockTriggerSourceRegister,
                kShadowTriggerSourceRegister);
  move_register(xml, "TriggerSoftwareCommandRegister", kStockTriggerSoftwareRegister,
                kShadowTriggerSoftwareRegister);
  return xml;
}

}  // namespace syncap::fakecam
