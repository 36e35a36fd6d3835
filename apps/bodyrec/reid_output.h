// The JSON of one re-identification frame and event, shared by `reid` and `eval reid-stream` (the
// schema `bodyrec report` reads: docs in README, "Online re-identification").
#pragma once

#include <chrono>
#include <cmath>

#include <nlohmann/json.hpp>

#include "reid_job.h"

namespace bodyrec::cli {

inline nlohmann::json reid_event_json(const ReidEvent& e) {
  return {{"kind", reid_event_name(e.kind)},
          {"user", e.user},
          {"track", e.track},
          {"view", e.view ? nlohmann::json(view_name(*e.view)) : nlohmann::json()},
          {"score", e.score ? nlohmann::json(std::round(*e.score * 1e4) / 1e4) : nlohmann::json()}};
}

// Seconds since the Unix epoch, to the millisecond.
inline double unix_seconds(std::chrono::system_clock::time_point t) {
  return std::round(std::chrono::duration<double>(t.time_since_epoch()).count() * 1000) / 1000;
}

// {"frame","time","bodies":[{"track","user","view","box"}],"events":[...],"ms":{"orient","scan","reid"}}
// (colour: "detect" for "orient"); live runs add "arrival" (when the frame came) and "wall" (when its
// decisions were made, just before the line was written and flushed), both Unix seconds, and "dropped"
// (frames dropped so far). The line after the last frame holds finish()'s events with "end": true.
inline nlohmann::json reid_frame_json(const ReidFrame& f, int end_frame, double end_time) {
  nlohmann::json bodies = nlohmann::json::array(), events = nlohmann::json::array();
  for (const ReidIdentity& id : f.step.identities)
    bodies.push_back({{"track", id.track},
                      {"user", id.user ? nlohmann::json(*id.user) : nlohmann::json()},
                      {"view", id.view ? nlohmann::json(view_name(*id.view)) : nlohmann::json()},
                      {"box", {id.box.x, id.box.y, id.box.width, id.box.height}}});
  for (const ReidEvent& e : f.step.events) events.push_back(reid_event_json(e));
  const auto r = [](double ms) { return std::round(ms * 1000) / 1000; };
  if (f.frame.index < 0)
    return {{"frame", end_frame}, {"time", end_time}, {"bodies", bodies}, {"events", events}, {"end", true}};
  nlohmann::json j = {{"frame", f.frame.index},
                      {"time", f.frame.time_s},
                      {"bodies", bodies},
                      {"events", events},
                      {"ms", {{f.colour ? "detect" : "orient", r(f.ms_orient)}, {"scan", r(f.ms_scan)}, {"reid", r(f.ms_reid)}}}};
  if (f.live && f.arrival) {
    j["arrival"] = unix_seconds(f.arrival->wall);
    j["wall"] = unix_seconds(std::chrono::system_clock::now());
    j["dropped"] = f.arrival->dropped;
  }
  return j;
}

}  // namespace bodyrec::cli
