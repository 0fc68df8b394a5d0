// libFuzzer target: the LCM log reader of `syncap log` and the calibration's log input
// (io::LcmLogReader), on the input as a whole log file.
//
// Contract: the reader never throws and always ends; each event it returns is an intact record
// of the file, at an offset after the previous event's, and encodes (encode_log_record) to
// exactly the file's bytes there; the damage it reports lies inside the file, in file order.
#include <cstddef>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "io/lcm_log_reader.hpp"

namespace {

using syncap::fuzz::check;

void check_event(const syncap::io::LogEvent& event, const std::string& file) {
  const std::vector<uint8_t> record = syncap::io::encode_log_record(
      event.event_number, event.timestamp_us, event.channel, event.data);
  check(event.offset + record.size() <= file.size(), "an event extends past the end of the file");
  check(file.compare(event.offset, record.size(), std::string(record.begin(), record.end())) == 0,
        "an event differs from the file's bytes at its offset");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string file(reinterpret_cast<const char*>(data), size);
  std::istringstream in(file);
  std::vector<syncap::io::LogError> errors;
  std::vector<syncap::io::LogEvent> events;
  syncap::fuzz::decodes<syncap::fuzz::NothingThrown>("LcmLogReader", [&] {
    syncap::io::LcmLogReader reader(in);
    while (auto event = reader.next()) {
      check(events.empty() || event->offset > events.back().offset, "events out of file order");
      check_event(*event, file);
      events.push_back(std::move(*event));
      check(events.size() <= size, "more events than bytes: the reader does not end");
      for (auto& error : reader.take_errors()) errors.push_back(std::move(error));
    }
    for (auto& error : reader.take_errors()) errors.push_back(std::move(error));
  });
  for (std::size_t i = 0; i < errors.size(); ++i) {
    check(errors[i].offset < size || (size == 0 && errors[i].offset == 0),
          "damage reported outside the file");
    check(i == 0 || errors[i].offset >= errors[i - 1].offset, "damage reported out of order");
    check(!errors[i].message.empty(), "damage reported without a message");
  }
  return 0;
}
