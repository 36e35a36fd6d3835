#include "bodyrec/io/imglab_xml.h"

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "bodyrec/core/error.h"
#include "bodyrec/io/xml_document.h"

namespace fs = std::filesystem;

namespace bodyrec {

namespace {

ImglabDataset imglab_from_document(const pugi::xml_document& doc, const std::string& path) {
  const pugi::xml_node root = doc.child("dataset");
  if (!root) throw InputError(path + ": not an imglab dataset (no <dataset> root element)");
  ImglabDataset dataset;
  dataset.name = root.child_value("name");
  dataset.comment = root.child_value("comment");
  int image_index = 0;
  for (const pugi::xml_node image : root.child("images").children("image")) {
    ImglabImage out;
    out.file = image.attribute("file").value();
    if (out.file.empty())
      throw InputError(path + ": image " + std::to_string(image_index) + ": missing attribute 'file'");
    const std::string image_where = path + ": image " + out.file;
    int box_index = 0;
    for (const pugi::xml_node box : image.children("box")) {
      const std::string where = image_where + ": box " + std::to_string(box_index++);
      ImglabBox b;
      b.box = Box(required_number(box, "left", where), required_number(box, "top", where),
                  required_number(box, "width", where), required_number(box, "height", where));
      if (b.box.width < 0 || b.box.height < 0) throw InputError(where + ": negative width or height");
      b.ignore = box.attribute("ignore").as_int(0) != 0;
      b.label = box.child_value("label");
      for (const pugi::xml_node part : box.children("part")) {
        ImglabPart p;
        p.name = part.attribute("name").value();
        if (p.name.empty()) throw InputError(where + ": <part> without attribute 'name'");
        const std::string part_where = where + ": part " + p.name;
        p.point = cv::Point2d(required_number(part, "x", part_where), required_number(part, "y", part_where));
        b.parts.push_back(p);
      }
      out.boxes.push_back(std::move(b));
    }
    dataset.images.push_back(std::move(out));
    ++image_index;
  }
  return dataset;
}

}  // namespace

ImglabDataset read_imglab(const std::string& path) { return imglab_from_document(load_xml_file(path), path); }

ImglabDataset parse_imglab(const std::string& text, const std::string& name) {
  return imglab_from_document(parse_xml_text(text, name), name);
}

void write_imglab(const ImglabDataset& dataset, const std::string& path) {
  pugi::xml_document doc;
  auto decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  pugi::xml_node root = doc.append_child("dataset");
  root.append_child("name").text() = dataset.name.c_str();
  root.append_child("comment").text() = dataset.comment.c_str();
  pugi::xml_node images = root.append_child("images");
  for (const auto& image : dataset.images) {
    pugi::xml_node img = images.append_child("image");
    img.append_attribute("file") = image.file.c_str();
    for (const auto& b : image.boxes) {
      pugi::xml_node box = img.append_child("box");
      // dlib stores integer rectangles; round so that reading back gives the same box.
      box.append_attribute("top") = static_cast<long long>(std::lround(b.box.y));
      box.append_attribute("left") = static_cast<long long>(std::lround(b.box.x));
      box.append_attribute("width") = static_cast<long long>(std::lround(b.box.width));
      box.append_attribute("height") = static_cast<long long>(std::lround(b.box.height));
      if (b.ignore) box.append_attribute("ignore") = 1;
      if (!b.label.empty()) box.append_child("label").text() = b.label.c_str();
      for (const auto& p : b.parts) {
        pugi::xml_node part = box.append_child("part");
        part.append_attribute("name") = p.name.c_str();
        part.append_attribute("x") = static_cast<long long>(std::lround(p.point.x));
        part.append_attribute("y") = static_cast<long long>(std::lround(p.point.y));
      }
    }
  }
  if (!doc.save_file(path.c_str(), "  ", pugi::format_default, pugi::encoding_utf8))
    throw ProcessingError("cannot write " + path);
}

std::string resolve_image_path(const std::string& xml_path, const std::string& image_file) {
  const fs::path file(image_file);
  if (file.is_absolute()) return image_file;
  return (fs::path(xml_path).parent_path() / file).lexically_normal().string();
}

std::vector<cv::Point2d> ordered_parts(const ImglabBox& box, const std::string& where) {
  std::map<int, cv::Point2d> by_index;
  for (const auto& p : box.parts) {
    char* end = nullptr;
    const long index = std::strtol(p.name.c_str(), &end, 10);
    if (p.name.empty() || !std::isdigit(static_cast<unsigned char>(p.name[0])) || *end != '\0' || index > 100000)
      throw InputError(where + ": part name '" + p.name + "' is not a landmark number");
    if (!by_index.emplace(static_cast<int>(index), p.point).second)
      throw InputError(where + ": part " + p.name + " appears twice");
  }
  std::vector<cv::Point2d> points;
  for (const auto& [index, point] : by_index) {
    if (index != static_cast<int>(points.size()))
      throw InputError(where + ": landmark " + std::to_string(points.size()) + " is missing");
    points.push_back(point);
  }
  return points;
}

}  // namespace bodyrec
