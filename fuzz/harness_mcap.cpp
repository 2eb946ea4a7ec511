// fuzz_mcap: an MCAP file read as hba reads it. The container first (the
// summary or the scan of the data section, then every channel's messages
// read), then the recording (topics chosen, trajectory read, scans placed
// and loaded).
#include <cstdlib>
#include <set>
#include <string>

#include "harness.hpp"
#include "hba/core/error.hpp"
#include "hba/rec/recording.hpp"
#include "rec/message_store.hpp"

namespace hba::fuzz {
namespace {

template <typename Parse>
void rejectOnlyWithError(Parse parse) {
  try {
    parse();
  } catch (const Error&) {
    // The documented outcome for bad input.
  }
}

void readEveryMessage(const std::filesystem::path& input) {
  const std::unique_ptr<rec::MessageStore> store = rec::openMcap(input);
  std::size_t counted = 0;
  for (const rec::StoredChannel& channel : store->channels()) counted += channel.messages;
  std::set<std::string> topics;  // channels sharing a topic list their messages under it once
  for (const rec::StoredChannel& channel : store->channels()) topics.insert(channel.topic);
  std::size_t listed = 0;
  for (const std::string& topic : topics) {
    for (const rec::StoredMessage& message : store->messages(topic)) {
      ++listed;
      rejectOnlyWithError([&] { store->read(message); });
    }
  }
  if (listed != counted) std::abort();  // the channels' counts are the messages listed
}

}  // namespace

void feedMcap(const std::filesystem::path& input) {
  rejectOnlyWithError([&] { readEveryMessage(input); });
  rejectOnlyWithError([&] {
    const rec::Recording recording = rec::Recording::open(input);
    for (std::size_t i = 0; i < recording.size(); ++i) recording.loadScan(i);
  });
}

}  // namespace hba::fuzz
