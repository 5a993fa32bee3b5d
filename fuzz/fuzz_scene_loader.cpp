// libFuzzer target: scene JSON text -> a World (reading, validation and building of every object
// kind, without stepping). Refusing the input (InputError) is the expected answer to nonsense;
// anything else that escapes — another exception, a crash, a leak, a hang, an allocation the
// memory limit should have stopped — is a finding. The memory limit is 16 MB, so a scene that
// asks for 10^9 vertices must be refused before it allocates, and scenes that are merely large
// (a tank of 250,000 wall samples takes 14 s to build under the sanitizers) are refused too
// instead of timing out.
#include <cstdint>
#include <string>

#include "moreau/errors.hpp"
#include "moreau/moreau.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  moreau::set_memory_limit(16e6);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    moreau::World::from_json(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const moreau::InputError&) {
  }
  return 0;
}
