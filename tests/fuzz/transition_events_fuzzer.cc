// libFuzzer target: ParseTransitionEvents must either return well-formed events or throw
// InputError. The events written back in their plainest form (TRIAL KIND [@FRAME] [tune])
// must parse to the same events.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/base/error.h"
#include "io/gait/split.h"
#include "prior/motion/transition_event.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<jgpm::TransitionEvent> events = jgpm::ParseTransitionEvents(text, "fuzz.txt");
    JGPM_CHECK(!events.empty());
    std::string written;
    for (const jgpm::TransitionEvent& e : events) {
      jgpm::TrialId id;
      JGPM_CHECK(jgpm::ParseTrialId(e.trial, &id));
      JGPM_CHECK(!e.frame_number || *e.frame_number >= 1);
      written += e.trial + " " + std::string(jgpm::TransitionKindName(e.kind));
      if (e.frame_number) written += " @" + std::to_string(*e.frame_number);
      if (e.tune) written += " tune";
      written += "\n";
    }
    const std::vector<jgpm::TransitionEvent> back = jgpm::ParseTransitionEvents(written, "back.txt");
    JGPM_CHECK(back.size() == events.size());
    for (size_t i = 0; i < events.size(); ++i) {
      JGPM_CHECK(back[i].trial == events[i].trial && back[i].kind == events[i].kind &&
                 back[i].frame_number == events[i].frame_number && back[i].tune == events[i].tune);
    }
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
