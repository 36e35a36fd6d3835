#include "bodyrec/io/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"
#include "bodyrec/io/xml_document.h"

namespace bodyrec {
namespace {

void check_size(const LabelledBox& b, const std::string& where) {
  if (b.box.width < 0 || b.box.height < 0)
    throw InputError(where + ": negative box size (w=" + std::to_string(b.box.width) +
                     ", h=" + std::to_string(b.box.height) + ")");
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream s(line);
  // MOT files use commas; some tools write spaces or tabs. Accept either (runs of blanks are one separator).
  if (line.find(',') == std::string::npos) {
    while (s >> field) fields.push_back(field);
    return fields;
  }
  while (std::getline(s, field, ',')) {
    field.erase(0, field.find_first_not_of(" \t\r"));
    field.erase(field.find_last_not_of(" \t\r") + 1);
    fields.push_back(field);
  }
  return fields;
}

}  // namespace

std::map<int, std::vector<LabelledBox>> GroundTruth::by_frame() const {
  std::map<int, std::vector<LabelledBox>> frames;
  for (const auto& b : boxes) frames[b.frame].push_back(b);
  return frames;
}

static GroundTruth cvml_from_document(const pugi::xml_document& doc, const std::string& path) {
  const pugi::xml_node root = doc.child("dataset");
  if (!root) throw InputError(path + ": not CVML ground truth (no <dataset> root element)");
  GroundTruth gt;
  for (const pugi::xml_node frame : root.children("frame")) {
    const int number = required_int(frame, "number", path + ": <frame>");
    if (number < 0) throw InputError(path + ": frame " + std::to_string(number) + ": negative frame number");
    gt.frame_count = std::max(gt.frame_count, number + 1);
    const std::string frame_where = path + ": frame " + std::to_string(number);
    for (const pugi::xml_node object : frame.child("objectlist").children("object")) {
      const int id = required_int(object, "id", frame_where + ": <object>");
      const std::string where = frame_where + ": object " + std::to_string(id);
      const pugi::xml_node box = object.child("box");
      if (!box) throw InputError(where + ": missing <box>");
      LabelledBox b;
      b.frame = number;
      b.id = id;
      const double w = required_number(box, "w", where), h = required_number(box, "h", where);
      b.box = Box(required_number(box, "xc", where) - w / 2, required_number(box, "yc", where) - h / 2, w, h);
      check_size(b, where);
      gt.boxes.push_back(b);
    }
  }
  if (gt.frame_count == 0) throw InputError(path + ": no <frame> elements");
  return gt;
}

GroundTruth read_cvml(const std::string& path) { return cvml_from_document(load_xml_file(path), path); }

GroundTruth parse_cvml(const std::string& text, const std::string& name) {
  return cvml_from_document(parse_xml_text(text, name), name);
}

GroundTruth read_mot(const std::string& path, bool is_ground_truth) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path);
  return read_mot(in, path, is_ground_truth);
}

GroundTruth read_mot(std::istream& in, const std::string& path, bool is_ground_truth) {
  GroundTruth gt;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 byte-order mark
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = path + ": line " + std::to_string(line_number);
    const auto f = split_fields(line);
    if (f.size() < 6)
      throw InputError(where + ": expected at least 6 comma-separated fields (frame,id,x,y,w,h), got " +
                       std::to_string(f.size()));
    LabelledBox b;
    const double frame = parse_finite_field(f[0], where, "frame");
    if (frame < 1 || frame != std::floor(frame) || frame > 1e8)
      throw InputError(where + ": field 'frame' must be an integer >= 1 (MOTChallenge frames are 1-based), got '" +
                       f[0] + "'");
    b.frame = static_cast<int>(frame) - 1;
    const double id = parse_finite_field(f[1], where, "id");
    if (id != std::floor(id) || std::fabs(id) > 1e9)
      throw InputError(where + ": field 'id' must be an integer, got '" + f[1] + "'");
    b.id = static_cast<int>(id);
    b.box = Box(parse_finite_field(f[2], where, "x"), parse_finite_field(f[3], where, "y"), parse_finite_field(f[4], where, "w"),
                parse_finite_field(f[5], where, "h"));
    check_size(b, where);
    if (f.size() > 6) b.score = parse_finite_field(f[6], where, "conf");
    if (is_ground_truth) {
      const bool zero_conf = f.size() > 6 && b.score == 0;
      const double object_class = f.size() > 7 ? parse_finite_field(f[7], where, "class") : 1;
      const bool other_class = object_class != 1 && object_class != -1;
      b.ignore = zero_conf || other_class;
      b.score = 1.0;
    }
    gt.frame_count = std::max(gt.frame_count, b.frame + 1);
    gt.boxes.push_back(b);
  }
  if (in.bad()) throw InputError("error while reading " + path);
  return gt;
}

GroundTruth read_ground_truth(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError("ground truth not found: " + path);
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
  if (ext == ".xml") return read_cvml(path);
  GroundTruth gt = read_mot(path, true);
  // Nothing to score against: an empty or blank gt.txt is a mistake, not a sequence without people.
  if (gt.boxes.empty()) throw InputError(path + ": no ground-truth rows (empty file)");
  return gt;
}

}  // namespace bodyrec
