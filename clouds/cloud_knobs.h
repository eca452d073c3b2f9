#pragma once
// The cloud march's knobs as data, from the one table shaders/clouds/cloud_march_knobs.def: each knob's
// identifier, type, default, range, scene path and one-line doc, for the docs (docs/clouds/knobs.md,
// `firmament cloud-knobs`), the bench and hosts that set knobs by name (CloudOverrides::set).
#include <string>
#include <vector>

namespace firmament {

struct CloudKnob {
  const char* name;   // the CloudMarchSettings field, e.g. "lightSteps"
  std::string id;     // its identifier, snake_case: "light_steps"
  const char* type;   // "int", "double", "bool" or "AerialPerspective"
  std::string value;  // the default as text: "6", "0.01", "true", "volume"
  double min, max;    // the allowed range (bool 0-1; an enum its values' order)
  const char* scene;  // the scene file's JSON pointer, "" where code alone sets it
  const char* doc;    // one line
};

// Every row of the table, in its order.
const std::vector<CloudKnob>& cloudMarchKnobs();

// docs/clouds/knobs.md: a Markdown table of the knobs (a test checks the file is current).
std::string cloudMarchKnobsMarkdown();

// The values a knob allows, as text: "integer in [1, 256]", "true, false", "volume, march, off".
std::string cloudKnobAllowed(const CloudKnob& knob);

// "lightSteps" -> "light_steps"; "maxDistance_m" -> "max_distance_m".
std::string cloudKnobIdentifier(const std::string& name);

}  // namespace firmament
