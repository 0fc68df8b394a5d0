// The GenICam XML syncap-fakecam serves, patched from this Aravis' stock fake-camera XML (no
// network: the XML comes from an ArvFakeCamera object).
#include "genicam_xml.hpp"

#include <arv.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace {

using namespace syncap::fakecam;

std::string stock_xml() {
  ArvFakeCamera* camera = arv_fake_camera_new("xml-test");
  size_t size = 0;
  const char* xml = arv_fake_camera_get_genicam_xml(camera, &size);
  std::string copy(xml, size);
  g_object_unref(camera);
  return copy;
}

std::string element(const std::string& xml, const std::string& start_tag, const std::string& end) {
  const std::size_t begin = xml.find(start_tag);
  if (begin == std::string::npos) return {};
  return xml.substr(begin, xml.find(end, begin) + end.size() - begin);
}

TEST(GenicamXml, OffersMono8Only) {
  const std::string xml = patch_genicam_xml(stock_xml());
  const std::string pixel_format =
      element(xml, "<Enumeration Name=\"PixelFormat\"", "</Enumeration>");
  EXPECT_NE(pixel_format.find("\"Mono8\""), std::string::npos);
  EXPECT_EQ(pixel_format.find("Mono16"), std::string::npos);
  EXPECT_EQ(pixel_format.find("Bayer"), std::string::npos);
  EXPECT_NE(pixel_format.find("<pValue>PixelFormatRegister</pValue>"), std::string::npos);
}

TEST(GenicamXml, MovesTheTriggerRegistersToTheShadowOnes) {
  const std::string xml = patch_genicam_xml(stock_xml());
  EXPECT_NE(element(xml, "<IntReg Name=\"TriggerModeRegister\"", "</IntReg>")
                .find("<Address>0x9300</Address>"),
            std::string::npos);
  EXPECT_NE(element(xml, "<IntReg Name=\"TriggerSourceRegister\"", "</IntReg>")
                .find("<Address>0x9304</Address>"),
            std::string::npos);
  EXPECT_NE(element(xml, "<IntReg Name=\"TriggerSoftwareCommandRegister\"", "</IntReg>")
                .find("<Address>0x930c</Address>"),
            std::string::npos);
  // Everything else stays where Aravis' fake camera keeps it.
  EXPECT_NE(element(xml, "<IntReg Name=\"WidthRegister\"", "</IntReg>").find("0x100"),
            std::string::npos);
}

TEST(GenicamXml, NamesWhatItCannotFind) {
  try {
    (void)patch_genicam_xml("<RegisterDescription/>");
    FAIL() << "no exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("PixelFormat"), std::string::npos) << error.what();
  }
}

}  // namespace
