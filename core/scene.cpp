#include "core/scene.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>

#include "core/error.h"
#include "core/hash.h"

namespace firmament {

std::string_view sceneSchemaText();  // generated from core/scene_schema.json

namespace {

using nlohmann::json;

std::string describe(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return std::string("boolean ") + (value.get<bool>() ? "true" : "false");
    case json::value_t::string:
      return "string " + value.dump();
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "number " + value.dump();
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    default:
      return "a value";
  }
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// "number in [0, 20000]", "integer ≥ 1", "one of \"auto\", \"fixed\"" ...
std::string allowed(const json& schema) {
  std::string type = schema.value("type", "");
  if (schema.contains("enum")) {
    std::string s = "one of ";
    bool first = true;
    for (const auto& e : schema["enum"]) {
      s += (first ? "" : ", ") + e.dump();
      first = false;
    }
    return s;
  }
  if (type == "number" || type == "integer") {
    std::string lo, hi;
    if (schema.contains("minimum")) lo = "[" + formatNumber(schema["minimum"].get<double>());
    if (schema.contains("exclusiveMinimum")) lo = "(" + formatNumber(schema["exclusiveMinimum"].get<double>());
    if (schema.contains("maximum")) hi = formatNumber(schema["maximum"].get<double>()) + "]";
    if (schema.contains("exclusiveMaximum")) hi = formatNumber(schema["exclusiveMaximum"].get<double>()) + ")";
    if (!lo.empty() && !hi.empty()) return type + " in " + lo + ", " + hi;
    if (!lo.empty()) return type + (lo[0] == '[' ? " >= " : " > ") + lo.substr(1);
    if (!hi.empty()) return type + (hi.back() == ']' ? " <= " : " < ") + hi.substr(0, hi.size() - 1);
    return type;
  }
  if (type == "string" && schema.value("format", "") == "date-time")
    return "a UTC date-time string like \"2026-06-21T15:30:00Z\"";
  if (type == "object") return "an object";
  if (type == "array")
    return schema.contains("maxItems") ? "at most " + std::to_string(schema["maxItems"].get<size_t>()) + " items"
                                       : "an array";
  return type;
}

[[noreturn]] void fail(const std::string& source, const std::string& pointer, const std::string& found,
                       const std::string& allowedText) {
  throw InputError(source + ": " + (pointer.empty() ? "/" : pointer) + ": found " + found +
                   ", allowed: " + allowedText);
}

// ISO 8601 UTC: YYYY-MM-DDThh:mm:ss(.fff)?Z, with calendar-valid fields.
bool isUtcDateTime(const std::string& s) {
  int y, mo, d, h, mi;
  double sec;
  char z = 0;
  int consumed = 0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%c%n", &y, &mo, &d, &h, &mi, &sec, &z, &consumed) != 7)
    return false;
  if (z != 'Z' || size_t(consumed) != s.size() || s.size() < 20 || s[4] != '-' || s[7] != '-' || s[13] != ':' ||
      s[16] != ':')
    return false;
  static const int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  if (mo < 1 || mo > 12 || d < 1 || d > kDays[mo - 1] || (mo == 2 && d == 29 && !leap)) return false;
  return h >= 0 && h < 24 && mi >= 0 && mi < 60 && sec >= 0.0 && sec < 61.0;
}

void validateNode(json& value, const json& schema, const std::string& pointer, const std::string& source) {
  const std::string type = schema.value("type", "");
  if (type == "object") {
    if (!value.is_object()) fail(source, pointer, describe(value), "an object");
    const json& properties = schema.contains("properties") ? schema["properties"] : json::object();
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (!properties.contains(it.key())) {
        // A key of an option the project measured and removed: say so and where the finding is kept.
        if (schema.contains("x-removed") && schema["x-removed"].contains(it.key()))
          fail(source, pointer + "/" + it.key(), "the removed key \"" + it.key() + "\"",
               "nothing: it was removed, " + schema["x-removed"][it.key()].get<std::string>());
        std::string keys;
        for (auto p = properties.begin(); p != properties.end(); ++p) keys += (keys.empty() ? "" : ", ") + p.key();
        fail(source, pointer + "/" + it.key(), "an unknown key \"" + it.key() + "\"",
             keys.empty() ? "no keys here" : "the keys " + keys);
      }
    }
    for (auto p = properties.begin(); p != properties.end(); ++p) {
      const json& child = p.value();
      const std::string childPointer = pointer + "/" + p.key();
      if (!value.contains(p.key())) {
        if (child.value("x-optional-section", false)) continue;  // absent = not simulated
        if (child.contains("default")) {
          value[p.key()] = child["default"];
        } else if (child.value("type", "") == "object") {
          value[p.key()] = json::object();
        } else {
          fail(source, childPointer, "nothing", allowed(child) + " (required)");
        }
      }
      validateNode(value[p.key()], child, childPointer, source);
    }
    return;
  }
  if (type == "array") {
    if (!value.is_array()) fail(source, pointer, describe(value), "an array");
    if (schema.contains("maxItems") && value.size() > schema["maxItems"].get<size_t>())
      fail(source, pointer, std::to_string(value.size()) + " items",
           "at most " + std::to_string(schema["maxItems"].get<size_t>()) + " items");
    if (schema.contains("minItems") && value.size() < schema["minItems"].get<size_t>())
      fail(source, pointer, std::to_string(value.size()) + " items",
           "at least " + std::to_string(schema["minItems"].get<size_t>()) + " items");
    if (schema.contains("items"))
      for (size_t i = 0; i < value.size(); ++i)
        validateNode(value[i], schema["items"], pointer + "/" + std::to_string(i), source);
    return;
  }
  if (type == "number" || type == "integer") {
    if (!value.is_number()) fail(source, pointer, describe(value), allowed(schema));
    double v = value.get<double>();
    if (!std::isfinite(v)) fail(source, pointer, describe(value), allowed(schema));
    if (type == "integer" && (value.is_number_float() && v != std::floor(v)))
      fail(source, pointer, describe(value), allowed(schema));
    bool ok = true;
    if (schema.contains("minimum") && v < schema["minimum"].get<double>()) ok = false;
    if (schema.contains("maximum") && v > schema["maximum"].get<double>()) ok = false;
    if (schema.contains("exclusiveMinimum") && v <= schema["exclusiveMinimum"].get<double>()) ok = false;
    if (schema.contains("exclusiveMaximum") && v >= schema["exclusiveMaximum"].get<double>()) ok = false;
    if (!ok) fail(source, pointer, describe(value), allowed(schema));
    // Canonical storage, so the scene hash does not depend on how a number was spelled.
    if (type == "integer")
      value = static_cast<int64_t>(v);
    else
      value = v;
    return;
  }
  if (type == "string") {
    if (!value.is_string()) fail(source, pointer, describe(value), allowed(schema));
    if (schema.contains("enum")) {
      bool found = false;
      for (const auto& e : schema["enum"]) found = found || e == value;
      if (!found) fail(source, pointer, describe(value), allowed(schema));
    }
    if (schema.value("format", "") == "date-time" && !isUtcDateTime(value.get<std::string>()))
      fail(source, pointer, describe(value), allowed(schema));
    return;
  }
  if (type == "boolean") {
    if (!value.is_boolean()) fail(source, pointer, describe(value), "true or false");
    return;
  }
  throw std::logic_error("scene schema: unsupported type '" + type + "' at " + pointer);
}

// "line 3, column 7" for a byte offset into text.
std::string lineColumn(std::string_view text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

const json& fieldAt(const json& root, const std::string& pointer) {
  json::json_pointer p(pointer);
  if (!root.contains(p)) throw std::logic_error("scene has no field " + pointer);
  return root.at(p);
}

}  // namespace

void applyOverride(json& document, const std::string& override) {
  auto eq = override.find('=');
  if (override.empty() || override[0] != '/' || eq == std::string::npos || eq == 1)
    throw InputError("--set '" + override + "': expected /json/pointer=value, e.g. --set /camera/fov_deg=60");
  std::string pointer = override.substr(0, eq);
  std::string text = override.substr(eq + 1);
  json value = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;  // a bare word is a string
  try {
    json::json_pointer p(pointer);
    if (!document.is_object()) document = json::object();
    document[p] = value;
  } catch (const json::exception& e) {
    throw InputError("--set '" + override + "': cannot set " + pointer + " (" + e.what() + ")");
  }
}

void validateScene(json& document, const std::string& source) { validateNode(document, sceneSchema(), "", source); }

const json& sceneSchema() {
  static const json schema = json::parse(sceneSchemaText());
  return schema;
}

Scene Scene::parse(std::string_view text, const std::string& source, const std::vector<std::string>& overrides) {
  bool blank = true;
  for (char c : text) blank = blank && std::isspace(static_cast<unsigned char>(c));
  if (blank) throw InputError(source + ": the file is empty; expected a JSON object (see docs/scene.md)");
  json document;
  try {
    document = json::parse(text);
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    // nlohmann's message: "[json.exception.parse_error.101] parse error at line 1, column 2: ..."
    auto colon = what.find(": ", what.find("parse error"));
    std::string detail = colon == std::string::npos ? what : what.substr(colon + 2);
    throw InputError(source + ": malformed JSON at " + lineColumn(text, e.byte > 0 ? e.byte - 1 : 0) + ": " + detail);
  }
  for (const auto& o : overrides) applyOverride(document, o);
  validateScene(document, source);
  return Scene(std::move(document), source);
}

Scene Scene::load(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw InputError(file.string() + ": no such scene file");
  if (std::filesystem::is_directory(file, ec))
    throw InputError(file.string() + ": is a folder, expected a scene file (.json)");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot read the scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(file.string() + ": error while reading the scene file");
  return parse(buffer.str(), file.string(), overrides);
}

double Scene::number(const std::string& pointer) const { return fieldAt(root_, pointer).get<double>(); }
int64_t Scene::integer(const std::string& pointer) const { return fieldAt(root_, pointer).get<int64_t>(); }
std::string Scene::string(const std::string& pointer) const { return fieldAt(root_, pointer).get<std::string>(); }
bool Scene::boolean(const std::string& pointer) const { return fieldAt(root_, pointer).get<bool>(); }
const json& Scene::at(const std::string& pointer) const { return fieldAt(root_, pointer); }

std::string Scene::hash() const {
  // FNV-1a over the canonical dump (nlohmann sorts object keys), so equal scenes hash equal.
  return hex16(fnv1a(root_.dump()));
}

namespace {
// One Markdown section per object: a table of its plain fields, then its nested objects.
void objectSection(const json& schema, const std::string& pointer, std::string& out) {
  out += "\n### `" + pointer + "`" + (schema.value("x-optional-section", false) ? " (optional section)" : "") + "\n\n" +
         schema.value("description", "") + "\n\n";
  out += "| field | type and allowed values | default | meaning |\n| --- | --- | --- | --- |\n";
  std::vector<std::pair<std::string, const json*>> nested;
  for (auto q = schema["properties"].begin(); q != schema["properties"].end(); ++q) {
    const json& leaf = q.value();
    std::string type = leaf.value("type", "");
    if (type == "object") {
      out += "| `" + q.key() + "` | object, see `" + pointer + "/" + q.key() + "` | | " +
             leaf.value("description", "") + " |\n";
      nested.emplace_back(pointer + "/" + q.key(), &leaf);
    } else if (type == "array" && leaf.contains("items") && leaf["items"].value("type", "") == "object") {
      out += "| `" + q.key() + "` | array (" + allowed(leaf) + ") of objects, see `" + pointer + "/" + q.key() +
             "/N` | `" + leaf.value("default", json::array()).dump() + "` | " + leaf.value("description", "") + " |\n";
      nested.emplace_back(pointer + "/" + q.key() + "/N", &leaf["items"]);
    } else {
      out += "| `" + q.key() + "` | " + allowed(leaf) + " | " +
             (leaf.contains("default")                  ? "`" + leaf["default"].dump() + "`"
              : leaf.value("x-optional-section", false) ? "optional"
                                                        : "required") +
             " | " + leaf.value("description", "") + " |\n";
    }
  }
  if (schema.contains("x-removed")) {
    out += "\nRemoved keys (measured, not adopted; a scene that sets one is an error naming its decision record):";
    std::string sep = " ";
    for (auto r = schema["x-removed"].begin(); r != schema["x-removed"].end(); ++r, sep = ", ")
      out += sep + "`" + r.key() + "`";
    out += ".\n";
  }
  for (const auto& [p, child] : nested) objectSection(*child, p, out);
}
}  // namespace

std::string sceneSchemaMarkdown() {
  const json& schema = sceneSchema();
  std::string out =
      "# Scene files\n\n"
      "<!-- Generated by `firmament scene-doc` from core/scene_schema.json; a test checks it is current. -->\n\n"
      "A scene is a JSON object. " +
      schema.value("description", "") +
      "\n\nEvery field has a default; a section marked *optional* is left out to leave that part of the sky "
      "out (no `clouds` → a clear sky, and no cloud pass runs). An unknown key, a wrong type or an out-of-range "
      "value is an error that names the file, the JSON pointer, what was found and what is allowed (exit code 2). "
      "Any field can be overridden from the command line with `--set /json/pointer=value` (the value is read "
      "as JSON when it parses, else as a string), e.g. `--set /camera/fov_deg=60 --set /camera/projection=fisheye`.\n\n"
      "Units: metres, seconds, degrees at this boundary (radians inside the code).\n";
  for (auto p = schema["properties"].begin(); p != schema["properties"].end(); ++p)
    objectSection(p.value(), "/" + p.key(), out);
  return out;
}

std::string clearSkyDefaultSceneText() {
  nlohmann::json document = nlohmann::json::parse(defaultSceneText());
  for (const char* section : {"terrain", "clouds", "weather"}) document.erase(section);
  return document.dump(2);
}

}  // namespace firmament
