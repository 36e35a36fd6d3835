// Fuzz targets for every parser of outside input. Each function feeds `data` to one parser and accepts
// only bodyrec's typed errors (bodyrec::Error and subclasses); anything else escapes as a finding: another
// exception, a crash, a sanitizer report, a hang or too much memory. The same functions back the libFuzzer
// programs (fuzz_main.cc, clang, BODYREC_FUZZ=ON) and the GCC replay test (fuzz_replay_test.cc).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bodyrec::fuzz {

using Target = int (*)(const uint8_t* data, size_t size);

int fuzz_cvml(const uint8_t* data, size_t size);              // PETS/CVML ground-truth XML
int fuzz_mot(const uint8_t* data, size_t size);               // MOTChallenge text (gt and results)
int fuzz_imglab(const uint8_t* data, size_t size);            // dlib imglab XML (+ ordered parts)
int fuzz_roles_csv(const uint8_t* data, size_t size);         // roles CSV
int fuzz_homography(const uint8_t* data, size_t size);        // 3x3 homography text
int fuzz_tsai(const uint8_t* data, size_t size);              // PETS Tsai calibration XML
int fuzz_ntu_skeleton(const uint8_t* data, size_t size);      // NTU RGB+D .skeleton (+ camera fit)
int fuzz_pcd(const uint8_t* data, size_t size);               // PCD ascii/binary/binary_compressed (+ fit)
int fuzz_recording_meta(const uint8_t* data, size_t size);    // recording meta.json
int fuzz_recording_bodies(const uint8_t* data, size_t size);  // recording bodies/*.json and truth/*.json
int fuzz_obsmat(const uint8_t* data, size_t size);            // EWAP obsmat.txt (+ frame period)
int fuzz_groups(const uint8_t* data, size_t size);            // EWAP groups.txt
int fuzz_event_spool(const uint8_t* data, size_t size);       // the --events spool file (events/event_spool.h)
int fuzz_mqtt_uri(const uint8_t* data, size_t size);          // --events URI (one line) and credentials file

struct NamedTarget {
  const char* name;  // folder name under fuzz/corpus and fuzz/regressions
  Target function;
};
// Every target, for the replay test.
const std::vector<NamedTarget>& all_targets();

}  // namespace bodyrec::fuzz
